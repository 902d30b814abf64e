"""States, phases and outcomes of the door task ([Banerjee 2015], Fig. 3).

DETECT_DOOR → WALK_TO_DOOR → OPEN_DOOR [MOVE_TO_HANDLE → GRASP → TURN_HANDLE → PUSH or PULL
→ BLOCK (pull doors) → READY_TO_WALK] → WALK_THROUGH → DONE, plus PAUSED, MANUAL and FAILED.
A pull door's WALK_THROUGH walks in two parts around an arm motion: [TO_DOORWAY → TUCK] →
WALK_THROUGH (:mod:`footstep_planner.pull_passage` says why).
"""

from __future__ import annotations

from enum import Enum


class TaskState(str, Enum):
    DETECT_DOOR = "DETECT_DOOR"
    WALK_TO_DOOR = "WALK_TO_DOOR"
    MOVE_TO_HANDLE = "MOVE_TO_HANDLE"
    GRASP = "GRASP"
    TURN_HANDLE = "TURN_HANDLE"
    PUSH = "PUSH"
    PULL = "PULL"
    BLOCK = "BLOCK"
    READY_TO_WALK = "READY_TO_WALK"
    TO_DOORWAY = "TO_DOORWAY"
    TUCK = "TUCK"
    WALK_THROUGH = "WALK_THROUGH"
    DONE = "DONE"
    PAUSED = "PAUSED"
    MANUAL = "MANUAL"
    FAILED = "FAILED"

    @property
    def is_terminal(self) -> bool:
        return self in (TaskState.DONE, TaskState.FAILED)

    @property
    def is_open_door_substate(self) -> bool:
        return self in OPEN_DOOR_SUBSTATES

    @property
    def is_walk_through_substate(self) -> bool:
        return self in WALK_THROUGH_SUBSTATES

    @property
    def label(self) -> str:
        """``OPEN_DOOR/TURN_HANDLE`` and ``WALK_THROUGH/TUCK`` for sub-states, the plain name otherwise."""
        if self.is_open_door_substate:
            return f"OPEN_DOOR/{self.value}"
        return f"WALK_THROUGH/{self.value}" if self.is_walk_through_substate else self.value


OPEN_DOOR_SUBSTATES = frozenset({TaskState.MOVE_TO_HANDLE, TaskState.GRASP, TaskState.TURN_HANDLE,
                                 TaskState.PUSH, TaskState.PULL, TaskState.BLOCK,
                                 TaskState.READY_TO_WALK})
WALK_THROUGH_SUBSTATES = frozenset({TaskState.TO_DOORWAY, TaskState.TUCK})


class Phase(str, Enum):
    """Where an active state is in its work: ask a planner, wait for the operator, act."""

    PLANNING = "planning"
    AWAITING_APPROVAL = "awaiting_approval"
    EXECUTING = "executing"


class StateOutcome(str, Enum):
    """How a state ended; the wiring maps (state, outcome) to the next state."""

    SUCCEEDED = "succeeded"
    FAILED = "failed"            # planner or execution failure (after the repeat limit)
    SLIPPED = "slipped"          # the hand slipped off the handle: redo from MOVE_TO_HANDLE
    TIMEOUT = "timeout"
    ABORTED = "aborted"
    FELL = "fell"                # the robot fell: the task ends FAILED, nothing repeats
