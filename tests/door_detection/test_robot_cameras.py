"""Each robot's own head camera, as the graph renders it (640×480, 60°, the profile's camera
frame, axes and look posture), sees door and handle well enough for the automatic detector.

G1 has no neck: its camera looks 48° down as mounted and sees the handle only from within
~1 m; its profile's look posture leans the torso back 0.3 rad (camera 31° down).
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers_detection import angle_deg, handle_error

from door_detection.automatic import detect_automatic
from door_detection.estimate import DetectionOutcome
from door_sim_bridge.world import DoorWorld, RobotMode, StanceConfig, WorldConfig


def _detect(robot: str, distance: float, posture_overrides: tuple[tuple[str, float], ...] = ()):
    """(outcome, handle error m, normal error deg) of one frame from ``distance`` facing the door."""
    config = WorldConfig(robot_profile=robot, stance=StanceConfig(distance=distance),
                         robot_mode=RobotMode.KINEMATIC, posture_overrides=posture_overrides)
    with DoorWorld(config) as world:
        frame, truth, grasp = world.render(), world.door_ground_truth(), world.handle_grasp_pose()
    rotation, origin = frame.camera_pose[:3, :3], frame.camera_pose[:3, 3]
    result = detect_automatic(frame.rgb, frame.depth, frame.intrinsics)
    if result.estimate is None:
        return result.outcome, np.nan, np.nan
    return (result.outcome, handle_error(result.estimate.handle_position, (grasp[:3, 3] - origin) @ rotation),
            angle_deg(result.estimate.normal, np.asarray(truth.normal) @ rotation))


@pytest.mark.parametrize("distance", [1.0, 2.5, 4.0])
def test_g1_leaning_back_sees_door_and_handle_from_1_to_4_m(distance):
    outcome, handle, normal = _detect("g1", distance)
    assert outcome is DetectionOutcome.DETECTED
    assert handle < 0.02 and normal < 2.0


def test_g1_upright_does_not_see_the_handle_at_2_5_m():
    """Why the look posture: upright, the mounted camera's view ends above the handle."""
    outcome, _, _ = _detect("g1", 2.5, posture_overrides=(("waist_pitch_joint", 0.0),))
    assert outcome is DetectionOutcome.NO_HANDLE
