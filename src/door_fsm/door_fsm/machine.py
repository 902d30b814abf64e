"""The door task's state machine: events in, actions out, no ROS and no clock of its own.

Each active state works in phases (:class:`~door_fsm.states.Phase`): PLANNING (a request
is out, answered by a proposal or a failure), AWAITING_APPROVAL (only when the autonomy
level makes this proposal wait for the operator), EXECUTING (the robot acts). Answers are
matched by request id, so a stale answer (from before a repeat or a pause) is ignored, and
an operator's ``approve N`` applies only while request N awaits approval.

Failures and timeouts repeat the state up to ``max_repeats`` (every repeat is a new request
with ``attempt`` + 1, planned from the measured state); a slipped hand goes back to
MOVE_TO_HANDLE; a fall fails the task at once. Leaving a phase early cancels its planner
request or stops its motion; PAUSED, MANUAL and FAILED always stop all motion. Deadlines:
planning and approval on the wall clock, execution on the robot clock, scaled with the work
(``work_s`` × ``execution_factor`` + ``execution_margin_s``); see :mod:`door_fsm.records`.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass

from door_contract.payloads import StateAttempt
from door_contract.vocabulary import Autonomy, DoorOpening, Motion, TaskState, WalkGoal
from door_fsm import actions as act
from door_fsm import events as ev
from door_fsm.approvals import approval_text, refusal
from door_fsm.errors import DoorFsmError
from door_fsm.operator_commands import OperatorCommand, OperatorWord
from door_fsm.records import PHASE_CLOCK, Clock, Deadline, Instant, StateRecord
from door_fsm.states import Phase, StateOutcome
from door_fsm.wiring import build_wiring
from door_fsm.work import STATE_WORK, StateWork, WorkKind

__all__ = ["DoorTaskMachine", "MachineOptions", "MachineOptionsError"]

SUSPENDED = {OperatorCommand.PAUSE: TaskState.PAUSED, OperatorCommand.STOP: TaskState.PAUSED,
             OperatorCommand.MANUAL: TaskState.MANUAL}


class MachineOptionsError(DoorFsmError):
    """Options the machine cannot run with; the message names the option."""


@dataclass(frozen=True)
class MachineOptions:
    opening: DoorOpening = DoorOpening.PUSH
    autonomy: Autonomy = Autonomy.SUPERVISED
    planning_timeout_s: float = 60.0    # wall clock, per attempt (detection included)
    approval_timeout_s: float = 120.0   # wall clock: operator silence
    execution_factor: float = 2.0       # execution deadline = work_s × factor + margin (robot clock)
    execution_margin_s: float = 10.0
    max_repeats: int = 3                # automatic repeats of a failed state (and slips)

    def __post_init__(self) -> None:
        if not (self.planning_timeout_s > 0 and self.approval_timeout_s > 0 and self.execution_margin_s > 0):
            raise MachineOptionsError("timeouts must be > 0 s")
        if self.execution_factor < 1.0:
            raise MachineOptionsError("execution_factor must be ≥ 1 (an execution needs its own duration)")
        if self.max_repeats < 0:
            raise MachineOptionsError("max_repeats must be ≥ 0")


class DoorTaskMachine:
    def __init__(self, options: MachineOptions) -> None:
        self.options = options
        self.wiring = build_wiring(options.opening)
        self.state = TaskState.DETECT_DOOR
        self.phase: Phase | None = None
        self.records: list[StateRecord] = []
        self.failure_reason = ""
        self._request_id = 0
        self._deadline: Deadline | None = None
        self._phase_started = 0.0  # on PHASE_CLOCK[self.phase]
        self._work_s = 0.0  # nominal duration of the proposal awaiting execution (robot s)
        self._repeats: Counter[TaskState] = Counter()
        self._slips = 0
        self._resume_to: TaskState | None = None

    # ------------------------------------------------------------------ public interface
    @property
    def request_id(self) -> int:
        """Id of the request the current state waits on."""
        return self._request_id

    @property
    def work(self) -> StateWork | None:
        return STATE_WORK.get(self.state)

    @property
    def _active_work(self) -> StateWork:
        """The work of the active state (planning, approval and execution have one)."""
        work = self.work
        if work is None:
            raise RuntimeError(f"state {self.state.value} has no work: not an active state")
        return work

    def start(self, now: Instant) -> list[act.Action]:
        return self._enter(TaskState.DETECT_DOOR, now)

    def handle(self, event: ev.Event, now: Instant) -> list[act.Action]:
        return _one_stop(self._handle(event, now))

    def tick(self, now: Instant) -> list[act.Action]:
        """Check the current phase's deadline (on the phase's clock)."""
        return _one_stop(self._tick(now))

    def report(self) -> list[StateAttempt]:
        """Every state attempt so far (the TaskReport's ``attempts``)."""
        return [record.as_state_attempt() for record in self.records]

    def _handle(self, event: ev.Event, now: Instant) -> list[act.Action]:
        if self.state.is_terminal:
            return [act.Notice(f"task is {self.state.value}; {type(event).__name__} ignored")]
        if isinstance(event, ev.OperatorSaid):
            return self._on_operator(event.word, now)
        if isinstance(event, ev.NodeLost):
            return self._terminal_failure(f"node /{event.node_name} is gone", now)
        if isinstance(event, ev.HandSlipped):
            return self._on_slip(event.reason, now)
        if getattr(event, "request_id", None) != self._request_id:
            return []  # stale answer to an earlier request
        if isinstance(event, ev.ProposalReady) and self.phase is Phase.PLANNING:
            return self._on_proposal(event, now)
        if isinstance(event, ev.ProposalFailed) and self.phase is Phase.PLANNING:
            return self._retry(f"planning failed: {event.reason}", now)
        if isinstance(event, ev.ProposalSkipped) and self.phase is Phase.PLANNING:
            return self._on_skip(event.reason, now)
        if isinstance(event, ev.GraspAnswered) and self.work and self.work.kind is WorkKind.GRASP:
            return self._on_grasp(event, now)
        if isinstance(event, ev.ExecutionFinished) and self.phase is Phase.EXECUTING:
            return self._on_execution(event, now)
        return []

    def _tick(self, now: Instant) -> list[act.Action]:
        if self._deadline is None or self.phase is None or self.state.is_terminal or not self._deadline.passed(now):
            return []
        if self.phase is Phase.AWAITING_APPROVAL:
            return self._finish(StateOutcome.TIMEOUT, now,
                                f"operator did not answer within {self.options.approval_timeout_s:g} s")
        reason = f"{self.phase.value} took longer than {self._deadline}"
        return self._leave_early(reason) + self._retry(reason, now, outcome=StateOutcome.TIMEOUT)

    # ------------------------------------------------------------------ state entry and exit
    def _enter(self, state: TaskState, now: Instant, reason: str = "") -> list[act.Action]:
        self.state, self.phase, self._deadline = state, None, None
        actions: list[act.Action] = [act.ClearApproval(), act.AnnounceState(state, reason)]
        if state in (TaskState.PAUSED, TaskState.MANUAL, TaskState.FAILED):
            actions.insert(0, act.StopMotion(f"{state.value}: {reason}" if reason else state.value))
        work = STATE_WORK.get(state)
        if work is None:  # DONE, FAILED, PAUSED, MANUAL: nothing to do until told
            return actions
        self._request_id += 1
        attempt = sum(1 for record in self.records if record.state is state)
        self.records.append(StateRecord(state, attempt + 1, now))
        self._begin_phase(Phase.PLANNING, now, self.options.planning_timeout_s)
        if work.release_first:
            self._request_id += 1  # the release's answer is not waited for
            actions.append(act.CallGrasp(self._request_id - 1, close=False))
        return actions + [self._request_for(work, attempt)]

    def _request_for(self, work: StateWork, attempt: int) -> act.Action:
        rid = self._request_id
        makers: dict[WorkKind, Callable[[], act.Action]] = {
                WorkKind.DETECTION: lambda: act.RequestDetection(rid),
                WorkKind.FOOTSTEPS: lambda: act.RequestFootsteps(rid, WalkGoal(str(work.target)), attempt),
                WorkKind.MOTION: lambda: act.RequestMotion(rid, Motion(str(work.target)), attempt),
                WorkKind.GRASP: lambda: act.CallGrasp(rid, close=True)}
        return makers[work.kind]()

    def _begin_phase(self, phase: Phase, now: Instant, timeout_s: float) -> None:
        self.phase = phase
        self._phase_started = now.on(PHASE_CLOCK[phase])
        self._deadline = Deadline.after(now, self._deadline_clock(phase), timeout_s)

    def _deadline_clock(self, phase: Phase) -> Clock:
        """The phase's own clock, but the robot's for planning the robot answers at its pace
        (detection: :attr:`~door_fsm.work.WorkKind.answered_in_robot_time`)."""
        if phase is Phase.PLANNING and self._active_work.kind.answered_in_robot_time:
            return Clock.ROBOT
        return PHASE_CLOCK[phase]

    def _close_phase(self, now: Instant) -> None:
        if self.phase is None or not self.records:
            return
        ended = now.on(PHASE_CLOCK[self.phase])
        self.records[-1].add(self.phase, ended - self._phase_started)
        self._phase_started = ended  # closing twice counts once: a detection finishes in the call that closed its planning

    def _leave_early(self, reason: str) -> list[act.Action]:
        """Leaving the phase before its answer: cancel its planner request, stop its motion."""
        work = self.work
        if work is None or self.phase is None:
            return []
        if self.phase is Phase.EXECUTING:
            return [act.StopMotion(reason)]
        if self.phase is Phase.PLANNING and work.kind in (WorkKind.FOOTSTEPS, WorkKind.MOTION):
            return [act.CancelPlanning(self._request_id, work.kind.planner, reason)]
        return []

    def _finish(self, outcome: StateOutcome, now: Instant, reason: str = "") -> list[act.Action]:
        self._close_phase(now)
        if self.records and self.records[-1].state is self.state:
            self.records[-1].conclude(outcome, reason, now)
        following = self.wiring[(self.state, outcome)]
        if outcome is StateOutcome.SLIPPED:
            self._slips += 1
            if self._slips > self.options.max_repeats:
                following, reason = TaskState.FAILED, f"{reason} (slipped {self._slips} times)"
        if following is TaskState.FAILED:
            self.failure_reason = f"{self.state.label}: {reason or outcome.value}"
        return self._enter(following, now, reason)

    def _terminal_failure(self, reason: str, now: Instant,
                          outcome: StateOutcome = StateOutcome.ABORTED) -> list[act.Action]:
        """Straight to FAILED (abort, lost node, fall), whatever the wiring says."""
        actions = self._leave_early(reason)
        self._close_phase(now)
        if self.work is not None and self.records:
            self.records[-1].conclude(outcome, reason, now)
        self.failure_reason = f"{self.state.label}: {reason}"
        return actions + self._enter(TaskState.FAILED, now, reason)

    def _retry(self, reason: str, now: Instant, outcome: StateOutcome = StateOutcome.FAILED) -> list[act.Action]:
        self._repeats[self.state] += 1
        if self._repeats[self.state] > self.options.max_repeats:
            return self._finish(outcome, now, f"{reason} (after {self.options.max_repeats} repeats)")
        self._close_phase(now)
        self.records[-1].conclude(outcome, reason, now)
        return self._enter(self.state, now, f"repeat {self._repeats[self.state]}: {reason}")

    # ------------------------------------------------------------------ answers
    def _on_proposal(self, event: ev.ProposalReady, now: Instant) -> list[act.Action]:
        self._close_phase(now)
        self.records[-1].summary = dict(event.summary)
        self._work_s = max(0.0, event.work_s)
        if self._needs_approval():
            self._begin_phase(Phase.AWAITING_APPROVAL, now, self.options.approval_timeout_s)
            return [act.AskApproval(self._request_id, approval_text(self.state.label, self._request_id, self._active_work,
                                                                    event.summary))]
        return self._execute(now)

    def _on_skip(self, reason: str, now: Instant) -> list[act.Action]:
        """Nothing to do here for this door: on past the state's part of the task (its
        :attr:`~door_fsm.work.StateWork.skip_to`), without approval — nothing moves. A state
        that cannot be skipped takes it as a planning failure."""
        if self._active_work.skip_to is None:
            return self._retry(f"planning failed: skipped, but {self.state.label} cannot be: {reason}", now)
        self.records[-1].summary = {"skipped": reason}
        return self._finish(StateOutcome.SKIPPED, now, reason)

    def _execute(self, now: Instant) -> list[act.Action]:
        work = self._active_work
        if work.kind is WorkKind.DETECTION:
            return self._finish(StateOutcome.SUCCEEDED, now)
        timeout = self._work_s * self.options.execution_factor + self.options.execution_margin_s
        self._begin_phase(Phase.EXECUTING, now, timeout)
        return [act.ClearApproval(), act.Execute(self._request_id, work.kind.planner)]

    def _on_execution(self, event: ev.ExecutionFinished, now: Instant) -> list[act.Action]:
        if event.fell:
            return self._terminal_failure(f"the robot fell: {event.reason}", now, StateOutcome.FELL)
        if event.succeeded:
            return self._finish(StateOutcome.SUCCEEDED, now)
        return self._retry(f"execution failed: {event.reason}", now)

    def _on_grasp(self, answer: ev.GraspAnswered, now: Instant) -> list[act.Action]:
        if answer.succeeded:
            return self._finish(StateOutcome.SUCCEEDED, now)
        self._repeats[self.state] += 1
        if self._repeats[self.state] > self.options.max_repeats:
            return self._finish(StateOutcome.FAILED, now, f"grasp failed: {answer.message}")
        return self._finish(StateOutcome.SLIPPED, now, f"grasp failed, re-approaching: {answer.message}")

    def _on_slip(self, reason: str, now: Instant) -> list[act.Action]:
        if not (self.work and self.work.holds_handle):
            return [act.Notice(f"slip reported in {self.state.label} ignored: hand not on the handle")]
        return self._leave_early(f"hand slipped: {reason}") + self._finish(StateOutcome.SLIPPED, now,
                                                                           f"hand slipped: {reason}")

    def _needs_approval(self) -> bool:
        level = self.options.autonomy
        return level is Autonomy.STEP or (level is Autonomy.SUPERVISED and self._active_work.critical)

    # ------------------------------------------------------------------ operator
    def _on_operator(self, word: OperatorWord, now: Instant) -> list[act.Action]:
        command = word.command
        if command is OperatorCommand.ABORT:
            return self._terminal_failure("aborted by the operator", now)
        if command in SUSPENDED:
            return self._suspend(SUSPENDED[command], f"{command.value} by the operator", now)
        if command is OperatorCommand.RESUME:
            if self._resume_to is None:
                return [act.Notice(f"nothing to resume in {self.state.label}")]
            state, self._resume_to = self._resume_to, None
            return self._enter(state, now, "resumed by the operator")
        refused = refusal(word, self.state.label, self.work, self._request_id, self.phase)
        if refused:
            return [act.Notice(refused)]
        if command is OperatorCommand.APPROVE:
            self._close_phase(now)
            return self._execute(now)
        # REJECT / REPEAT: plan this state again (an operator's repeat is not a failure)
        reason = f"{word} by the operator"
        actions = self._leave_early(reason)
        self._close_phase(now)
        self.records[-1].conclude(StateOutcome.FAILED, reason, now)
        return actions + self._enter(self.state, now, reason)

    def _suspend(self, target: TaskState, reason: str, now: Instant) -> list[act.Action]:
        if self.state is target:
            return [act.StopMotion(reason), act.Notice(f"already {target.value}")]
        actions = self._leave_early(reason)
        if self.work is not None:
            self._close_phase(now)
            self._resume_to = self.state
        return actions + self._enter(target, now, reason)


def _one_stop(actions: list[act.Action]) -> list[act.Action]:
    """``actions`` with only the first StopMotion (leaving a phase and entering FAILED both stop)."""
    stops = [i for i, a in enumerate(actions) if isinstance(a, act.StopMotion)]
    return [a for i, a in enumerate(actions) if i not in stops[1:]]
