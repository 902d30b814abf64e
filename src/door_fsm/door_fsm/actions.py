"""Actions the machine asks the supervisor node to perform (publish, call, execute, stop)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from door_contract.vocabulary import Motion, PlannerKind, TaskState, WalkGoal

__all__ = ["Action", "AnnounceState", "AskApproval", "CallGrasp", "CancelPlanning", "ClearApproval", "EndLook",
           "Execute", "Look", "Notice", "RequestDetection", "RequestFootsteps", "RequestMotion", "StopMotion"]


@dataclass(frozen=True)
class RequestDetection:
    request_id: int


@dataclass(frozen=True)
class RequestFootsteps:
    request_id: int
    goal: WalkGoal
    attempt: int = 0  # 0 first try, +1 per repeat of the state


@dataclass(frozen=True)
class RequestMotion:
    request_id: int
    motion: Motion
    attempt: int = 0


@dataclass(frozen=True)
class CancelPlanning:
    """Tell the planner to drop ``request_id`` (it answers SUPERSEDED and proposes nothing)."""

    request_id: int
    kind: PlannerKind
    reason: str


@dataclass(frozen=True)
class StopMotion:
    """Stop every execution now: an empty JointTrajectory (the arm holds) and an empty
    footstep Path (the walk ends at the next stable stance), as ros2_control does."""

    reason: str


@dataclass(frozen=True)
class CallGrasp:
    request_id: int
    close: bool


@dataclass(frozen=True)
class Execute:
    """Send the approved proposal of ``request_id`` to the robot."""

    request_id: int
    kind: PlannerKind


@dataclass(frozen=True)
class Look:
    """Send the detector's neck move (a JointTrajectory) to the robot: DETECT_DOOR's head search."""

    trajectory: Any


@dataclass(frozen=True)
class EndLook:
    """The head search is over (the door is confirmed) or its next look replaces the last: stop
    the neck move if one still runs, with an empty JointTrajectory (the neck holds where it is),
    so the robot is free for the walk or the next look."""


@dataclass(frozen=True)
class AskApproval:
    request_id: int
    text: str


@dataclass(frozen=True)
class ClearApproval:
    pass


@dataclass(frozen=True)
class AnnounceState:
    """Publish the state the machine entered (its label on ``/door_task/state``)."""

    state: TaskState
    reason: str = ""


@dataclass(frozen=True)
class Notice:
    """Something the operator should read in the log (e.g. a refused command)."""

    text: str


Action = (RequestDetection | RequestFootsteps | RequestMotion | CancelPlanning | StopMotion | CallGrasp
          | Execute | Look | EndLook | AskApproval | ClearApproval | AnnounceState | Notice)
