"""The trajectory optimizer as a process over real DDS: the test plays the sim bridge
(joint states, odometry at 20 Hz) and the detector (door estimate), and sends requests."""

import math
from dataclasses import replace

import pytest
import rclpy
from nav_msgs.msg import Odometry
from ros_helpers import executor_for, node_process, spin_until
from sensor_msgs.msg import JointState
from std_msgs.msg import String

from door_contract.converters.trajectory import msg_to_joint_path
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import DoorEstimate, MotionRequest, OutcomeStatus, PlanningOutcome, decode, encode
from door_contract.stamps import stamp_ns
from door_contract.topics import Topics
from door_contract.vocabulary import Backend, HingeSide
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_trajopt.library import MotionLibrary

pytestmark = pytest.mark.ros  # starts rclpy nodes / DDS participants

# base at (-0.5, -0.12) facing +x, door plane x = 0, left hinge: the footstep planner's stand pose
ESTIMATE = DoorEstimate(1.0, "odom", (-0.06, -0.321, 0.91), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((0.0, 0.457, 0.01), (0.0, -0.457, 0.01), (0.0, -0.457, 2.09), (0.0, 0.457, 2.09)),
                        1.0, 10, "automatic")


@pytest.fixture(scope="module")
def optimizer(workspace, tmp_path_factory):
    log = tmp_path_factory.mktemp("optimizer") / "trajectory_optimizer.log"
    with node_process(workspace, "trajectory_optimizer", log) as process:
        yield process


class Robot:
    def __init__(self, context, joints):
        self.node = rclpy.create_node("trajopt_test_robot", context=context)
        self.executor = executor_for(self.node, context)
        self.joints = joints
        self.outcomes, self.trajectories = [], []
        self.ticks = 0  # joint states / odometry published so far
        self.joint_pub = create_contract_publisher(self.node, Topics.JOINT_STATES)
        self.odom_pub = create_contract_publisher(self.node, Topics.ODOM)
        self.door_pub = create_contract_publisher(self.node, Topics.DOOR_ESTIMATE)
        self.request_pub = create_contract_publisher(self.node, Topics.MOTION_REQUEST)
        create_contract_subscription(self.node, Topics.MOTION_OUTCOME,
                                     lambda m: self.outcomes.append(decode(PlanningOutcome, m.data)))
        create_contract_subscription(self.node, Topics.MOTION_PROPOSAL, self.trajectories.append)
        self.node.create_timer(0.05, self._publish_state)

    def _publish_state(self):
        self.ticks += 1
        positions = self.joints()
        self.joint_pub.publish(JointState(name=list(positions), position=list(positions.values())))
        odom = Odometry()
        odom.header.frame_id = "odom"
        odom.pose.pose.position.x, odom.pose.pose.position.y, odom.pose.pose.position.z = -0.5, -0.121, 1.01927
        self.odom_pub.publish(odom)

    def request(self, request: MotionRequest, retry_not_ready: bool = True) -> PlanningOutcome:
        """Send; while the inputs are still in flight after discovery ('no … yet', 'not
        received'), send again (bounded)."""
        publishers = (self.request_pub, self.door_pub, self.joint_pub)
        assert spin_until(self.executor, lambda: all(p.get_subscription_count() for p in publishers), 30.0)
        for attempt in range(20):
            rid = request.request_id * 100 + attempt
            self.request_pub.publish(String(data=encode(replace(request, request_id=rid))))
            assert spin_until(self.executor, lambda rid=rid: any(o.request_id == rid for o in self.outcomes), 60.0)
            outcome = next(o for o in self.outcomes if o.request_id == rid)
            in_flight = "yet" in outcome.reason or "not received" in outcome.reason
            if not (retry_not_ready and in_flight):
                return outcome
            ticks = self.ticks  # let two more states go out before asking again
            assert spin_until(self.executor, lambda ticks=ticks: self.ticks >= ticks + 2, 10.0)
        raise AssertionError("the optimizer never had its inputs")


@pytest.fixture
def robot(optimizer, rclpy_context):
    kinematics = RobotKinematics(load_profile("talos"))
    nominal = dict(zip(kinematics.joint_names, kinematics.nominal_q.tolist()))
    state = {"positions": nominal}
    robot = Robot(rclpy_context, lambda: state["positions"])  # raw: the NaN case must reach the node
    robot.state = state
    robot.door_pub.publish(String(data=encode(ESTIMATE)))
    yield robot
    robot.node.destroy_node()


def test_approach_is_planned_within_limits(robot):
    outcome = robot.request(MotionRequest(1, "approach_handle", "push", "chomp", 0.0, ESTIMATE.stamp))
    assert outcome.status is OutcomeStatus.SUCCESS, outcome.reason
    # within the library's constraint tolerance (10 µm): the node now plans with its 10 waypoints
    figures = outcome.motion
    assert figures is not None and figures.max_violation is not None
    assert figures.max_violation <= MotionLibrary().constraint_tolerance
    assert figures.backend is Backend.CHOMP
    assert spin_until(robot.executor, lambda: any(
        stamp_ns(t.header.stamp) == outcome.stamp_ns
        for t in robot.trajectories), 10.0)
    path = msg_to_joint_path(robot.trajectories[-1])
    assert path.joint_names[:2] == ("torso_1_joint", "torso_2_joint") and "arm_right_4_joint" in path.joint_names


def test_unknown_motion_and_unknown_door_are_rejected(robot):
    unknown = robot.request(MotionRequest(2, "moonwalk", "push"))
    assert unknown.status is OutcomeStatus.REJECTED and "unknown motion" in unknown.reason
    missing = robot.request(MotionRequest(3, "approach_handle", "push", None, 0.0, 123.0), retry_not_ready=False)
    assert missing.status is OutcomeStatus.REJECTED and "123.000" in missing.reason


def test_nan_joint_states_are_rejected(robot):
    robot.state["positions"] = {**robot.state["positions"], "arm_right_4_joint": math.nan}
    outcome = None
    for attempt in range(20):  # until the NaN state has replaced the good one in the node
        outcome = robot.request(MotionRequest(4 + attempt, "approach_handle", "push", None, 0.0, ESTIMATE.stamp),
                                retry_not_ready=False)
        if outcome.status is not OutcomeStatus.SUCCESS:
            break
    assert outcome.status is OutcomeStatus.REJECTED and "joint states" in outcome.reason
    robot.state["positions"] = {**robot.state["positions"], "arm_right_4_joint": -0.5}
    again = robot.request(MotionRequest(40, "approach_handle", "push", None, 0.0, ESTIMATE.stamp))
    assert again.status is OutcomeStatus.SUCCESS, again.reason  # the node kept running


def test_a_door_angle_outside_the_stops_is_rejected_at_once(robot):
    """turn_handle at 1e6 rad once blocked the optimiser for 80 s; the library refuses it."""
    outcome = robot.request(MotionRequest(50, "turn_handle", "push", None, 1e6, ESTIMATE.stamp))
    assert outcome.status is OutcomeStatus.REJECTED and "door_angle 1e+06 rad is outside" in outcome.reason
    again = robot.request(MotionRequest(51, "approach_handle", "push", None, 0.0, ESTIMATE.stamp))
    assert again.status is OutcomeStatus.SUCCESS, again.reason  # the node kept running
