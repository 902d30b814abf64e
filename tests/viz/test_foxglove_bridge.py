"""The Foxglove bridge over a real WebSocket and real DDS: a client sees the graph's topics with
their ROS 2 schemas, subscribes to the FSM's approval request and decodes it (CDR), publishes
``approve <id>`` from a client channel, and the FSM acts on it; refused client channels are
answered with a status; the URDF's meshes are served, nothing else is."""

import re
import time

import pytest
import rclpy
from foxglove_client import FoxgloveClient
from rcl_interfaces.msg import Log
from rclpy.qos import DurabilityPolicy, QoSProfile
from rclpy.serialization import deserialize_message
from ros_helpers import executor_for, spin_until, start_node
from std_msgs.msg import String

from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import DoorEstimate, encode
from door_contract.topics import Topics
from door_contract.vocabulary import HingeSide
from door_robot.meshes import resolve_package_uri

pytestmark = pytest.mark.ros
ESTIMATE = DoorEstimate(0.0, "odom", (1.2, -0.35, 0.95), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((1.2, 0.46, 0.0), (1.2, -0.46, 0.0), (1.2, -0.46, 2.08), (1.2, 0.46, 2.08)),
                        1.0, 10, "automatic")
MESH = "package://example-robot-data/robots/talos_data/meshes/arm/arm_1_collision.STL"


class Detector:
    """Stands in for the door detector; watches the FSM's state and its log lines on /rosout."""

    def __init__(self, context):
        self.node = rclpy.create_node("foxglove_test_peer", context=context)
        self.executor = executor_for(self.node, context)
        self.states, self.fsm_warnings = [], []
        self.estimate_pub = create_contract_publisher(self.node, Topics.DOOR_ESTIMATE)
        create_contract_subscription(self.node, Topics.TASK_STATE, self._on_state)
        self.node.create_subscription(Log, "/rosout", lambda m: m.name == "fsm_supervisor" and m.level >= Log.WARN
                                      and self.fsm_warnings.append(m.msg),
                                      QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL))

    def _on_state(self, msg):
        self.states.append(msg.data)
        if msg.data == "DETECT_DOOR":
            self.estimate_pub.publish(String(data=encode(ESTIMATE)))


@pytest.fixture
def graph(workspace, rclpy_context, tmp_path):
    detector = Detector(rclpy_context)
    bridge_log, fsm_log = tmp_path / "foxglove_bridge.log", tmp_path / "fsm.log"
    bridge = start_node(workspace, "foxglove_bridge", bridge_log, "port:=0", "discovery_period:=0.2")
    fsm = start_node(workspace, "fsm_supervisor", fsm_log, "approval_timeout:=120.0", "start_delay:=0.5",
                     "required_nodes:=['foxglove_test_peer']", "autonomy:=supervised")
    client = None
    try:
        port = []

        def port_logged() -> bool:
            port.extend(int(p) for p in re.findall(r"ws://127\.0\.0\.1:(\d+)", bridge_log.read_text())[:1])
            return bool(port) or bridge.poll() is not None

        assert spin_until(detector.executor, port_logged, 60.0) and port, bridge_log.read_text()
        # both up before a test can end: a SIGINT during start-up would interrupt an import
        assert spin_until(detector.executor, lambda: "fsm_supervisor" in detector.node.get_node_names()
                          or fsm.poll() is not None, 60.0), fsm_log.read_text()
        client = FoxgloveClient(f"ws://127.0.0.1:{port[0]}")
        yield detector, client, (bridge_log, fsm_log)
    finally:  # the processes stop even when the set-up failed (a leaked FSM would answer the next test)
        if client is not None:
            client.close()
        for process in (fsm, bridge):
            process.send_signal(2)
        codes = [bridge.wait(timeout=30), fsm.wait(timeout=30)]
        detector.node.destroy_node()
    assert codes == [0, 0], bridge_log.read_text() + fsm_log.read_text()


def _both(detector, client, condition, timeout_s):
    """Serve DDS and the WebSocket until ``condition()`` holds (deadline ``timeout_s``)."""
    deadline = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > deadline:
            return False
        detector.executor.spin_once(timeout_sec=0.02)
        client.pump(lambda: False, 0.02)
    return True


def test_client_decodes_the_approval_request_and_its_approval_moves_the_fsm(graph):
    detector, client, logs = graph
    topic = Topics.APPROVAL_REQUEST.name
    assert _both(detector, client, lambda: topic in client.channels, 30.0), logs[0].read_text()
    channel = client.channels[topic]
    assert (channel["encoding"], channel["schemaName"], channel["schemaEncoding"]) == (
        "cdr", "std_msgs/msg/String", "ros2msg")
    assert channel["schema"].strip() == "string data"
    client.subscribe(1, topic)
    def requests():
        return [t for t in (deserialize_message(b, String).data for b in client.messages.get(1, [])) if t]
    assert _both(detector, client, requests, 60.0), logs[1].read_text()
    request = requests()[0]
    assert request.startswith("DETECT_DOOR #")
    request_id = int(re.search(r"#(\d+)", request).group(1))

    client.advertise(7, Topics.OPERATOR.name)
    client.publish_json(7, {"data": f"approve {request_id}"})
    def moved():
        return "WALK_TO_DOOR" in detector.states
    def refused():
        return any(f"approve {request_id}" in w for w in detector.fsm_warnings)
    assert _both(detector, client, lambda: moved() or refused(), 60.0), logs[1].read_text()
    assert moved() and not refused(), detector.fsm_warnings  # the FSM answers ids only (a bare approve is refused)
    assert "'approve" in logs[0].read_text()  # the bridge logged what the client sent


def test_channels_outside_the_allowed_topics_are_refused_with_a_status(graph):
    detector, client, logs = graph
    assert _both(detector, client, lambda: client.server_info, 30.0)
    assert "clientPublish" in client.server_info["capabilities"]
    client.advertise(3, Topics.TASK_STATE.name)
    client.publish_json(3, {"data": "DONE"})
    assert _both(detector, client, lambda: len(client.statuses) >= 2, 30.0), logs[0].read_text()
    assert "clients may publish only on /door_task/operator" in client.statuses[0]["message"]
    assert "DONE" not in detector.states
    client.advertise(4, Topics.OPERATOR.name)
    client.publish_json(4, {"data": 5})
    assert _both(detector, client, lambda: any("std_msgs/String in JSON" in s["message"] for s in client.statuses),
                 30.0), client.statuses


def test_meshes_of_the_urdf_are_served_and_nothing_else(graph):
    detector, client, _ = graph
    client.fetch_asset(1, MESH)
    client.fetch_asset(2, "package://example-robot-data/../../../../../../etc/passwd")
    assert _both(detector, client, lambda: {1, 2} <= set(client.assets), 30.0)
    assert client.assets[1] == (0, resolve_package_uri(MESH).read_bytes())
    assert client.assets[2][0] == 1
