"""What each active state asks for, and which of its proposals are critical.

A state's work is: ask (detector, footstep planner, trajectory optimizer or the grasp
service), optionally wait for the operator's approval of the proposal, then execute it.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from door_contract.vocabulary import Motion, PlannerKind, TaskState, WalkGoal
from door_fsm.errors import DoorFsmError
from door_fsm.states import StateOutcome

__all__ = ["STATE_WORK", "StateWork", "WorkKind"]


class WorkKind(str, Enum):
    DETECTION = "detection"
    FOOTSTEPS = "footsteps"
    MOTION = "motion"
    GRASP = "grasp"

    @property
    def answered_in_robot_time(self) -> bool:
        """Whether the answer comes at the robot's pace: the detector confirms a door from camera
        frames and head moves, which come in robot time (a loaded machine slows the simulation,
        and a wall-clock deadline would cut a head search short); planners compute in real time."""
        return self is WorkKind.DETECTION

    @property
    def planner(self) -> PlannerKind:
        """The planner of footstep and motion work (its requests, proposals and cancels)."""
        planners = {WorkKind.FOOTSTEPS: PlannerKind.FOOTSTEPS, WorkKind.MOTION: PlannerKind.MOTION}
        if self not in planners:
            raise DoorFsmError(f"{self.value} work has no planner")
        return planners[self]


@dataclass(frozen=True)
class StateWork:
    kind: WorkKind
    target: WalkGoal | Motion | None  # what a footstep or motion request asks for (None: detection, grasp)
    critical: bool             # waits for approval under SUPERVISED autonomy
    holds_handle: bool = False  # the hand is on the handle: a slip can happen
    release_first: bool = False  # open the hand before planning (READY_TO_WALK)
    skip_to: TaskState | None = None  # where a planner's SKIPPED answer goes (None: it is a failure)

    @property
    def subject(self) -> str:
        """What the state asks for, as the operator reads it (``'turn_handle'``, ``'door'``)."""
        if self.target is not None:
            return str(self.target)
        return "door" if self.kind is WorkKind.DETECTION else "close"

    @property
    def outcomes(self) -> frozenset[StateOutcome]:
        """The outcomes this state can end with (the wiring must route every one)."""
        base = {StateOutcome.SUCCEEDED, StateOutcome.FAILED, StateOutcome.TIMEOUT, StateOutcome.ABORTED}
        if self.holds_handle or self.kind is WorkKind.GRASP:
            base.add(StateOutcome.SLIPPED)
        if self.skip_to is not None:
            base.add(StateOutcome.SKIPPED)
        return frozenset(base)


STATE_WORK: dict[TaskState, StateWork] = {
    TaskState.DETECT_DOOR: StateWork(WorkKind.DETECTION, None, critical=True),
    TaskState.WALK_TO_DOOR: StateWork(WorkKind.FOOTSTEPS, WalkGoal.STAND, critical=True),
    TaskState.MOVE_TO_HANDLE: StateWork(WorkKind.MOTION, Motion.APPROACH_HANDLE, critical=False),
    TaskState.GRASP: StateWork(WorkKind.GRASP, None, critical=False),
    TaskState.TURN_HANDLE: StateWork(WorkKind.MOTION, Motion.TURN_HANDLE, critical=True, holds_handle=True),
    TaskState.PUSH: StateWork(WorkKind.MOTION, Motion.PUSH_DOOR, critical=False, holds_handle=True),
    TaskState.PULL: StateWork(WorkKind.MOTION, Motion.PULL_DOOR, critical=False, holds_handle=True),
    TaskState.BLOCK: StateWork(WorkKind.MOTION, Motion.BLOCK_DOOR, critical=False, holds_handle=True),
    TaskState.READY_TO_WALK: StateWork(WorkKind.MOTION, Motion.READY_TO_WALK, critical=False, release_first=True),
    # a door without a doorway walk (a narrow push door) has no tuck either: on to WALK_THROUGH
    TaskState.TO_DOORWAY: StateWork(WorkKind.FOOTSTEPS, WalkGoal.DOORWAY, critical=True,
                                    skip_to=TaskState.WALK_THROUGH),
    TaskState.TUCK: StateWork(WorkKind.MOTION, Motion.TUCK_ARM, critical=False),
    TaskState.WALK_THROUGH: StateWork(WorkKind.FOOTSTEPS, WalkGoal.THROUGH, critical=True),
}
