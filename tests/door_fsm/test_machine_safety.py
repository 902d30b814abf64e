"""The FSM core's safety rules: answers name their request, stops stop, cancels cancel,
repeats change something, deadlines scale with the work on the right clock, falls end it."""

import pytest
from test_machine import Robot, _advance_to, _until_approval, say, t

from door_contract.vocabulary import Autonomy, TaskState
from door_fsm import actions as act
from door_fsm import events as ev
from door_fsm.machine import DoorTaskMachine, MachineOptions, MachineOptionsError
from door_fsm.operator_commands import OperatorCommand
from door_fsm.records import Instant
from door_fsm.states import Phase, StateOutcome


def _executing(state=TaskState.WALK_TO_DOOR, work_s=20.0):
    """A machine (full autonomy) whose ``state`` is executing a proposal of ``work_s`` seconds."""
    machine = DoorTaskMachine(MachineOptions(autonomy=Autonomy.FULL, execution_factor=2.0,
                                             execution_margin_s=5.0))
    _advance_to(machine, state)
    actions = machine.handle(ev.ProposalReady(machine.request_id, work_s=work_s), t(100.0))
    assert machine.phase is Phase.EXECUTING and any(isinstance(a, act.Execute) for a in actions)
    return machine


def test_a_burst_of_approvals_approves_one_request_only():
    """Issue #12: 100 'approve' took effect twice and approved a plan the operator never saw."""
    machine = DoorTaskMachine(MachineOptions())
    _until_approval(machine)
    detection = machine.request_id
    executed = [a for _ in range(100) for a in say(machine, OperatorCommand.APPROVE, detection)
                if not isinstance(a, act.Notice)]
    assert machine.state is TaskState.WALK_TO_DOOR and machine.phase is Phase.PLANNING
    machine.handle(ev.ProposalReady(machine.request_id, {"steps": 12}, 12.0), t(11.0))
    assert machine.phase is Phase.AWAITING_APPROVAL  # the plan waits: the old approvals do not apply
    refusal = say(machine, OperatorCommand.APPROVE, detection)
    assert machine.phase is Phase.AWAITING_APPROVAL and "refused" in refusal[0].text
    assert not any(isinstance(a, act.Execute) for a in executed)


@pytest.mark.parametrize("command", [OperatorCommand.APPROVE, OperatorCommand.REJECT, OperatorCommand.REPEAT])
def test_an_answer_for_another_id_changes_nothing(command):
    machine = DoorTaskMachine(MachineOptions())
    _until_approval(machine)
    before = (machine.state, machine.phase, machine.request_id, len(machine.records))
    for wrong in (machine.request_id - 1, machine.request_id + 1, 0, 10**9):
        actions = say(machine, command, wrong)
        assert len(actions) == 1 and isinstance(actions[0], act.Notice) and "refused" in actions[0].text
    assert (machine.state, machine.phase, machine.request_id, len(machine.records)) == before


def test_the_approval_request_shows_its_id():
    machine = DoorTaskMachine(MachineOptions())
    robot = _until_approval(machine)
    assert robot.approvals[-1].startswith(f"DETECT_DOOR #{machine.request_id}: ")
    assert f"'approve {machine.request_id}'" in robot.approvals[-1]


@pytest.mark.parametrize("command, state", [(OperatorCommand.PAUSE, TaskState.PAUSED),
                                            (OperatorCommand.STOP, TaskState.PAUSED),
                                            (OperatorCommand.ABORT, TaskState.FAILED),
                                            (OperatorCommand.MANUAL, TaskState.MANUAL)])
def test_pause_stop_abort_manual_stop_the_motion_at_once(command, state):
    machine = _executing()
    actions = say(machine, command)
    assert machine.state is state
    assert isinstance(actions[0], act.StopMotion)  # first, before anything is announced
    assert sum(isinstance(a, act.StopMotion) for a in actions) == 1


def test_a_lost_node_stops_the_motion():
    machine = _executing()
    actions = machine.handle(ev.NodeLost("footstep_planner"), t(101.0))
    assert machine.state is TaskState.FAILED and isinstance(actions[0], act.StopMotion)


def test_leaving_planning_cancels_the_planner_request():
    machine = DoorTaskMachine(MachineOptions(autonomy=Autonomy.FULL))
    _advance_to(machine, TaskState.WALK_TO_DOOR)
    planning = machine.request_id
    actions = say(machine, OperatorCommand.PAUSE)
    cancels = [a for a in actions if isinstance(a, act.CancelPlanning)]
    assert [(c.request_id, c.kind) for c in cancels] == [(planning, "footsteps")]


