"""The supervisor against hostile operators and lost nodes, over DDS, with the real sim bridge
as the robot and the test as detector and planners: an approval answers one request only,
garbage changes nothing, and pause, abort, a lost node or a killed supervisor stop the
robot (an arm holds at once; a walk ends with the step in progress)."""

import signal

import numpy as np
import pytest
from fuzz_graph import ESTIMATE, STILL_BASE, Observer
from ros_helpers import start_node, stop_node
from std_msgs.msg import String

from door_contract.converters.footsteps import footsteps_to_path
from door_contract.converters.trajectory import JointPath, joint_path_to_msg
from door_contract.node_support import create_contract_publisher, create_contract_subscription
from door_contract.payloads import FootstepRequest, MotionRequest, OutcomeStatus, PlanningOutcome, decode, encode
from door_contract.stamps import UniqueStamps, stamp_ns, time_msg_of_ns
from door_contract.topics import Topics

pytestmark = pytest.mark.ros

ELBOW = "arm_right_4_joint"
PLANNER = "fuzz_fake_planner"


class FakePlanners:
    """Plays both planners (and is a required node): answers each request with a slow plan
    from where the robot is — ``steps`` footsteps, or the elbow 0.5 rad down in 5 s."""

    def __init__(self, context, observer, steps=20):  # ~15 s of walking for the physical robot
        import rclpy

        self.node = rclpy.create_node(PLANNER, context=context)
        self.observer, self.steps, self.stamps = observer, steps, UniqueStamps()
        self.requests = []
        def pub(topic):
            return create_contract_publisher(self.node, topic)
        self.pubs = {"footsteps": (pub(Topics.FOOTSTEP_PROPOSAL), pub(Topics.FOOTSTEP_OUTCOME)),
                     "motion": (pub(Topics.MOTION_PROPOSAL), pub(Topics.MOTION_OUTCOME))}
        create_contract_subscription(self.node, Topics.FOOTSTEP_REQUEST, self._on_footsteps)
        create_contract_subscription(self.node, Topics.MOTION_REQUEST, self._on_motion)
        observer.executor.add_node(self.node)

    def _on_footsteps(self, msg):
        request = decode(FootstepRequest, msg.data)
        self.requests.append(request)
        self._propose("footsteps", request.request_id, footsteps_to_path(self.observer.walk_plan(self.steps)))

    def _on_motion(self, msg):
        request = decode(MotionRequest, msg.data)
        self.requests.append(request)
        elbow = self.observer.joints[ELBOW]
        self._propose("motion", request.request_id,
                      joint_path_to_msg(JointPath(np.array([5.0]), (ELBOW,), np.array([[elbow - 0.5]]))))

    def _propose(self, kind, request_id, message):
        message.header.stamp = time_msg_of_ns(self.stamps.next(self.node.get_clock().now().nanoseconds))
        proposal_pub, outcome_pub = self.pubs[kind]
        proposal_pub.publish(message)
        outcome_pub.publish(String(data=encode(PlanningOutcome(
            request_id, OutcomeStatus.SUCCESS, "", 0.01, stamp_ns=stamp_ns(message.header.stamp)))))

    def destroy(self):
        self.observer.executor.remove_node(self.node)
        self.node.destroy_node()


@pytest.fixture(scope="module")
def bridge(workspace, tmp_path_factory):
    log = tmp_path_factory.mktemp("fuzz_fsm") / "sim.log"
    process = start_node(workspace, "sim_bridge", log, "camera_rate:=0.0", "real_time:=true",
                         "supervisor_timeout:=2.0")
    yield process
    assert stop_node(process) == 0, log.read_text()[-3000:]


@pytest.fixture
def task(workspace, bridge, rclpy_context, tmp_path):
    """A fresh supervisor (supervised autonomy) with the test as detector and planners."""
    observer = Observer(rclpy_context)
    planners = FakePlanners(rclpy_context, observer)
    estimate_pub = observer.pubs["DOOR_ESTIMATE"]
    create_contract_subscription(observer.node, Topics.TASK_STATE,
                                 lambda m: m.data == "DETECT_DOOR" and estimate_pub.publish(String(data=encode(ESTIMATE))))
    fsm = start_node(workspace, "fsm_supervisor", tmp_path / "fsm.log", "start_delay:=0.5", "autonomy:=supervised",
                     f"required_nodes:=['sim_bridge', '{PLANNER}']", "execution_timeout_margin:=60.0")
    observer.fsm, observer.planners, observer.bridge = fsm, planners, bridge
    assert observer.wait(lambda: observer.requests, 60.0), fsm.log.read_text()
    # the bridge's dead-man tripped when the previous test's supervisor stopped: let it hear this one
    assert observer.wait(lambda: observer.heartbeats.get("fsm_supervisor", 0) >= 3, 30.0)
    yield observer
    planners.destroy()
    observer.destroy()
    if fsm.poll() is None:
        assert stop_node(fsm) == 0, fsm.log.read_text()[-3000:]


def _approve(task, request_id):
    count = len(task.requests)
    task.publish("OPERATOR", f"approve {request_id}")
    return count


