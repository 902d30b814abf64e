"""The supervisor as a process over real DDS, with the test acting as operator and detector."""

import subprocess

import pytest
import rclpy
from builtin_interfaces.msg import Duration
from diagnostic_msgs.msg import DiagnosticArray
from ros_helpers import executor_for, node_process, spin_until, start_node, stop_node
from std_msgs.msg import String
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from door_bringup.graph_spec import GRAPH
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import DoorEstimate, FootstepRequest, TaskReport, decode, encode
from door_contract.topics import Topics
from door_contract.vocabulary import AttemptOutcome, HingeSide, TaskState, WalkGoal

pytestmark = pytest.mark.ros
ESTIMATE = DoorEstimate(0.0, "odom", (1.2, -0.35, 0.95), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((1.2, 0.46, 0.0), (1.2, -0.46, 0.0), (1.2, -0.46, 2.08), (1.2, 0.46, 2.08)),
                        1.0, 10, "automatic")


class Peer:
    """Stands in for the detector (and is a 'required node'); records what the FSM says."""

    def __init__(self, context, detects=True):
        self.node = rclpy.create_node("fsm_test_peer", context=context)
        self.detects = detects  # publishes the estimate as DETECT_DOOR starts
        self.executor = executor_for(self.node, context)
        self.states, self.requests, self.failures = [], [], []
        self.estimate_pub = create_contract_publisher(self.node, Topics.DOOR_ESTIMATE)
        self.operator_pub = create_contract_publisher(self.node, Topics.OPERATOR)
        create_contract_subscription(self.node, Topics.TASK_STATE, self._on_state)
        create_contract_subscription(self.node, Topics.APPROVAL_REQUEST,
                                     lambda m: m.data and self.requests.append(m.data))
        self.walk_messages = []  # ("crouch", m) and ("request", goal), in arrival order
        create_contract_subscription(self.node, Topics.WALK_CROUCH,
                                     lambda m: self.walk_messages.append(("crouch", m.data)))
        create_contract_subscription(self.node, Topics.FOOTSTEP_REQUEST,
                                     lambda m: self.walk_messages.append(("request", decode(FootstepRequest, m.data).goal)))
        self.reports = []
        self.watching = []  # required nodes the supervisor reports having seen
        self.messages = []  # its diagnostics messages
        create_contract_subscription(self.node, Topics.TASK_REPORT,
                                     lambda m: self.reports.append(decode(TaskReport, m.data)))
        self.node.create_subscription(DiagnosticArray, Topics.DIAGNOSTICS.name, self._on_diagnostics, 10)

    def _on_diagnostics(self, array):
        for status in (s for s in array.status if s.name == "fsm_supervisor"):
            values = {kv.key: kv.value for kv in status.values}
            if values.get("failure", "-") != "-":
                self.failures.append(values["failure"])
            if "watching" in values:
                self.watching.append(values["watching"])
            self.messages.append(status.message)

    def _on_state(self, msg):
        self.states.append(msg.data)
        if msg.data == "DETECT_DOOR" and self.detects:
            self.estimate_pub.publish(String(data=encode(ESTIMATE)))

    def say(self, word):
        self.operator_pub.publish(String(data=word))

    def wait(self, condition, timeout=30.0):
        return spin_until(self.executor, condition, timeout)


@pytest.fixture
def supervisor(workspace, rclpy_context, tmp_path, request):
    peer = Peer(rclpy_context, detects=getattr(request, "param", True))
    peer.log_path = tmp_path / "fsm.log"
    with node_process(workspace, "fsm_supervisor", peer.log_path, "approval_timeout:=4.0", "start_delay:=0.5",
                      "required_nodes:=['fsm_test_peer']", timeout_s=20):
        yield peer
    peer.node.destroy_node()


def test_approval_request_then_operator_silence_times_out(supervisor):
    assert supervisor.wait(lambda: supervisor.requests), supervisor.log_path.read_text()
    assert supervisor.requests[0].startswith("DETECT_DOOR #1: approve detection")
    assert "hinge=left" in supervisor.requests[0]
    assert supervisor.wait(lambda: "FAILED" in supervisor.states, 30.0)
    assert supervisor.wait(lambda: any("operator did not answer" in f for f in supervisor.failures), 10.0)
    assert supervisor.wait(lambda: supervisor.reports, 10.0)
    report = supervisor.reports[-1]
    assert report.final_state == "FAILED" and "operator did not answer" in report.failure_reason
    assert report.attempts[0].state is TaskState.DETECT_DOOR and report.attempts[0].outcome is AttemptOutcome.TIMEOUT


def test_each_walk_request_sets_the_walks_crouch_first(supervisor):
    """/walking/crouch is set when a walk is asked for, before its plan can exist: the walk to
    the door upright (TALOS crouches only through a push door whose lever meets its pelvis)."""
    assert supervisor.wait(lambda: supervisor.requests), supervisor.log_path.read_text()
    supervisor.say("approve 1")
    assert supervisor.wait(lambda: ("request", WalkGoal.STAND) in supervisor.walk_messages), supervisor.walk_messages
    assert supervisor.wait(lambda: ("crouch", 0.0) in supervisor.walk_messages), supervisor.walk_messages
    assert [kind for kind, _ in supervisor.walk_messages].count("crouch") == 1  # one walk, one crouch


