"""Markers of what the FSM is offered (ROS-free): footsteps, hand paths (Pinocchio FK), the door
and its swing; the picture keeps the latest of each; the converter refuses NaN."""

import math

import numpy as np
import pytest

from door_contract.converters.footsteps import FootPlacement
from door_contract.converters.markers import shapes_to_marker_array
from door_contract.converters.trajectory import JointPath
from door_contract.errors import NonFiniteError
from door_contract.marker_shapes import MarkerKind, MarkerShape
from door_contract.payloads import DoorEstimate
from door_contract.vocabulary import Foot, HingeSide, Side
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_viz.hand_paths import hand_paths
from door_viz.picture import ProposalPicture, SoleSize
from door_viz.proposals import footstep_shapes, leaf_axes, swing_shapes

# a left-hinged door in the wall x = 1.2 seen from the robot at x < 1.2 (normal −x)
ESTIMATE = DoorEstimate(0.0, "odom", (1.2, -0.35, 0.95), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((1.2, 0.457, 0.0), (1.2, -0.457, 0.0), (1.2, -0.457, 2.08), (1.2, 0.457, 2.08)),
                        1.0, 10, "automatic")
STEPS = [FootPlacement(Foot.LEFT, 0.0, 0.085, 0.0), FootPlacement(Foot.RIGHT, 0.2, -0.085, 0.1),
         FootPlacement(Foot.LEFT, 0.4, 0.085, 0.2)]


def test_footsteps_are_sole_sized_boxes_in_alternating_colours():
    shapes = footstep_shapes(STEPS, 0.22, 0.13)
    boxes = [s for s in shapes if s.kind is MarkerKind.CUBE]
    assert len(boxes) == 3 and boxes[0].scale[:2] == (0.22, 0.13)
    assert boxes[0].rgba == boxes[2].rgba != boxes[1].rgba
    np.testing.assert_allclose(boxes[1].pose[:2, 3], (0.2, -0.085))
    assert math.isclose(math.atan2(boxes[2].pose[1, 0], boxes[2].pose[0, 0]), 0.2)


@pytest.mark.parametrize("opening, away_from_robot", [("push", True), ("pull", False)])
def test_swing_opens_away_for_push_and_towards_the_robot_for_pull(opening, away_from_robot):
    hinge, u, s, width = leaf_axes(ESTIMATE, opening)
    np.testing.assert_allclose(hinge, (1.2, 0.457, 0.0))
    np.testing.assert_allclose(u, (0.0, -1.0, 0.0), atol=1e-12)
    assert math.isclose(width, 0.914)
    assert bool(s[0] > 0.99) is away_from_robot  # push: +x, past the wall; pull: −x, the robot's side
    fan, arc, leaf = swing_shapes(ESTIMATE, opening, math.radians(30))
    np.testing.assert_allclose(arc.points[-1][:2], hinge[:2] + width * s[:2], atol=1e-9)  # 90° open
    assert np.allclose(np.linalg.norm(arc.points[:, :2] - hinge[:2], axis=1), width)
    free_edge = leaf.points[1]
    np.testing.assert_allclose(free_edge, hinge + width * (math.cos(math.radians(30)) * u + math.sin(math.radians(30)) * s))


def test_hand_path_is_forward_kinematics_of_each_waypoint_in_odom():
    kinematics = RobotKinematics(load_profile("talos"))
    measured = dict(load_profile("talos").nominal_posture)
    base = np.eye(4)
    base[:3, 3] = (-1.0, 0.2, 1.0)
    path = JointPath(np.array([0.0, 1.0, 2.0]), ("arm_right_4_joint", "door_hinge"),
                     np.array([[-0.5, 0.0], [-1.0, 0.0], [-1.5, 0.0]]))
    paths = hand_paths(kinematics, measured, path, base)
    q = kinematics.configuration({**measured, "arm_right_4_joint": -1.5})
    expected = (base @ kinematics.frame_pose(q, kinematics.profile.tcp_frame(Side.RIGHT)))[:3, 3]
    np.testing.assert_allclose(paths["right"][-1], expected, atol=1e-12)
    assert np.ptp(paths["left"], axis=0).max() < 1e-12  # the left arm did not move


def test_picture_keeps_the_latest_of_each_and_draws_the_swing_once_the_opening_is_known():
    picture = ProposalPicture(SoleSize(0.22, 0.13))
    picture.show_door(ESTIMATE)
    assert {s.namespace for s in picture.shapes()} == {"door"}
    picture.show_request("pull", 0.2)
    picture.show_footsteps(STEPS)
    picture.show_footsteps(STEPS[:1])
    picture.show_hand_paths({"right": np.array([[0, 0, 1], [0.2, 0, 1]]), "left": np.zeros((2, 3))})
    shapes = picture.shapes()
    assert {s.namespace for s in shapes} == {"door", "door_swing", "footsteps", "hand_path"}
    assert len([s for s in shapes if s.namespace == "footsteps"]) == 1
    assert len([s for s in shapes if s.namespace == "hand_path"]) == 2  # the right hand's line + end


def test_marker_array_replaces_the_picture_and_refuses_nan():
    array = shapes_to_marker_array(footstep_shapes(STEPS, 0.22, 0.13), stamp=3.5)
    assert array.markers[0].action == array.markers[0].DELETEALL
    assert {m.ns for m in array.markers[1:]} == {"footsteps"} and array.markers[1].header.stamp.sec == 3
    with pytest.raises(NonFiniteError):
        shapes_to_marker_array([MarkerShape("x", 0, MarkerKind.LINE_STRIP, (1, 1, 1, 1), points=np.array([[np.nan, 0, 0]]))])
