"""The footstep planner as a process over real DDS: the test publishes odometry and a door
estimate (as the sim bridge and detector would) and sends requests."""

import math
from dataclasses import replace

import pytest
import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from nav_msgs.msg import Odometry
from ros_helpers import executor_for, node_process, spin_until
from std_msgs.msg import String

from door_contract.converters.footsteps import path_to_footsteps
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import DoorEstimate, FootstepRequest, OutcomeStatus, PlanningOutcome, decode, encode
from door_contract.stamps import stamp_ns
from door_contract.topics import Topics
from door_contract.vocabulary import Foot, HingeSide

pytestmark = pytest.mark.ros  # starts rclpy nodes / DDS participants

# Wall at x = 0, robot at x = -4 facing +x; left hinge at y = +0.457, handle near y = -0.39.
ESTIMATE = DoorEstimate(0.0, "odom", (-0.06, -0.39, 0.91), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((0.0, 0.457, 0.0), (0.0, -0.457, 0.0), (0.0, -0.457, 2.08), (0.0, 0.457, 2.08)),
                        1.0, 10, "automatic")


@pytest.fixture(scope="module")
def planner(workspace, tmp_path_factory):
    log = tmp_path_factory.mktemp("planner") / "planner.log"
    with node_process(workspace, "footstep_planner", log, timeout_s=20) as process:
        yield process


class Client:
    def __init__(self, context):
        self.node = rclpy.create_node("footstep_client", context=context)
        self.executor = executor_for(self.node, context)
        self.plans, self.outcomes = [], []
        self.odom_pub = create_contract_publisher(self.node, Topics.ODOM)
        self.door_pub = create_contract_publisher(self.node, Topics.DOOR_ESTIMATE)
        self.request_pub = create_contract_publisher(self.node, Topics.FOOTSTEP_REQUEST)
        create_contract_subscription(self.node, Topics.FOOTSTEP_PROPOSAL, self.plans.append)
        create_contract_subscription(self.node, Topics.FOOTSTEP_OUTCOME,
                                     lambda m: self.outcomes.append(decode(PlanningOutcome, m.data)))
        self.inputs = {}  # what the planner reports having, from its /diagnostics
        self.node.create_subscription(DiagnosticArray, Topics.DIAGNOSTICS.name, lambda a: self.inputs.update(
            {kv.key: kv.value for s in a.status if s.name == "footstep_planner" for kv in s.values}), 10)

    def request(self, request_id, goal, x=-4.0, y=0.0, opening="push", door=ESTIMATE, attempt=0):
        """Publish odometry and the door like the graph does, wait until the planner reports
        (on /diagnostics) that it has both, then request."""
        odom = Odometry()
        odom.header.frame_id = "odom"
        odom.header.stamp.sec = request_id  # lets the test recognise this odometry in the planner's report
        odom.pose.pose.position.x, odom.pose.pose.position.y = x, y
        door = replace(door, stamp=float(request_id))
        publishers = (self.odom_pub, self.door_pub, self.request_pub)
        assert spin_until(self.executor, lambda: all(p.get_subscription_count() > 0 for p in publishers), 30.0)
        self.odom_pub.publish(odom)
        self.door_pub.publish(String(data=encode(door)))
        expected = {"odom": f"{request_id}.000000000", "door": f"{float(request_id):.3f}"}
        assert spin_until(self.executor, lambda: self.inputs.get("odom") == expected["odom"]
                          and self.inputs.get("door") == expected["door"], 30.0), self.log.read_text()
        self.request_pub.publish(String(data=encode(FootstepRequest(request_id, goal, opening, attempt=attempt))))
        assert spin_until(self.executor, lambda: any(o.request_id == request_id for o in self.outcomes), 30.0), \
            self.log.read_text()
        return next(o for o in self.outcomes if o.request_id == request_id)


@pytest.fixture
def client(planner, rclpy_context):
    client = Client(rclpy_context)
    client.log = planner.log
    yield client
    client.node.destroy_node()


def test_stand_pose_plan_alternates_feet_and_ends_in_front_of_the_door(client):
    outcome = client.request(1, "stand")
    assert outcome.status is OutcomeStatus.SUCCESS, outcome.reason
    assert spin_until(client.executor, lambda: any(
        stamp_ns(p.header.stamp) == outcome.stamp_ns for p in client.plans), 10.0)
    steps = path_to_footsteps(client.plans[-1])
    assert [s.foot for s in steps] == [Foot.LEFT if i % 2 == 0 else Foot.RIGHT for i in range(len(steps))]
    last_two = steps[-2:]
    centre_x = sum(s.x for s in last_two) / 2
    assert -0.7 < centre_x < -0.3  # ~0.5 m in front of the door plane
    assert outcome.footsteps is not None and outcome.footsteps.steps >= math.ceil(3.4 / 0.25)


def test_passage_through_the_door(client):
    outcome = client.request(2, "through", x=-0.6, y=0.0)
    assert outcome.status is OutcomeStatus.SUCCESS, outcome.reason
    steps = path_to_footsteps(client.plans[-1])
    assert steps[-1].x > 0.5  # beyond the wall


def test_goal_behind_a_closed_wall_fails_with_reason(client):
    boxed = DoorEstimate(0.0, "odom", (-0.06, -0.39, 0.91), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                         ESTIMATE.corners, 1.0, 10, "automatic")
    outcome = client.request(3, "stand", x=3.0, y=0.0, door=boxed)  # robot behind the wall
    assert outcome.status is not OutcomeStatus.SUCCESS
    assert outcome.reason


def test_unknown_goal_is_rejected(client):
    outcome = client.request(4, "moon")
    assert outcome.status is OutcomeStatus.REJECTED and "unknown goal" in outcome.reason


def test_a_repeat_is_planned_and_a_negative_attempt_is_rejected(client):
    repeat = client.request(5, "stand", attempt=1)
    assert repeat.status is OutcomeStatus.SUCCESS, repeat.reason
    refused = client.request(6, "stand", attempt=-1)
    assert refused.status is OutcomeStatus.REJECTED and "attempt" in refused.reason
