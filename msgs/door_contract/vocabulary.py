"""The words every package of the door task shares: door opening, sides, walk goals, the task's states.

ROS-free (standard library only), so the cores (footstep planner, trajectory optimiser,
detector, sim) import it without rclpy. Every enum but :class:`TaskState` is a
:class:`~enum.StrEnum` whose values are the spellings used in parameters, YAML and JSON
payloads (``"push"``, ``"left"``, ``"stand"``): a member compares equal to its spelling,
formats as it (``f"/{side}_hand"`` is ``/left_hand``) and :mod:`door_contract.payloads`
decodes it. A task state is spelled by its :attr:`~TaskState.label`, which is not its value
(``OPEN_DOOR/TURN_HANDLE``), so it is a plain Enum: it equals no string at all.

Sides are **as seen by the robot facing forward** (REP-103: x forward, y left). For a door
that is the approach side facing the door, which is also left/right in the head camera's
image.
"""

from __future__ import annotations

from enum import Enum, StrEnum

from door_contract.errors import ContractError

__all__ = ["OPEN_DOOR_SUBSTATES", "WALK_THROUGH_SUBSTATES", "AttemptOutcome", "Autonomy", "Backend", "DetectionMode",
           "DoorOpening", "Foot", "HingeSide", "Motion", "PlannerKind", "Side", "TaskEnd", "TaskState", "WalkGoal",
           "grasp_hand"]


class DoorOpening(StrEnum):
    """Which way the leaf swings, seen from the approach side."""

    PUSH = "push"
    """Away from the robot."""
    PULL = "pull"
    """Towards the robot."""


class Side(StrEnum):
    """Left or right as seen by the robot facing forward (or facing the door)."""

    LEFT = "left"
    RIGHT = "right"

    @property
    def other(self) -> Side:
        """The opposite side (for a hinge: the handle's side)."""
        return Side.RIGHT if self is Side.LEFT else Side.LEFT

    @property
    def sign(self) -> float:
        """+1 for LEFT (REP-103 +y, where the left foot and hand are), -1 for RIGHT."""
        return 1.0 if self is Side.LEFT else -1.0


Foot = Side
"""Which foot a footstep belongs to: a :class:`Side` (the feet are keyed by side)."""

HingeSide = Side
"""The side of the door's hinges, seen from the approach side facing the door: a :class:`Side`."""


def grasp_hand(hinge_side: Side, opening: DoorOpening) -> Side:
    """The hand that opens the door.

    Push doors: the hand on the handle's side (opposite the hinge). Pull doors: the robot
    stands beyond the latch edge, outside the leaf's sweep, so the handle is on its hinge side
    and that hand reaches it.
    """
    return hinge_side.other if DoorOpening(opening) is DoorOpening.PUSH else hinge_side


class WalkGoal(StrEnum):
    """What a footstep request plans to (``FootstepRequest.goal``)."""

    STAND = "stand"
    """The stand pose in front of the door, from which the arm opens it."""
    DOORWAY = "doorway"
    """Into the doorway, to where the arm on the leaf tucks: a pull door's along the wall and
    sideways, the blocking hand on the leaf, to before the door plane; a wide push door's
    side-steps, the pushing hand on the leaf, to just past it. A door walked through in one
    go has none: its planner answers SKIPPED."""
    THROUGH = "through"
    """Through the open doorway, past the door plane (a pull door: on from the doorway)."""


class Motion(StrEnum):
    """A motion of the door motion library (``MotionRequest.motion``; [Banerjee 2015] Sec. IV)."""

    APPROACH_HANDLE = "approach_handle"
    TURN_HANDLE = "turn_handle"
    PUSH_DOOR = "push_door"
    PULL_DOOR = "pull_door"
    BLOCK_DOOR = "block_door"
    READY_TO_WALK = "ready_to_walk"
    TUCK_ARM = "tuck_arm"
    """The arm on the leaf to the walking posture, in the doorway: a pull door's blocking arm,
    a push door's pushing arm."""

    def moves_other_arm(self, opening: DoorOpening) -> bool:
        """Whether the arm that did not open the door moves: a pull door's blocking arm
        (blocking, tucking); a push door's tuck moves the arm that pushed it."""
        return self is Motion.BLOCK_DOOR or (self is Motion.TUCK_ARM and opening is DoorOpening.PULL)

    @property
    def holds_handle(self) -> bool:
        """The hand is locked on the handle throughout (closed kinematic chain)."""
        return self in (Motion.TURN_HANDLE, Motion.PUSH_DOOR, Motion.PULL_DOOR)


class Backend(StrEnum):
    """The trajectory optimiser that plans a motion (``MotionRequest.backend``)."""

    SQP = "sqp"
    """TrajOpt-style sequential quadratic programming ([Banerjee 2015])."""
    CHOMP = "chomp"
    """Constrained CHOMP ([Zucker 2013] Sec. III)."""


