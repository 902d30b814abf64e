"""The words every package of the door task shares: door opening, sides, walk goals.

ROS-free (standard library only), so the cores (footstep planner, trajectory optimiser,
detector, sim) import it without rclpy. Every enum is a :class:`~enum.StrEnum` whose values
are the spellings used in parameters, YAML and JSON payloads (``"push"``, ``"left"``,
``"stand"``): a member compares equal to its spelling, formats as it (``f"/{side}_hand"`` is
``/left_hand``) and :mod:`door_contract.payloads` decodes it.

Sides are **as seen by the robot facing forward** (REP-103: x forward, y left). For a door
that is the approach side facing the door, which is also left/right in the head camera's
image.
"""

from __future__ import annotations

from enum import StrEnum

__all__ = ["AttemptOutcome", "Autonomy", "Backend", "DetectionMode", "DoorOpening", "Foot", "HingeSide", "Motion",
           "PlannerKind", "Side", "TaskEnd", "WalkGoal", "grasp_hand"]


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
    """A pull door: along the wall and sideways into the doorway, the blocking hand on the
    leaf, to where that arm tucks before the door plane."""
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
    """A pull door's blocking arm to the walking posture, in the doorway."""

    @property
    def uses_other_arm(self) -> bool:
        """The blocking arm moves (the other one opened the door)."""
        return self in (Motion.BLOCK_DOOR, Motion.TUCK_ARM)

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
    """How the door task ended (``TaskReport.final_state``: the FSM's two terminal states)."""

    DONE = "DONE"
    FAILED = "FAILED"


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
    UNFINISHED = "unfinished"