def test_execution_deadline_scales_with_the_work_on_the_robot_clock():
    machine = _executing(work_s=40.0)  # e.g. 40 steps of 1 s: deadline 40 × 2 + 5 = 85 s of robot time
    started = 100.0
    assert machine.tick(Instant(started + 10_000.0, started + 84.0)) == []  # wall time is irrelevant
    actions = machine.tick(Instant(started + 10_001.0, started + 86.0))
    assert isinstance(actions[0], act.StopMotion)
    assert machine.state is TaskState.WALK_TO_DOOR and machine.records[-2].outcome is StateOutcome.TIMEOUT
    assert "robot clock" in machine.records[-2].reason


def test_detection_times_out_on_the_robot_clock_and_repeats():
    """The detector answers at the robot's pace (camera frames, head moves): a loaded machine
    slows the simulation, and 60 s of wall clock once nearly cut a head search short (56 s)."""
    machine = DoorTaskMachine(MachineOptions(planning_timeout_s=60.0))
    machine.start(t(0.0))
    assert machine.tick(Instant(10_000.0, 59.0)) == []  # the wall clock does not bound detection
    actions = machine.tick(Instant(10_001.0, 61.0))
    assert machine.state is TaskState.DETECT_DOOR and machine.records[-2].outcome is StateOutcome.TIMEOUT
    assert "took longer than 60.0 s (robot clock)" in machine.records[-2].reason
    assert any(isinstance(a, act.RequestDetection) and a.request_id == machine.request_id for a in actions)


def test_a_planner_times_out_on_the_wall_clock():
    """Planners compute in real time: the robot clock does not bound a footstep plan."""
    machine = DoorTaskMachine(MachineOptions(planning_timeout_s=60.0, autonomy=Autonomy.FULL))
    robot = Robot(machine)
    pending = machine.start(t(0.0))
    while machine.state is not TaskState.WALK_TO_DOOR:
        pending = pending[1:] + robot.answer(pending[0])
    assert machine.tick(Instant(59.0, 10_000.0)) == []
    machine.tick(Instant(61.0, 10_001.0))
    assert machine.records[-2].state is TaskState.WALK_TO_DOOR
    assert machine.records[-2].outcome is StateOutcome.TIMEOUT and "(wall clock)" in machine.records[-2].reason


def test_repeats_carry_growing_attempts_and_never_resend_a_request():
    machine = DoorTaskMachine(MachineOptions(autonomy=Autonomy.FULL, max_repeats=3))
    robot = Robot(machine)
    pending = machine.start(t(0.0))
    while machine.state is not TaskState.WALK_TO_DOOR:
        pending = pending[1:] + robot.answer(pending[0])
    requests = [a for a in pending if isinstance(a, act.RequestFootsteps)]
    for _ in range(3):
        actions = machine.handle(ev.ProposalFailed(machine.request_id, "expansion budget spent"), t(20.0))
        requests += [a for a in actions if isinstance(a, act.RequestFootsteps)]
    assert [r.attempt for r in requests] == [0, 1, 2, 3]
    assert len({r.request_id for r in requests}) == 4


def test_operator_repeat_also_counts_as_an_attempt():
    machine = DoorTaskMachine(MachineOptions(autonomy=Autonomy.SUPERVISED))
    robot = Robot(machine, approve=False)
    robot.run(machine.start(t(0.0)))
    say(machine, OperatorCommand.APPROVE)  # the door
    robot.run([])
    actions = say(machine, OperatorCommand.REPEAT)
    repeat = next(a for a in actions if isinstance(a, act.RequestFootsteps))
    assert repeat.attempt == 1


def test_a_fall_fails_the_task_without_repeat():
    machine = _executing(TaskState.WALK_THROUGH)
    machine.handle(ev.ExecutionFinished(machine.request_id, False, "fell: base 0.4 m high", fell=True), t(101.0))
    assert machine.state is TaskState.FAILED and "the robot fell" in machine.failure_reason
    assert machine.records[-1].outcome is StateOutcome.FELL


def test_stop_while_paused_stops_again():
    machine = _executing()
    say(machine, OperatorCommand.PAUSE)
    actions = say(machine, OperatorCommand.STOP)
    assert isinstance(actions[0], act.StopMotion) and machine.state is TaskState.PAUSED


def test_options_are_validated():
    with pytest.raises(MachineOptionsError, match="execution_factor"):
        MachineOptions(execution_factor=0.5)
    with pytest.raises(MachineOptionsError, match="timeouts"):
        MachineOptions(planning_timeout_s=0.0)