class DetectionMode(StrEnum):
    """Which pipeline produced a door estimate (``DoorEstimate.mode``; [Banerjee 2015] Sec. III-A vs III-B)."""

    AUTOMATIC = "automatic"
    OPERATOR = "operator"
    """Operator-aided: from the operator's scribble on the handle."""


class Autonomy(StrEnum):
    """Which proposals wait for the operator (as FlexBE's autonomy levels; ``TaskReport.autonomy``)."""

    FULL = "full"
    """None."""
    SUPERVISED = "supervised"
    """The critical ones (door estimate, footstep plans, handle turn)."""
    STEP = "step"
    """Every proposal."""


class TaskEnd(StrEnum):
    """How the door task ended (``TaskReport.final_state``): the FSM's two terminal states
    (:attr:`TaskState.end`), spelled as their labels."""

    DONE = "DONE"
    FAILED = "FAILED"


class TaskState(Enum):
    """The door task's states ([Banerjee 2015], Fig. 3): what the FSM is in, what
    ``/door_task/state`` publishes (the :attr:`label`) and what ``StateAttempt.state`` names.

    DETECT_DOOR → WALK_TO_DOOR → OPEN_DOOR [MOVE_TO_HANDLE → GRASP → TURN_HANDLE → PUSH or PULL
    → BLOCK (pull doors) → READY_TO_WALK] → WALK_THROUGH → DONE, plus PAUSED, MANUAL and FAILED.
    A pull door's WALK_THROUGH walks in two parts around an arm motion: [TO_DOORWAY → TUCK] →
    WALK_THROUGH (:mod:`footstep_planner.pull_passage` says why), and so does a wide push door's
    (:mod:`footstep_planner.push_passage`); a narrow push door skips TO_DOORWAY and TUCK.

    Not a StrEnum: its spelling on the bus and in reports is the label, not the value, and a
    state that compared equal to ``"TURN_HANDLE"`` but not to ``"OPEN_DOOR/TURN_HANDLE"`` would
    make a comparison with a label silently false (mypy flags any comparison with a string).
    """

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
    def end(self) -> TaskEnd | None:
        """How the task ended, in a terminal state (DONE, FAILED); None in any other."""
        return _TASK_ENDS.get(self)

    @property
    def is_terminal(self) -> bool:
        return self.end is not None

    @property
    def is_open_door_substate(self) -> bool:
        return self in OPEN_DOOR_SUBSTATES

    @property
    def is_walk_through_substate(self) -> bool:
        return self in WALK_THROUGH_SUBSTATES

    @property
    def label(self) -> str:
        """``OPEN_DOOR/TURN_HANDLE`` and ``WALK_THROUGH/TUCK`` for sub-states (the phase first, as
        Table I groups them), the plain name otherwise: the state's spelling on ``/door_task/state``
        and in JSON payloads."""
        if self.is_open_door_substate:
            return f"OPEN_DOOR/{self.value}"
        return f"WALK_THROUGH/{self.value}" if self.is_walk_through_substate else self.value

    @classmethod
    def of_label(cls, text: str) -> TaskState:
        """The state whose :attr:`label` is ``text`` (a ``/door_task/state`` message, a report's
        ``state``); :class:`~door_contract.errors.ContractError` for any other text (a bare
        sub-state name such as ``TURN_HANDLE`` is not a label)."""
        state = _STATES_BY_LABEL.get(text)
        if state is None:
            raise ContractError(f"unknown task state {text!r}; use one of {', '.join(_STATES_BY_LABEL)}")
        return state


OPEN_DOOR_SUBSTATES = frozenset({TaskState.MOVE_TO_HANDLE, TaskState.GRASP, TaskState.TURN_HANDLE,
                                 TaskState.PUSH, TaskState.PULL, TaskState.BLOCK,
                                 TaskState.READY_TO_WALK})
WALK_THROUGH_SUBSTATES = frozenset({TaskState.TO_DOORWAY, TaskState.TUCK})
_TASK_ENDS = {TaskState.DONE: TaskEnd.DONE, TaskState.FAILED: TaskEnd.FAILED}
_STATES_BY_LABEL = {state.label: state for state in TaskState}


class PlannerKind(StrEnum):
    """Which planner a request goes to and a proposal comes from (its topics:
    :data:`door_contract.topics.PLANNER_TOPICS`)."""

    FOOTSTEPS = "footsteps"
    MOTION = "motion"


class AttemptOutcome(StrEnum):
    """How one state attempt of the task ended (``StateAttempt.outcome`` in the TaskReport): the
    spelling of the FSM's ``door_fsm.states.StateOutcome``, or unfinished (the task ended while
    the state was still at work)."""

    SUCCEEDED = "succeeded"
    FAILED = "failed"
    SLIPPED = "slipped"
    TIMEOUT = "timeout"
    ABORTED = "aborted"
    FELL = "fell"
    SKIPPED = "skipped"
    UNFINISHED = "unfinished"
