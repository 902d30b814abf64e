"""Bad input never crashes: a clear outcome (or, for options, DetectionError)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from door_contract.vocabulary import Side
from door_detection.automatic import detect_automatic
from door_detection.errors import DetectionError, InputError
from door_detection.estimate import DetectionOutcome
from door_detection.operator_aided import detect_from_scribble
from door_detection.options import DetectionOptions
from door_detection.preprocessing import validate_frame


def _both(rgb, depth, intrinsics, scribble):
    return (detect_automatic(rgb, depth, intrinsics),
            detect_from_scribble(rgb, depth, intrinsics, scribble, hinge_side=Side.LEFT))


def test_empty_image(straight_on) -> None:
    for result in _both(np.zeros((0, 0, 3), np.uint8), np.zeros((0, 0), np.float32),
                        straight_on.intrinsics, straight_on.scribble):
        assert result.outcome is DetectionOutcome.BAD_INPUT
        assert "empty" in result.reason or "registered" in result.reason


def test_depth_and_colour_sizes_differ(straight_on) -> None:
    half_depth = straight_on.depth[::2, ::2]
    for result in _both(straight_on.rgb, half_depth, straight_on.intrinsics, straight_on.scribble):
        assert result.outcome is DetectionOutcome.BAD_INPUT
        assert "registered" in result.reason and "1024×544" in result.reason


def test_all_invalid_depth(straight_on) -> None:
    for depth in (np.full_like(straight_on.depth, np.nan), np.zeros_like(straight_on.depth),
                  np.full_like(straight_on.depth, np.inf)):
        for result in _both(straight_on.rgb, depth, straight_on.intrinsics, straight_on.scribble):
            assert result.outcome is DetectionOutcome.NO_VALID_DEPTH
            assert not result.ok and result.estimate is None


def test_intrinsics_for_another_image_size(straight_on) -> None:
    other = replace(straight_on.intrinsics, width=640, height=480)
    for result in _both(straight_on.rgb, straight_on.depth, other, straight_on.scribble):
        assert result.outcome is DetectionOutcome.BAD_INPUT
        assert "640×480" in result.reason


def test_non_finite_or_negative_focal_length(straight_on) -> None:
    for bad in (replace(straight_on.intrinsics, fx=float("nan")), replace(straight_on.intrinsics, fy=-1.0)):
        for result in _both(straight_on.rgb, straight_on.depth, bad, straight_on.scribble):
            assert result.outcome is DetectionOutcome.BAD_INPUT


def test_wrong_dtypes_and_shapes(straight_on) -> None:
    as_float = straight_on.rgb.astype(np.float32)
    assert detect_automatic(as_float, straight_on.depth, straight_on.intrinsics).outcome is \
        DetectionOutcome.BAD_INPUT
    four_channels = np.zeros((*straight_on.rgb.shape[:2], 4), np.uint8)
    assert detect_automatic(four_channels, straight_on.depth, straight_on.intrinsics).outcome is \
        DetectionOutcome.BAD_INPUT
    millimetres = (straight_on.depth * 1000).astype(np.uint16)
    assert detect_automatic(straight_on.rgb, millimetres, straight_on.intrinsics).outcome is \
        DetectionOutcome.BAD_INPUT


@pytest.mark.parametrize("scribble", [
    np.array([[2000.0, 100.0], [2010.0, 100.0], [2010.0, 110.0]]),   # right of the image
    np.array([[-5.0, 10.0], [5.0, 10.0], [5.0, 20.0]]),              # partly left of it
    np.array([[100.0, 600.0]]),                                     # below it
])
def test_scribble_outside_the_image(straight_on, scribble) -> None:
    result = detect_from_scribble(straight_on.rgb, straight_on.depth, straight_on.intrinsics, scribble)
    assert result.outcome is DetectionOutcome.BAD_INPUT
    assert "outside" in result.reason


@pytest.mark.parametrize("scribble", [np.zeros((0, 2)), np.array([[np.nan, 3.0]]), np.zeros((3, 3))])
def test_malformed_scribble(straight_on, scribble) -> None:
    result = detect_from_scribble(straight_on.rgb, straight_on.depth, straight_on.intrinsics, scribble)
    assert result.outcome is DetectionOutcome.BAD_INPUT


def test_scribble_on_a_region_without_depth(straight_on) -> None:
    depth = straight_on.depth.copy()
    depth[150:450, 450:800] = np.nan
    result = detect_from_scribble(straight_on.rgb, depth, straight_on.intrinsics, straight_on.scribble,
                                  hinge_side=Side.LEFT)
    assert result.outcome is DetectionOutcome.NO_VALID_DEPTH


def test_bad_up_vector(straight_on) -> None:
    result = detect_from_scribble(straight_on.rgb, straight_on.depth, straight_on.intrinsics,
                                  straight_on.scribble, up=np.zeros(3))
    assert result.outcome is DetectionOutcome.BAD_INPUT


def test_validate_frame_raises_input_error(straight_on) -> None:
    with pytest.raises(InputError):
        validate_frame(straight_on.rgb, straight_on.depth[:10], straight_on.intrinsics, DetectionOptions())
    assert issubclass(InputError, DetectionError) and not issubclass(DetectionError, ValueError)


def test_mono_image_is_accepted(straight_on) -> None:
    mono = straight_on.rgb.mean(axis=2).astype(np.uint8)
    result = detect_automatic(mono, straight_on.depth, straight_on.intrinsics)
    assert result.outcome is not DetectionOutcome.BAD_INPUT
