"""Options validation and the estimate's pose convention."""

from __future__ import annotations

import numpy as np
import pytest

from door_contract.vocabulary import DetectionMode, Side
from door_detection.errors import DetectionError
from door_detection.estimate import DetectedDoor
from door_detection.options import DetectionOptions


def test_defaults_follow_the_paper() -> None:
    options = DetectionOptions()
    assert options.min_pair_separation == 60.0            # Sec. III-A: 60 px
    assert (options.door_width_min, options.door_width_max) == (0.80, 1.00)   # 90 ± 10 cm
    assert options.plane_inlier_distance == 0.05           # 5 cm
    assert options.vote_frames == 10                       # the window of Sec. III-A
    assert options.vote_min_agreeing == 2                   # ours: confirms before the window is full


@pytest.mark.parametrize("field, value, words", [
    ("canny_low", 0, "canny_low = 0 is outside the allowed range [1, 1000]"),
    ("plane_inlier_distance", 0.0, "plane_inlier_distance = 0.0 is outside the allowed range (0, 0.5] m"),
    ("vote_frames", 2.5, "vote_frames must be an integer"),
    ("line_scale", True, "line_scale must be a number"),
    ("door_width_min", float("nan"), "door_width_min = nan is outside"),
    ("vote_min_agreeing", 0, "vote_min_agreeing = 0 is outside the allowed range [1, 100] frames"),
    ("vote_handle_confidence", 0.0, "vote_handle_confidence = 0.0 is outside the allowed range (0, 0.1] m"),
])
def test_bad_option_names_field_and_range(field, value, words) -> None:
    with pytest.raises(DetectionError, match=words.replace("(", r"\(").replace("[", r"\[")):
        DetectionOptions(**{field: value})


def test_ordered_pairs_are_checked() -> None:
    with pytest.raises(DetectionError, match="door_width_min = 1.1 must be below door_width_max"):
        DetectionOptions(door_width_min=1.1)
    with pytest.raises(DetectionError, match="canny_low"):
        DetectionOptions(canny_low=200, canny_high=100)


def _estimate(normal, up=(0.0, -1.0, 0.0)) -> DetectedDoor:
    return DetectedDoor(np.array([0.2, 0.3, 2.0]), np.array(normal), Side.LEFT, 0.9,
                        np.zeros((4, 3)), 1.0, DetectionMode.AUTOMATIC, 1, np.array(up))


def test_handle_pose_axes() -> None:
    pitched_normal = np.array([0.0, 0.3, -1.0]) / np.linalg.norm([0.0, 0.3, -1.0])
    pose = _estimate(pitched_normal).handle_pose()
    rotation = pose[:3, :3]
    assert np.allclose(rotation.T @ rotation, np.eye(3)) and np.isclose(np.linalg.det(rotation), 1.0)
    assert np.allclose(rotation[:, 0], pitched_normal)           # x: normal towards the camera
    assert rotation[1, 2] < -0.9                                 # z: up (−y optical)
    assert np.allclose(pose[:3, 3], [0.2, 0.3, 2.0])
    gravity_up = np.array([0.0, -0.8, 0.6])
    assert np.isclose(_estimate(pitched_normal).handle_pose(gravity_up)[:3, 2] @ pitched_normal, 0.0)


def test_estimate_validation_and_transform() -> None:
    with pytest.raises(DetectionError, match="unit"):
        _estimate((0.0, 0.0, -2.0))
    with pytest.raises(DetectionError, match="confidence"):
        DetectedDoor(np.zeros(3), np.array([0.0, 0.0, -1.0]), Side.LEFT, 0.9, np.zeros((4, 3)), 1.5,
                     DetectionMode.OPERATOR)
    estimate = _estimate((0.0, 0.0, -1.0))
    assert not estimate.handle_position.flags.writeable
    shift = np.eye(4)
    shift[:3, 3] = [1.0, 2.0, 3.0]
    moved = estimate.transformed(shift)
    assert np.allclose(moved.handle_position, [1.2, 2.3, 5.0]) and np.allclose(moved.normal, estimate.normal)
    assert Side.LEFT.other is Side.RIGHT and Side.RIGHT.sign == -1
