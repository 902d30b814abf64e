"""Stopping with standard messages (ros2_control's convention): the supervisor's stop pair
is empty, stamped, in odom, and is what the sim bridge reads as a stop; motion is not."""

from builtin_interfaces.msg import Time
from geometry_msgs.msg import PoseStamped
from trajectory_msgs.msg import JointTrajectoryPoint

from door_contract.converters.stop import is_stop, stop_messages


def test_the_stop_pair_is_empty_stamped_and_read_as_a_stop():
    trajectory, path = stop_messages(Time(sec=3, nanosec=5))
    assert (trajectory.header.stamp.sec, path.header.stamp.nanosec, path.header.frame_id) == (3, 5, "odom")
    assert is_stop(trajectory) and is_stop(path)


def test_a_trajectory_with_points_or_a_path_with_poses_is_motion():
    trajectory, path = stop_messages(Time())
    trajectory.points.append(JointTrajectoryPoint())
    path.poses.append(PoseStamped())
    assert not is_stop(trajectory) and not is_stop(path)
