"""The FSM's transitions: (state, outcome) → next state, built per door and validated.

Validation (run when the supervisor starts) checks that every outcome every reachable
state declares is routed, and that DONE is reachable from DETECT_DOOR — a mis-wired
machine is refused before it moves the robot.
"""

from __future__ import annotations

from collections import deque

from door_contract.vocabulary import DoorOpening, TaskState
from door_fsm.errors import DoorFsmError
from door_fsm.states import StateOutcome
from door_fsm.work import STATE_WORK

__all__ = ["Wiring", "WiringError", "build_wiring", "success_sequence", "validate_wiring"]

Wiring = dict[tuple[TaskState, StateOutcome], TaskState]


class WiringError(DoorFsmError):
    """A wiring with an unrouted outcome, a state without work, or no way to DONE."""


def success_sequence(opening: DoorOpening) -> tuple[TaskState, ...]:
    """The states a successful run visits, in order (Fig. 3), when every planner has work for
    each: the robot walks to the doorway and tucks the arm on the leaf before it walks through
    (a pull door's blocking arm, a wide push door's pushing arm). A narrow push door's doorway
    walk is SKIPPED, straight on to WALK_THROUGH (:attr:`~door_fsm.work.StateWork.skip_to`)."""
    middle = (TaskState.PUSH,) if opening is DoorOpening.PUSH else (TaskState.PULL, TaskState.BLOCK)
    return (TaskState.DETECT_DOOR, TaskState.WALK_TO_DOOR, TaskState.MOVE_TO_HANDLE, TaskState.GRASP,
            TaskState.TURN_HANDLE, *middle, TaskState.READY_TO_WALK, TaskState.TO_DOORWAY, TaskState.TUCK,
            TaskState.WALK_THROUGH, TaskState.DONE)


def build_wiring(opening: DoorOpening) -> Wiring:
    sequence = success_sequence(opening)
    wiring: Wiring = {}
    for state, following in zip(sequence, sequence[1:]):
        wiring[(state, StateOutcome.SUCCEEDED)] = following
        work = STATE_WORK[state]
        if work.skip_to is not None:
            wiring[(state, StateOutcome.SKIPPED)] = work.skip_to
        for outcome in work.outcomes - {StateOutcome.SUCCEEDED, StateOutcome.SKIPPED}:
            wiring[(state, outcome)] = (TaskState.MOVE_TO_HANDLE if outcome is StateOutcome.SLIPPED
                                        else TaskState.FAILED)
    validate_wiring(wiring, sequence)
    return wiring


def validate_wiring(wiring: Wiring, sequence: tuple[TaskState, ...]) -> None:
    """Raise :class:`WiringError` when an outcome is unrouted or DONE is unreachable."""
    for state in _reachable(wiring, sequence[0]):
        if state.is_terminal:
            continue
        if state not in STATE_WORK:
            raise WiringError(f"{state.value} has no work defined")
        missing = [o.value for o in STATE_WORK[state].outcomes if (state, o) not in wiring]
        if missing:
            raise WiringError(f"{state.value}: outcome(s) {', '.join(sorted(missing))} are not wired")
    if TaskState.DONE not in _reachable(wiring, sequence[0]):
        raise WiringError("DONE is not reachable from DETECT_DOOR")


def _reachable(wiring: Wiring, start: TaskState) -> set[TaskState]:
    seen, queue = {start}, deque([start])
    while queue:
        state = queue.popleft()
        for (source, _), target in wiring.items():
            if source is state and target not in seen:
                seen.add(target)
                queue.append(target)
    return seen
