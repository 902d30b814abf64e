"""The door task's state machine: events in, actions out, no ROS and no clock of its own.

Each active state works in phases (:class:`~door_fsm.states.Phase`): PLANNING (a request
is out, answered by a proposal or a failure), AWAITING_APPROVAL (only when the autonomy
level makes this proposal wait for the operator), EXECUTING (the robot acts). Answers are
matched by request id, so a stale answer (from before a repeat or a pause) is ignored.
Failures repeat the state up to ``max_repeats``; a slipped hand goes back to
MOVE_TO_HANDLE; every phase has a deadline, checked by :meth:`DoorTaskMachine.tick`.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field

from door_fsm import actions as act
from door_fsm import events as ev
from door_fsm.operator_commands import AutonomyLevel, OperatorCommand
from door_fsm.states import DoorOpening, Phase, StateOutcome, TaskState
from door_fsm.wiring import build_wiring
from door_fsm.work import STATE_WORK, StateWork, WorkKind


@dataclass(frozen=True)
class MachineOptions:
    opening: DoorOpening = DoorOpening.PUSH
    autonomy: AutonomyLevel = AutonomyLevel.SUPERVISED
    state_timeout_s: float = 60.0     # planning or executing, per attempt
    approval_timeout_s: float = 120.0  # operator silence
    max_repeats: int = 3               # automatic repeats of a failed state (and slips)

    def __post_init__(self) -> None:
        if not (self.state_timeout_s > 0 and self.approval_timeout_s > 0):
            raise ValueError("timeouts must be > 0 s")
        if self.max_repeats < 0:
            raise ValueError("max_repeats must be ≥ 0")


@dataclass
class StateRecord:
    """One attempt at one state, for the Table I report (times in seconds)."""

    state: TaskState
    attempt: int
    started: float
    outcome: StateOutcome | None = None
    planning_s: float = 0.0
    waiting_s: float = 0.0
    moving_s: float = 0.0
    reason: str = ""
    summary: dict = field(default_factory=dict)


class DoorTaskMachine:
    def __init__(self, options: MachineOptions) -> None:
        self.options = options
        self.wiring = build_wiring(options.opening)
        self.state = TaskState.DETECT_DOOR
        self.phase: Phase | None = None
        self.records: list[StateRecord] = []
        self.failure_reason = ""
        self._request_id = 0
        self._deadline: float | None = None
        self._phase_started = 0.0
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

    def start(self, now: float) -> list[act.Action]:
        return self._enter(TaskState.DETECT_DOOR, now)

    def handle(self, event: ev.Event, now: float) -> list[act.Action]:
        if self.state.is_terminal:
            return [act.Notice(f"task is {self.state.value}; {type(event).__name__} ignored")]
        if isinstance(event, ev.OperatorSaid):
            return self._on_operator(event.command, now)
        if isinstance(event, ev.NodeLost):
            return self._terminal_failure(f"node /{event.node_name} is gone", now)
        if isinstance(event, ev.HandSlipped):
            return self._on_slip(event.reason, now)
        if getattr(event, "request_id", None) != self._request_id:
            return []  # stale answer to an earlier request
        if isinstance(event, ev.ProposalReady) and self.phase is Phase.PLANNING:
            return self._on_proposal(event.summary, now)
        if isinstance(event, ev.ProposalFailed) and self.phase is Phase.PLANNING:
            return self._retry(f"planning failed: {event.reason}", now)
        if isinstance(event, ev.GraspAnswered) and self.work and self.work.kind is WorkKind.GRASP:
            return self._on_grasp(event, now)
        if isinstance(event, ev.ExecutionFinished) and self.phase is Phase.EXECUTING:
            if event.succeeded:
                return self._finish(StateOutcome.SUCCEEDED, now)
            return self._retry(f"execution failed: {event.reason}", now)
        return []

    def tick(self, now: float) -> list[act.Action]:
        """Check the current phase's deadline."""
        if self._deadline is None or now <= self._deadline or self.state.is_terminal:
            return []
        if self.phase is Phase.AWAITING_APPROVAL:
            reason = f"operator did not answer within {self.options.approval_timeout_s:g} s"
        else:
            reason = f"{self.phase.value} took longer than {self.options.state_timeout_s:g} s"
        return self._finish(StateOutcome.TIMEOUT, now, reason)

    def report(self) -> list[dict]:
        """Every state attempt so far, as plain dicts (the TaskReport's ``attempts``)."""
        return [{"state": r.state.label, "attempt": r.attempt,
                 "outcome": r.outcome.value if r.outcome else "unfinished",
                 "planning_s": round(r.planning_s, 4), "waiting_s": round(r.waiting_s, 4),
                 "moving_s": round(r.moving_s, 4), "reason": r.reason, "summary": r.summary}
                for r in self.records]

    # ------------------------------------------------------------------ state entry and exit
    def _enter(self, state: TaskState, now: float, reason: str = "") -> list[act.Action]:
        self.state, self.phase, self._deadline = state, None, None
        actions: list[act.Action] = [act.ClearApproval(), act.AnnounceState(state.label, reason)]
        work = STATE_WORK.get(state)
        if work is None:  # DONE, FAILED, PAUSED, MANUAL: nothing to do until told
            return actions
        self._request_id += 1
        self.records.append(StateRecord(state, self._repeats[state] + 1, now))
        self._begin_phase(Phase.PLANNING, now, self.options.state_timeout_s)
        if work.release_first:
            self._request_id += 1  # the release's answer is not waited for
            actions.append(act.CallGrasp(self._request_id - 1, close=False))
        return actions + [self._request_for(work)]

    def _request_for(self, work: StateWork) -> act.Action:
        rid = self._request_id
        return {WorkKind.DETECTION: lambda: act.RequestDetection(rid),
                WorkKind.FOOTSTEPS: lambda: act.RequestFootsteps(rid, work.target),
                WorkKind.MOTION: lambda: act.RequestMotion(rid, work.target),
                WorkKind.GRASP: lambda: act.CallGrasp(rid, close=True)}[work.kind]()

    def _begin_phase(self, phase: Phase, now: float, timeout_s: float) -> None:
        self.phase, self._phase_started, self._deadline = phase, now, now + timeout_s

    def _close_phase(self, now: float) -> None:
        if self.phase is None or not self.records:
            return
        spent = now - self._phase_started
        record = self.records[-1]
        if self.phase is Phase.PLANNING:
            record.planning_s += spent
        elif self.phase is Phase.AWAITING_APPROVAL:
            record.waiting_s += spent
        else:
            record.moving_s += spent

    def _finish(self, outcome: StateOutcome, now: float, reason: str = "") -> list[act.Action]:
        self._close_phase(now)
        if self.records and self.records[-1].state is self.state:
            self.records[-1].outcome, self.records[-1].reason = outcome, reason
        following = self.wiring[(self.state, outcome)]
        if outcome is StateOutcome.SLIPPED:
            self._slips += 1
            if self._slips > self.options.max_repeats:
                following, reason = TaskState.FAILED, f"{reason} (slipped {self._slips} times)"
        if following is TaskState.FAILED:
            self.failure_reason = f"{self.state.label}: {reason or outcome.value}"
        return self._enter(following, now, reason)

    def _terminal_failure(self, reason: str, now: float) -> list[act.Action]:
        """Straight to FAILED (abort, lost node), whatever the wiring says."""
        self._close_phase(now)
        if self.work is not None and self.records:
            self.records[-1].outcome, self.records[-1].reason = StateOutcome.ABORTED, reason
        self.failure_reason = f"{self.state.label}: {reason}"
        return self._enter(TaskState.FAILED, now, reason)

    def _retry(self, reason: str, now: float) -> list[act.Action]:
        self._repeats[self.state] += 1
        if self._repeats[self.state] > self.options.max_repeats:
            return self._finish(StateOutcome.FAILED, now, f"{reason} (after {self.options.max_repeats} repeats)")
        self._close_phase(now)
        self.records[-1].outcome, self.records[-1].reason = StateOutcome.FAILED, reason
        return self._enter(self.state, now, f"repeat {self._repeats[self.state]}: {reason}")

    # ------------------------------------------------------------------ answers
    def _on_proposal(self, summary: dict, now: float) -> list[act.Action]:
        self._close_phase(now)
        self.records[-1].summary = dict(summary)
        if self._needs_approval():
            self._begin_phase(Phase.AWAITING_APPROVAL, now, self.options.approval_timeout_s)
            return [act.AskApproval(self._approval_text(summary))]
        return self._execute(now)

    def _execute(self, now: float) -> list[act.Action]:
        work = self.work
        if work.kind is WorkKind.DETECTION:
            return self._finish(StateOutcome.SUCCEEDED, now)
        self._begin_phase(Phase.EXECUTING, now, self.options.state_timeout_s)
        return [act.ClearApproval(), act.Execute(self._request_id, work.kind.value)]

    def _on_grasp(self, answer: ev.GraspAnswered, now: float) -> list[act.Action]:
        if answer.succeeded:
            return self._finish(StateOutcome.SUCCEEDED, now)
        self._repeats[self.state] += 1
        if self._repeats[self.state] > self.options.max_repeats:
            return self._finish(StateOutcome.FAILED, now, f"grasp failed: {answer.message}")
        return self._finish(StateOutcome.SLIPPED, now, f"grasp failed, re-approaching: {answer.message}")

    def _on_slip(self, reason: str, now: float) -> list[act.Action]:
        if not (self.work and self.work.holds_handle):
            return [act.Notice(f"slip reported in {self.state.label} ignored: hand not on the handle")]
        return self._finish(StateOutcome.SLIPPED, now, f"hand slipped: {reason}")

    def _needs_approval(self) -> bool:
        level = self.options.autonomy
        return level is AutonomyLevel.STEP or (level is AutonomyLevel.SUPERVISED and self.work.critical)

    def _approval_text(self, summary: dict) -> str:
        details = ", ".join(f"{k}={v}" for k, v in summary.items())
        return (f"{self.state.label} #{self._request_id}: approve {self.work.kind.value} "
                f"'{self.work.target}'? {details} | reply approve, reject, pause, abort or manual")

    # ------------------------------------------------------------------ operator
    def _on_operator(self, command: OperatorCommand, now: float) -> list[act.Action]:
        if command is OperatorCommand.ABORT:
            return self._terminal_failure("aborted by the operator", now)
        if command in (OperatorCommand.PAUSE, OperatorCommand.MANUAL):
            return self._suspend(TaskState.PAUSED if command is OperatorCommand.PAUSE else TaskState.MANUAL, now)
        if command is OperatorCommand.RESUME:
            if self._resume_to is None:
                return [act.Notice(f"nothing to resume in {self.state.label}")]
            state, self._resume_to = self._resume_to, None
            return self._enter(state, now, "resumed by the operator")
        if self.work is None:
            return [act.Notice(f"'{command.value}' ignored in {self.state.label}")]
        if command is OperatorCommand.APPROVE:
            if self.phase is not Phase.AWAITING_APPROVAL:
                return [act.Notice(f"nothing to approve in {self.state.label} ({self.phase.value})")]
            self._close_phase(now)
            return self._execute(now)
        # REJECT / REPEAT: plan this state again (an operator's repeat is not a failure)
        self._close_phase(now)
        self.records[-1].outcome, self.records[-1].reason = StateOutcome.FAILED, f"{command.value} by the operator"
        return self._enter(self.state, now, f"{command.value} by the operator")

    def _suspend(self, target: TaskState, now: float) -> list[act.Action]:
        if self.work is not None:
            self._close_phase(now)
            self._resume_to = self.state
        if self.state is target:
            return [act.Notice(f"already {target.value}")]
        return self._enter(target, now, "by the operator")
