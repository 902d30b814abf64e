"""The ROS-free pieces under the supervisor node: graph watching, answers → events, the work
of a proposal, the requests built from the door context."""

from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from door_contract.payloads import ExecutionKind, ExecutionOutcome, OutcomeStatus, PlanningOutcome
from door_contract.vocabulary import DoorOpening
from door_fsm import actions as act
from door_fsm import events as ev
from door_fsm.answers import execution_event, planning_event
from door_fsm.door_context import DoorContext
from door_fsm.graph_watch import GraphWatch
from door_fsm.summaries import work_of


def test_the_task_starts_when_the_required_nodes_are_up_or_after_the_timeout():
    watch = GraphWatch({"a", "b"}, start_at=1.0, graph_timeout=5.0)
    assert watch.step(0.5, {"a", "b"}).start is False  # before start_delay
    assert "waiting for b" in watch.step(2.0, {"a"}).message
    step = watch.step(6.5, {"a"})
    assert step.start and "starting without b" in step.warning
    assert watch.step(7.0, {"a", "b"}).lost == ()
    assert watch.step(8.0, {"b"}).lost == ("a",)
    assert watch.step(9.0, {"b"}).lost == ()  # reported once


def test_execution_answers_become_events():
    fell = execution_event(ExecutionOutcome(ExecutionKind.FOOTSTEPS, 5, OutcomeStatus.FELL, "base 0.3 m high"), 9)
    assert fell == ev.ExecutionFinished(9, False, "base 0.3 m high", fell=True)
    stopped = execution_event(ExecutionOutcome(ExecutionKind.TRAJECTORY, 5, OutcomeStatus.STOPPED, "dead-man"), 9)
    assert not stopped.succeeded and not stopped.fell and "stopped: dead-man" in stopped.reason
    slip = execution_event(ExecutionOutcome(ExecutionKind.TRAJECTORY, 5, OutcomeStatus.FAILURE, "slip", slipped=True), 9)
    assert isinstance(slip, ev.HandSlipped)


def test_planning_answers_become_events_a_skip_its_own():
    """A planner's SKIPPED (a narrow push door's doorway walk) is a skip with its reason, not a
    failure; any other status but success is a failure naming the status."""
    skipped = PlanningOutcome(4, OutcomeStatus.SKIPPED, "0.84 m wide: no doorway walk")
    assert planning_event(skipped) == ev.ProposalSkipped(4, "0.84 m wide: no doorway walk")
    rejected = PlanningOutcome(5, OutcomeStatus.REJECTED, "no valid odometry yet")
    assert planning_event(rejected) == ev.ProposalFailed(5, "rejected: no valid odometry yet")


def test_the_work_of_a_proposal():
    trajectory = JointTrajectory(points=[JointTrajectoryPoint(), JointTrajectoryPoint()])
    trajectory.points[-1].time_from_start.sec, trajectory.points[-1].time_from_start.nanosec = 3, 500_000_000
    assert work_of(trajectory, 1.0) == 3.5
    assert work_of(Path(poses=[PoseStamped() for _ in range(40)]), 0.8) == 32.0
    assert work_of(JointTrajectory(), 1.0) == 0.0


def test_requests_carry_the_attempt_and_the_approved_door():
    context = DoorContext(DoorOpening.PULL, "chomp")
    request = context.motion_request(act.RequestMotion(7, "pull_door", attempt=2))
    assert (request.attempt, request.backend, request.opening, request.door_stamp) == (2, "chomp", "pull", -1.0)
    assert context.footstep_request(act.RequestFootsteps(8, "through", attempt=1)).attempt == 1