def _walking(task):
    """Approve the door (#1) and the footstep plan (#2); returns the base pose before the walk."""
    start = task.settled_state().base
    count = _approve(task, 1)
    assert task.wait(lambda: len(task.requests) > count and task.requests[-1].startswith("WALK_TO_DOOR #2"), 30.0)
    _approve(task, 2)
    assert task.wait(lambda: np.linalg.norm(task.base - start) > 0.02, 30.0), task.fsm.log.read_text()[-2000:]
    return start


def _stopped_walk(task, start, max_steps=2):
    """The walk's outcome is STOPPED after at most ``max_steps`` of its steps and the base no
    longer moves (sub-millimetre sway of the physical robot aside)."""
    assert task.wait(lambda: any(o.status is OutcomeStatus.STOPPED for o in task.outcomes["execution"]), 20.0), \
        (task.outcomes["execution"], task.fsm.log.read_text()[-2000:])
    stopped = next(o for o in task.outcomes["execution"] if o.status is OutcomeStatus.STOPPED)
    steps_done = int(stopped.reason.split("after step ")[1].split(" ")[0])
    assert steps_done <= max_steps, stopped.reason  # the step in progress, no more
    held = task.settled_state().base
    assert np.linalg.norm(task.settled_state(samples=25).base - held) < 2e-3
    assert np.linalg.norm(held - start) < 0.1 * (steps_done + 1)
    return stopped


def test_a_burst_of_approvals_answers_one_request(task):
    """Issue #12: of 100 'approve' two took effect, the second approving an unseen plan."""
    start = task.settled_state()
    for _ in range(100):
        task.publish("OPERATOR", "approve 1")
    assert task.wait(lambda: any(r.startswith("WALK_TO_DOOR #2") for r in task.requests), 30.0)
    for _ in range(20):  # late approvals of the door
        task.publish("OPERATOR", "approve 1")
    assert task.wait(lambda: task.fsm.log.read_text().count("'approve 1' refused") >= 100, 30.0)
    task.assert_lives(task.fsm, "fsm_supervisor")
    assert task.sent_plans == []  # the plan awaits its own approval: nothing was executed
    joints, base, door = task.settled_state().moved(start)
    assert base < STILL_BASE and joints < 3e-3 and door < 1e-3


GARBAGE = ["", " ", "approve", "approve -1", "approve 1.0", "approve 99", "approve 1 2", "APPROVE #1", "pause 1",
           "résumé", "\n\n", "abort now", "x" * 100_000, "reject", "repeat 0", "approve 0x1", "☃ 1"]


def test_garbage_from_the_operator_changes_nothing(task):
    start = task.settled_state()
    states = len(task.states)
    for text in GARBAGE:
        task.publish("OPERATOR", text)
    count = _approve(task, 1)  # commands are handled in order: this one comes after all of them
    assert task.wait(lambda: len(task.requests) > count, 30.0), task.fsm.log.read_text()[-3000:]
    assert task.states[states:] == ["WALK_TO_DOOR"]  # no pause, repeat or abort happened
    assert task.requests[-1].startswith("WALK_TO_DOOR #2")
    task.assert_lives(task.fsm, "fsm_supervisor")
    joints, base, door = task.settled_state().moved(start)
    assert base < STILL_BASE and joints < 3e-3 and door < 1e-3


def test_pause_stops_the_walk(task):
    start = _walking(task)
    task.publish("OPERATOR", "pause")
    _stopped_walk(task, start, max_steps=8)  # the stop's latency, the step in the air and the one beside it
    assert task.wait(lambda: task.states[-1] == "PAUSED", 10.0)


def test_abort_holds_the_arm(task):
    task.planners.steps = 2
    _walking(task)
    assert task.wait(lambda: any(isinstance(r, MotionRequest) for r in task.planners.requests), 30.0), \
        task.fsm.log.read_text()[-2000:]
    elbow = task.settled_state().joints[ELBOW]
    assert task.wait(lambda: abs(task.joints[ELBOW] - elbow) > 0.05, 30.0)
    task.publish("OPERATOR", "abort")
    assert task.wait(lambda: task.states[-1] == "FAILED", 10.0)
    assert task.wait(lambda: any(o.status is OutcomeStatus.STOPPED and o.kind.value == "trajectory"
                                 for o in task.outcomes["execution"]), 10.0), task.outcomes["execution"]
    held = task.settled_state(samples=10).joints[ELBOW]
    assert abs(task.settled_state(samples=25).joints[ELBOW] - held) < 5e-3
    assert abs(held - (elbow - 0.5)) > 0.15  # it stopped well short of the trajectory's end


def test_a_lost_required_node_stops_the_walk(task):
    start = _walking(task)
    task.planners.destroy()  # the planner node is gone
    task.planners.destroy = lambda: None
    assert task.wait(lambda: task.states[-1] == "FAILED", 20.0), task.fsm.log.read_text()[-2000:]
    _stopped_walk(task, start, max_steps=10)  # the graph notices a lost node within ~1 s (4 sim s)
    assert f"/{PLANNER} is gone" in task.fsm.log.read_text()


def test_a_killed_supervisor_stops_the_walk_through_the_dead_man(task):
    start = _walking(task)
    task.fsm.send_signal(signal.SIGKILL)
    task.fsm.wait(timeout=10)
    stopped = _stopped_walk(task, start, max_steps=14)  # 3 s of silence (~12 sim s), then the stance
    assert "dead-man" in stopped.reason
