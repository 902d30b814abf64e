"""The sim bridge as a process over real DDS: clock, joint states and camera arrive; a
trajectory is executed and reported; bad input is rejected with its reason and moves nothing."""

import subprocess

import numpy as np
import pytest
import rclpy
from ros_helpers import executor_for, node_process, spin_until

from door_bringup.graph_spec import GRAPH
from door_contract.converters.joint_state import joint_state_to_positions
from door_contract.converters.trajectory import JointPath, joint_path_to_msg
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import ExecutionOutcome, OutcomeStatus, decode
from door_contract.topics import Topics

pytestmark = pytest.mark.ros
BRIDGE = next(launch for launch in GRAPH if launch.node_name == "sim_bridge")


@pytest.fixture(scope="module")
def bridge(workspace, tmp_path_factory):
    log = tmp_path_factory.mktemp("bridge") / "sim_bridge.log"
    with node_process(workspace, "sim_bridge", log, "camera_rate:=2.0") as process:
        yield process, log


class Listener:
    def __init__(self, context):
        self.node = rclpy.create_node("bridge_listener", context=context)
        self.executor = executor_for(self.node, context)
        self.got = {"clock": [], "joints": [], "color": [], "depth": [], "outcomes": []}
        create_contract_subscription(self.node, Topics.CLOCK, self.got["clock"].append)
        create_contract_subscription(self.node, Topics.JOINT_STATES, lambda m: self.got["joints"].append(
            joint_state_to_positions(m)))
        create_contract_subscription(self.node, Topics.COLOR_IMAGE, self.got["color"].append)
        create_contract_subscription(self.node, Topics.DEPTH_IMAGE, self.got["depth"].append)
        create_contract_subscription(self.node, Topics.EXECUTION_OUTCOME, lambda m: self.got["outcomes"].append(
            decode(ExecutionOutcome, m.data)))
        self.trajectory_pub = create_contract_publisher(self.node, Topics.ARM_TRAJECTORY)

    def send(self, path: JointPath, stamp_sec: int) -> ExecutionOutcome:
        msg = joint_path_to_msg(path)
        msg.header.stamp.sec = stamp_sec
        assert spin_until(self.executor, lambda: self.trajectory_pub.get_subscription_count() > 0, 30.0)
        self.trajectory_pub.publish(msg)
        request_id = stamp_sec * 1_000_000_000
        assert spin_until(self.executor, lambda: any(o.request_id == request_id for o in self.got["outcomes"]), 60.0)
        return next(o for o in self.got["outcomes"] if o.request_id == request_id)


@pytest.fixture
def listener(bridge, rclpy_context):
    listener = Listener(rclpy_context)
    assert spin_until(listener.executor, lambda: all(listener.got[k] for k in ("clock", "joints", "color", "depth")),
                      60.0), bridge[1].read_text()
    yield listener
    listener.node.destroy_node()


def test_streams_arrive(listener):
    image = listener.got["color"][-1]
    assert image.encoding == "rgb8" and image.width == 640 and image.height == 480
    assert listener.got["depth"][-1].encoding == "32FC1"
    assert "arm_right_4_joint" in listener.got["joints"][-1]
    def clock():
        return [c.clock.sec + c.clock.nanosec * 1e-9 for c in listener.got["clock"]]
    # /clock is best-effort depth 1: wait for a second reading (under load the first may be all there is)
    assert spin_until(listener.executor, lambda: clock()[-1] > clock()[0], 30.0), clock()


def test_trajectory_is_executed_and_reported(listener):
    start = listener.got["joints"][-1]["arm_right_4_joint"]
    path = JointPath(np.array([0.0, 1.5]), ("arm_right_4_joint",), np.array([[start], [start - 0.3]]))
    outcome = listener.send(path, 1001)
    assert outcome.status is OutcomeStatus.SUCCESS, outcome.reason
    assert spin_until(listener.executor, lambda: abs(listener.got["joints"][-1]["arm_right_4_joint"]
                                                     - (start - 0.3)) < np.radians(1), 10.0)


@pytest.mark.parametrize("names, positions, reason", [
    (("elbow_of_doom",), [[0.0], [0.1]], "elbow_of_doom"),
    (("arm_right_4_joint",), [[-0.5], [5.0]], "limit"),
])
def test_bad_trajectory_is_rejected_and_moves_nothing(listener, names, positions, reason):
    before = dict(listener.got["joints"][-1])
    path = JointPath(np.array([0.0, 1.0]), names, np.array(positions))
    outcome = listener.send(path, 2000 + len(listener.got["outcomes"]))
    assert outcome.status is OutcomeStatus.REJECTED
    assert reason in outcome.reason
    after = listener.got["joints"][-1]
    assert abs(after["arm_right_4_joint"] - before["arm_right_4_joint"]) < 1e-3


@pytest.mark.parametrize("override, message", [
    ("handle_colour:=[0.5, 2.0, 0.5]", r"DoorConfig.handle_colour = 2.0 is outside the allowed range \[0, 1\]"),
    ("light_direction:=[0.0, 0.0, 0.0]", r"CameraConfig.light_direction .* no direction"),
])
def test_an_unrenderable_appearance_stops_the_bridge_with_a_message(workspace, override, message):
    import re

    command = [str(workspace.executable(BRIDGE.package, BRIDGE.executable)), "--ros-args",
               "--params-file", str(workspace.params_file("sim_bridge")), "-p", override]
    result = subprocess.run(command, env=workspace.environment(), capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert re.search(message, result.stdout + result.stderr), result.stderr
