"""The run's summary figure from a bag: support polygon and margin, the derived handle, hand
distances from Pinocchio, states placed in sim time by /clock; and the progress line."""

import math

import numpy as np
import pytest
from nav_msgs.msg import Odometry
from rclpy.serialization import serialize_message
from rosgraph_msgs.msg import Clock
from std_msgs.msg import String

from door_bringup.bags.storage import BagWriter, StorageFormat
from door_bringup.progress import ProgressPrinter, TaskProgress, progress_line
from door_bringup.summary_data import handle_position, read_run
from door_bringup.summary_figure import plot_summary
from door_bringup.table_one import phase_of
from door_contract.converters.footsteps import FootPlacement, footsteps_to_path
from door_contract.converters.joint_state import positions_to_joint_state
from door_contract.payloads import DoorEstimate, encode
from door_contract.stamps import to_time_msg
from door_contract.topics import Topics
from door_contract.vocabulary import Foot, HingeSide, Side, TaskState
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_sim_bridge.world.door import HINGE_JOINT

ESTIMATE = DoorEstimate(0.0, "odom", (0.0, -0.35, 0.95), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((0.0, 0.457, 0.0), (0.0, -0.457, 0.0), (0.0, -0.457, 2.08), (0.0, 0.457, 2.08)),
                        1.0, 10, "automatic")
SOLES = [FootPlacement(Foot.LEFT, -1.0, 0.085, 0.0), FootPlacement(Foot.RIGHT, -1.0, -0.085, 0.0)]


@pytest.mark.parametrize("opening, sign", [("push", 1.0), ("pull", -1.0)])
def test_derived_handle_turns_about_the_hinge(opening, sign):
    np.testing.assert_allclose(handle_position(ESTIMATE, opening, 0.0), ESTIMATE.handle_position, atol=1e-12)
    quarter = handle_position(ESTIMATE, opening, math.pi / 2)
    hinge = np.array(ESTIMATE.corners[0])
    assert math.isclose(np.linalg.norm((quarter - hinge)[:2]), np.linalg.norm((np.array(ESTIMATE.handle_position) - hinge)[:2]))
    assert math.isclose(quarter[2], ESTIMATE.handle_position[2])
    assert sign * (quarter[0] - hinge[0]) > 0.7  # push: beyond the wall (+x); pull: towards the robot


def _synthetic_bag(path):
    """Two seconds of a standing robot whose right arm bends, the door opening 0.2 rad."""
    posture = dict(load_profile("talos").nominal_posture)
    odom = Odometry()
    odom.pose.pose.position.x, odom.pose.pose.position.z, odom.pose.pose.orientation.w = -1.0, 1.02, 1.0
    with BagWriter(path, StorageFormat.SQLITE3) as writer:
        def write(topic, ns, msg):
            return writer.write(topic.name, topic.type_name, ns, serialize_message(msg))
        write(Topics.DOOR_ESTIMATE, 1, String(data=encode(ESTIMATE)))
        write(Topics.TASK_STATE, 5_000_000_000, String(data="OPEN_DOOR/PUSH"))  # bag time: wall ns
        for k in range(21):
            t = 0.1 * k
            bag_ns = 4_000_000_000 + k * 100_000_000  # wall clock, 4 s ahead of sim time
            write(Topics.CLOCK, bag_ns, Clock(clock=to_time_msg(t)))
            odom.header.stamp = to_time_msg(t)
            write(Topics.ODOM, bag_ns, odom)
            write(Topics.JOINT_STATES, bag_ns, positions_to_joint_state({**posture, "arm_right_4_joint": -0.5 - 0.05 * k}, t))
            write(Topics.FOOT_POSES, bag_ns, footsteps_to_path(SOLES, t))
            write(Topics.DOOR_JOINT_STATES, bag_ns, positions_to_joint_state({HINGE_JOINT: 0.01 * k}, t))
    return posture


def test_run_series_from_a_bag(tmp_path):
    posture = _synthetic_bag(tmp_path / "bag")
    run = read_run(tmp_path / "bag", opening="push")
    assert run.states == [(pytest.approx(1.0), TaskState.PUSH)]  # wall 5 s ↔ sim 1 s through /clock
    assert len(run.com) == len(run.hands["right"]) == 21 and np.all(run.com[:, 3] > 0.0)
    kinematics = RobotKinematics(load_profile("talos"))
    q = kinematics.configuration({**posture, "arm_right_4_joint": -1.5})
    base = np.eye(4)
    base[:3, 3] = (-1.0, 0.0, 1.02)
    tcp = (base @ kinematics.frame_pose(q, kinematics.profile.tcp_frame(Side.RIGHT)))[:3, 3]
    np.testing.assert_allclose(run.hands["right"][-1, 1], np.linalg.norm(tcp - handle_position(ESTIMATE, "push", 0.2)))
    assert plot_summary(tmp_path / "bag", tmp_path / "summary.png", opening="push").stat().st_size > 50_000


def test_progress_line_and_printer():
    progress = TaskProgress(wall_s=41.2, sim_s=27.5, state=TaskState.TURN_HANDLE, base_xy=(-0.62, -0.15), door_angle=0.12)
    assert progress_line(progress) == ("[progress]   41 s | sim 27.5 s | 3/4 OPEN_DOOR/TURN_HANDLE | "
                                       "base (-0.62, -0.15) m | door 0.12 rad")
    assert phase_of(TaskState.PAUSED) == "PAUSED" and progress_line(TaskProgress()).endswith("waiting for the FSM")
    assert progress_line(progress.update(door_angle=-0.001)).endswith("door 0.00 rad")
    written = []
    log = ProgressPrinter(written.append, is_terminal=False, log_period_s=10.0)
    for wall in (0.0, 5.0, 10.0):
        log.show(progress.update(wall_s=wall))
    assert len(written) == 2 and all(w.endswith("\n") for w in written)
    terminal = ProgressPrinter(written.append, is_terminal=True)
    terminal.show(progress)
    assert written[-1].startswith("\r\033[K[progress]") and not written[-1].endswith("\n")