@pytest.mark.parametrize("supervisor", [False], indirect=True)  # the test looks, then detects
def test_each_look_of_the_head_search_replaces_the_last(supervisor):
    """The detector's looks reach the robot while DETECT_DOOR waits, each after a stop of the one
    before (the robot refuses a trajectory while another runs: a Monte-Carlo door was never
    confirmed, every look towards it refused as busy); the confirming estimate stops the last."""
    arm = []
    create_contract_subscription(supervisor.node, Topics.ARM_TRAJECTORY,
                                 lambda m: arm.append([p.positions[0] for p in m.points]))
    look_pub = create_contract_publisher(supervisor.node, Topics.HEAD_LOOK)
    assert supervisor.wait(lambda: "DETECT_DOOR" in supervisor.states), supervisor.log_path.read_text()
    for pan in (0.3, -0.3):
        look = JointTrajectory(joint_names=["head_2_joint"],
                               points=[JointTrajectoryPoint(positions=[pan], time_from_start=Duration(sec=1))])
        look_pub.publish(look)
        assert supervisor.wait(lambda sent=[pan]: sent in arm), (arm, supervisor.log_path.read_text())
    supervisor.estimate_pub.publish(String(data=encode(ESTIMATE)))
    assert supervisor.wait(lambda: len(arm) == 4), arm
    assert arm == [[0.3], [], [-0.3], []]  # a stop (no points) before the second look and after it


def test_reject_pause_resume_abort_and_unknown_command(supervisor):
    assert supervisor.wait(lambda: supervisor.requests)
    supervisor.say("reject")  # no id: refused, nothing changes
    supervisor.say("reject 2")  # another request's id: refused
    supervisor.say("reject 1")
    assert supervisor.wait(lambda: len(supervisor.requests) >= 2)  # re-detected, asked again
    assert supervisor.requests[1].startswith("DETECT_DOOR #2: approve detection")
    supervisor.say("dance")
    supervisor.say("pause")
    assert supervisor.wait(lambda: supervisor.states[-1] == "PAUSED")
    supervisor.say("resume")
    assert supervisor.wait(lambda: supervisor.states[-1] == "DETECT_DOOR")
    supervisor.say("abort")
    assert supervisor.wait(lambda: supervisor.states[-1] == "FAILED")
    assert supervisor.wait(lambda: any("aborted by the operator" in f for f in supervisor.failures), 10.0)
    log = supervisor.log_path.read_text()
    assert "unknown operator command 'dance'" in log
    assert "'reject' needs the id" in log and "'reject 2' refused: the current request is #1" in log


def test_a_killed_node_fails_the_task(workspace, rclpy_context, tmp_path):
    """SIGKILL a required node mid-task: the supervisor reports FAILED naming it, no hang."""
    detector = next(launch for launch in GRAPH if launch.node_name == "door_detector")
    victim = subprocess.Popen([str(workspace.executable(detector.package, detector.executable))],
                              env=workspace.environment(), stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    peer = Peer(rclpy_context)
    log = tmp_path / "fsm.log"
    fsm = start_node(workspace, "fsm_supervisor", log, "start_delay:=0.5", "required_nodes:=['door_detector']")
    try:
        assert peer.wait(lambda: peer.requests), log.read_text()
        # kill only once the supervisor itself has seen the node (its /diagnostics says so)
        assert peer.wait(lambda: any("door_detector" in w.split(",") for w in peer.watching), 30.0), log.read_text()
        victim.kill()
        assert peer.wait(lambda: peer.states[-1] == "FAILED", 30.0), log.read_text()
        assert peer.wait(lambda: any("/door_detector is gone" in f for f in peer.failures), 10.0)
    finally:
        victim.kill()
        assert stop_node(fsm, 20) == 0
        peer.node.destroy_node()


def test_the_task_starts_only_when_the_required_nodes_are_up(workspace, rclpy_context, tmp_path):
    """DETECT_DOOR's clock must not run while the graph is still starting."""
    peer = Peer(rclpy_context)
    log = tmp_path / "fsm.log"
    fsm = start_node(workspace, "fsm_supervisor", log, "start_delay:=0.2",
                     "required_nodes:=['fsm_test_peer', 'fsm_test_late_node']")
    late = None
    try:
        assert peer.wait(lambda: any("waiting for fsm_test_late_node" in m for m in peer.messages), 30.0), \
            log.read_text()
        assert peer.states == []
        late = rclpy.create_node("fsm_test_late_node", context=rclpy_context)
        assert peer.wait(lambda: "DETECT_DOOR" in peer.states, 30.0), log.read_text()
    finally:
        assert stop_node(fsm, 20) == 0
        peer.node.destroy_node()
        if late is not None:
            late.destroy_node()
