"""The detector's frames without ROS: streams matched by stamp within the tolerance, old
incomplete frames dropped saying which stream they lacked; the debug overlay."""

from __future__ import annotations

import numpy as np
import pytest

from door_contract.converters.camera_info import CameraIntrinsics
from door_contract.vocabulary import DetectionMode, Side
from door_detection.errors import DetectionError
from door_detection.estimate import DetectedDoor
from door_detection.frame_sync import STREAMS, FrameSync
from door_detection.overlay import HANDLE_COLOUR, LEAF_COLOUR, draw_estimate


def test_a_frame_is_complete_when_every_stream_has_a_message_within_the_tolerance() -> None:
    sync = FrameSync(0.05)
    for stream, stamp in zip(STREAMS[:-1], (1.00, 1.02, 0.97)):
        assert sync.add(stream, stamp, f"{stream}@{stamp}") == (None, [])
    complete, dropped = sync.add("pose", 1.04, "pose@1.04")
    assert dropped == [] and complete == (1.00, {"color": "color@1.0", "depth": "depth@1.02", "info": "info@0.97",
                                                 "pose": "pose@1.04"})
    assert sync.pending == 0


def test_messages_beyond_the_tolerance_start_a_frame_of_their_own() -> None:
    sync = FrameSync(0.05)
    sync.add("color", 1.0, "a")
    sync.add("color", 1.2, "b")
    assert sync.pending == 2


def test_the_oldest_incomplete_frames_are_dropped_with_the_streams_they_lacked() -> None:
    sync = FrameSync(0.01, max_pending=2)
    sync.add("color", 1.0, "c")
    sync.add("depth", 1.0, "d")
    sync.add("color", 2.0, "c")
    complete, dropped = sync.add("color", 3.0, "c")
    assert complete is None and [d.stamp for d in dropped] == [1.0] and dropped[0].missing == ("info", "pose")
    assert dropped[0].describe() == "CameraInfo, camera pose" and sync.pending == 2


def test_bad_settings_and_unknown_streams_are_refused() -> None:
    with pytest.raises(DetectionError, match="tolerance"):
        FrameSync(-0.1)
    with pytest.raises(DetectionError, match="unknown stream 'audio'"):
        FrameSync(0.05).add("audio", 1.0, None)


def _door(corners: np.ndarray) -> DetectedDoor:
    return DetectedDoor(np.array([0.3, 0.0, 2.0]), np.array([0.0, 0.0, -1.0]), Side.LEFT, 0.9, corners, 1.0,
                        DetectionMode.AUTOMATIC)


def test_the_overlay_circles_the_handle_and_outlines_a_measured_leaf() -> None:
    intrinsics = CameraIntrinsics(320, 240, 300.0, 300.0, 160.0, 120.0)
    rgb = np.zeros((240, 320, 3), np.uint8)
    corners = np.array([[-0.45, 0.9, 2.0], [0.45, 0.9, 2.0], [0.45, -0.9, 2.0], [-0.45, -0.9, 2.0]])
    drawn = draw_estimate(rgb, intrinsics, _door(corners))
    assert not rgb.any()                                                  # the frame itself is untouched
    colours = {tuple(c) for c in drawn.reshape(-1, 3)}
    assert HANDLE_COLOUR in colours and LEAF_COLOUR in colours
    unmeasured = draw_estimate(rgb, intrinsics, _door(np.full((4, 3), np.nan)))
    assert LEAF_COLOUR not in {tuple(c) for c in unmeasured.reshape(-1, 3)}
