"""CameraInfo, JointState, JointTrajectory, PoseStamped and Path converters."""

import math

import numpy as np
import pytest
from geometry_msgs.msg import Pose
from nav_msgs.msg import Path
from sensor_msgs.msg import CameraInfo, JointState
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from door_contract.converters.camera_info import (
    CameraIntrinsics,
    camera_info_to_intrinsics,
    check_matches_image,
    intrinsics_to_camera_info,
)
from door_contract.converters.footsteps import FootPlacement, footsteps_to_path, path_to_footsteps
from door_contract.converters.joint_state import joint_state_to_positions, positions_to_joint_state
from door_contract.converters.pose import matrix_to_pose_stamped, pose_stamped_to_matrix, pose_to_matrix
from door_contract.converters.trajectory import JointPath, joint_path_to_msg, msg_to_joint_path
from door_contract.errors import NonFiniteError, ShapeError
from door_contract.geometry import planar_pose
from door_contract.vocabulary import Foot

INTRINSICS = CameraIntrinsics(640, 480, 525.0, 520.0, 319.5, 239.5)


def test_camera_info_round_trip_and_projection():
    back = camera_info_to_intrinsics(intrinsics_to_camera_info(INTRINSICS, "cam"))
    assert back == INTRINSICS
    points = np.array([[0.2, -0.1, 2.0], [-0.5, 0.3, 3.5]])
    pixels = back.project(points)
    np.testing.assert_allclose(back.back_project(pixels[:, 0], pixels[:, 1], points[:, 2]), points)


@pytest.mark.parametrize("k, size, error", [
    ([math.nan, 0, 1, 0, 1, 1, 0, 0, 1], (640, 480), NonFiniteError),
    ([0, 0, 1, 0, 1, 1, 0, 0, 1], (640, 480), ShapeError),
    ([500, 0, 1, 0, 500, 1, 0, 0, 1], (0, 480), ShapeError),
])
def test_bad_camera_info(k, size, error):
    msg = CameraInfo(width=size[0], height=size[1])
    msg.k = [float(v) for v in k]
    with pytest.raises(error):
        camera_info_to_intrinsics(msg)


def test_camera_info_must_match_image_size():
    with pytest.raises(ShapeError, match="640×480"):
        check_matches_image(INTRINSICS, 1024, 544)


def test_joint_state_round_trip():
    positions = {"arm_left_1_joint": 0.3, "torso_1_joint": -0.1}
    assert joint_state_to_positions(positions_to_joint_state(positions, stamp=1.0)) == positions


@pytest.mark.parametrize("names, positions, error", [
    (["a", "b"], [0.1], ShapeError),
    (["a", "a"], [0.1, 0.2], ShapeError),
    (["a"], [math.nan], NonFiniteError),
])
def test_bad_joint_state(names, positions, error):
    with pytest.raises(error):
        joint_state_to_positions(JointState(name=names, position=positions))


def test_trajectory_round_trip():
    path = JointPath(np.array([0.0, 0.5, 1.25]), ("j1", "j2"),
                     np.array([[0.0, 0.1], [0.2, 0.3], [0.4, 0.5]]), np.zeros((3, 2)))
    back = msg_to_joint_path(joint_path_to_msg(path))
    np.testing.assert_allclose(back.times, path.times)
    np.testing.assert_allclose(back.positions, path.positions)
    assert back.joint_names == path.joint_names


def _trajectory(times, positions, names=("j1",)):
    msg = JointTrajectory(joint_names=list(names))
    for t, q in zip(times, positions):
        point = JointTrajectoryPoint(positions=list(q))
        point.time_from_start.sec, point.time_from_start.nanosec = int(t), int((t % 1) * 1e9)
        msg.points.append(point)
    return msg


@pytest.mark.parametrize("msg, error", [
    (_trajectory([0.0, 1.0], [[0.0], [math.inf]]), NonFiniteError),
    (_trajectory([1.0, 1.0], [[0.0], [0.1]]), ShapeError),
    (_trajectory([0.0, 1.0], [[0.0], [0.1, 0.2]]), ShapeError),
    (_trajectory([], []), ShapeError),
])
def test_bad_trajectory(msg, error):
    with pytest.raises(error):
        msg_to_joint_path(msg)


def test_pose_round_trip():
    transform = planar_pose(1.0, -2.0, 0.7, z=0.9)
    np.testing.assert_allclose(pose_stamped_to_matrix(matrix_to_pose_stamped(transform, "odom")),
                               transform, atol=1e-12)


def test_nan_and_zero_quaternion_poses_are_rejected():
    zero_quaternion = Pose()
    zero_quaternion.orientation.w = 0.0
    with pytest.raises(NonFiniteError, match="zero quaternion"):
        pose_to_matrix(zero_quaternion)
    pose = matrix_to_pose_stamped(np.eye(4), "odom").pose
    pose.position.y = math.nan
    with pytest.raises(NonFiniteError):
        pose_to_matrix(pose)


def test_footsteps_alternate_left_right():
    steps = [FootPlacement(Foot.LEFT, 0.2, 0.085, 0.0), FootPlacement(Foot.RIGHT, 0.4, -0.085, 0.1)]
    back = path_to_footsteps(footsteps_to_path(steps))
    assert [s.foot for s in back] == [Foot.LEFT, Foot.RIGHT]
    assert back[1].yaw == pytest.approx(0.1)
    with pytest.raises(ShapeError, match="left"):
        footsteps_to_path(steps[1:])


def test_footsteps_outside_odom_rejected():
    path = footsteps_to_path([FootPlacement(Foot.LEFT, 0.0, 0.0, 0.0)])
    path.header.frame_id = "map"
    with pytest.raises(ShapeError, match="odom"):
        path_to_footsteps(path)
    assert path_to_footsteps(Path()) == []
