"""The detector's ROS-free core: the camera is the robot profile's, frames from another camera
are refused, rendered frames are voted into one estimate in odom, scribbles are checked."""

from __future__ import annotations

import numpy as np
import pytest

from door_detection.detector import CameraFrame, DetectorCamera, DoorDetector
from door_detection.frame_sync import DroppedFrame
from door_detection.options import DetectionOptions
from door_detection.payload import NominalDoor
from door_robot.profile import load_profile

PROFILES = ("talos", "atlas_v4", "drc_hubo", "g1")
OPTICAL = "head_camera_optical_frame"
# odom_T_optical of a level camera 1.5 m up looking along odom +x: optical z = x, x = -y, y = -z
CAMERA_POSE = np.array([[0.0, 0.0, 1.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, -1.0, 0.0, 1.5], [0.0, 0.0, 0.0, 1.0]])


def _profile(name: str, request: pytest.FixtureRequest):
    if name in ("atlas_v4", "drc_hubo"):  # their URDFs are real files in ../shared/data
        request.getfixturevalue("shared_data")
    return load_profile(name)


@pytest.mark.parametrize("name", PROFILES)
def test_the_camera_is_the_profiles_head_camera(name: str, request: pytest.FixtureRequest) -> None:
    profile = _profile(name, request)
    camera = DetectorCamera.of(profile)
    assert (camera.robot, camera.camera_link, camera.optical_frame) == (name, profile.head_camera_frame, OPTICAL)
    assert camera.frame_problem({"color": OPTICAL, "depth": OPTICAL, "info": OPTICAL}, "odom") is None
    problem = camera.frame_problem({"color": OPTICAL, "depth": "left_camera_optical_frame", "info": OPTICAL}, "odom")
    assert problem is not None and "depth in 'left_camera_optical_frame'" in problem
    assert f"{name}'s head camera" in problem and profile.head_camera_frame in problem
    assert "camera pose in 'map'" in (camera.frame_problem({"color": OPTICAL}, "map") or "")


def _detector(**options: object) -> DoorDetector:
    return DoorDetector(DetectionOptions(**options), DetectorCamera("talos", "rgbd_rgb_optical_frame"),
                        NominalDoor(), scribble_timeout=30.0)


def test_rendered_frames_are_voted_into_one_estimate_in_odom(straight_on) -> None:
    detector = _detector()
    reports = [detector.process(CameraFrame(10.0 + 0.5 * i, straight_on.rgb, straight_on.depth,
                                            straight_on.intrinsics, CAMERA_POSE), now=0.0) for i in range(2)]
    assert reports[0].confirmed is None and reports[0].seen is not None and not reports[0].warning
    confirmed = reports[1].confirmed
    assert confirmed is not None and confirmed.stamp == 10.5 and confirmed.frames_voted == 2
    assert confirmed.frame_id == "odom"
    truth = CAMERA_POSE[:3, :3] @ straight_on.handle_position + CAMERA_POSE[:3, 3]
    assert np.linalg.norm(np.subtract(confirmed.handle_position, truth)) < 0.02
    assert reports[1].handle_pose is not None and np.allclose(reports[1].handle_pose[:3, 3], confirmed.handle_position)
    assert detector.counters() == {"frames": 2, "rejected": 0}


def test_a_frame_without_a_door_is_counted_and_not_voted_for(straight_on) -> None:
    detector = _detector()
    wall = np.full_like(straight_on.rgb, 120)
    report = detector.process(CameraFrame(1.0, wall, straight_on.depth, straight_on.intrinsics, CAMERA_POSE), 0.0)
    assert report.confirmed is None and report.seen is None and not report.warning
    assert report.note.startswith("frame at 1.00 s: no_")
    refused = detector.reject_input(2.0, "colour must be rgb8, got 'bgr8'")
    assert refused.warning and "frame at 2.00 s rejected: colour must be rgb8" in refused.note
    assert detector.counters() == {"frames": 2, "rejected": 2}


def test_a_scribble_is_checked_against_the_image_and_then_used_until_it_is_old(straight_on) -> None:
    detector = _detector()
    assert "no camera image has arrived" in detector.take_scribble(straight_on.scribble, 0.0).note
    height, width = straight_on.rgb.shape[:2]
    detector.image_size = (width, height)
    refused = detector.take_scribble(np.array([[width + 10.0, 5.0]]), 0.0)
    assert refused.warning and "outside" in refused.note and detector.scribble is None
    accepted = detector.take_scribble(straight_on.scribble, now=100.0)
    assert not accepted.warning and detector.scribble is not None
    frame = CameraFrame(3.0, straight_on.rgb, straight_on.depth, straight_on.intrinsics, CAMERA_POSE)
    assert detector.process(frame, now=110.0).values["mode"] == "operator"
    assert detector.process(frame, now=131.0).values["mode"] == "automatic"  # older than scribble_timeout


def test_a_dropped_frame_names_the_stream_it_lacked() -> None:
    detector = _detector()
    report = detector.dropped(DroppedFrame(4.0, ("info",)))
    assert report.warning and report.note == "frame at 4.00 s dropped: no CameraInfo with its stamp"
    assert report.values == {"incomplete": 1, "missing": "CameraInfo"}


def test_a_plane_that_is_not_vertical_in_odom_is_no_door(straight_on) -> None:
    """The same rendered door, with the camera pose saying the camera looked straight down: its
    plane is then the floor in odom. A head search looking down once confirmed such a plane (the
    handle on the floor); the FSM refused the estimate and nothing else was confirmed."""
    down = np.array([[0.0, -1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, -1.0, 1.5], [0.0, 0.0, 0.0, 1.0]])
    detector = _detector()
    reports = [detector.process(CameraFrame(10.0 + 0.5 * i, straight_on.rgb, straight_on.depth,
                                            straight_on.intrinsics, down), now=0.0) for i in range(3)]
    assert all(report.confirmed is None and report.seen is None for report in reports)
    assert reports[0].note.startswith("frame at 10.00 s: not_upright: the plane's normal is ")
    assert "° from vertical, not horizontal" in reports[0].note
    assert detector.counters() == {"frames": 3, "rejected": 3}
    upright = detector.process(CameraFrame(12.0, straight_on.rgb, straight_on.depth, straight_on.intrinsics,
                                           CAMERA_POSE), now=0.0)
    assert upright.seen is not None


def test_upright_problem_accepts_a_door_tilted_by_noise_and_refuses_floor_and_ceiling() -> None:
    from door_detection.detector import upright_problem

    assert upright_problem(np.array([0.99, 0.0, 0.14])) is None  # 8° of tilt
    assert upright_problem(np.array([0.0, 0.0, 1.0])) is not None
    assert upright_problem(np.array([0.1, 0.0, -0.99])) is not None
    assert upright_problem(np.zeros(3)) is not None
