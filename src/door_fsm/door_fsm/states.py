"""The FSM's own words for where a state is in its work and how it ended.

The task's states themselves (:class:`~door_contract.vocabulary.TaskState`, [Banerjee 2015]
Fig. 3) belong to the message contract: ``/door_task/state`` publishes their labels and the
TaskReport lists them.
"""

from __future__ import annotations

from enum import Enum

__all__ = ["Phase", "StateOutcome"]


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
    SKIPPED = "skipped"          # the planner has nothing to do for this door: the wiring goes past the state's part
