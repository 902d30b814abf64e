"""What the FSM knows about the door between states, and the planner requests built from it.

The estimate DETECT_DOOR proposed is the one every later request names (later estimates,
seen up close while walking, do not silently replace what the operator approved); the
hinge angle is the one the last *executed* door motion planned to leave.
"""

from __future__ import annotations

from dataclasses import dataclass

from door_contract.payloads import DoorEstimate, FootstepRequest, MotionRequest, PlanningOutcome, encode
from door_contract.vocabulary import Backend, DoorOpening, Side, grasp_hand
from door_fsm import actions as act

__all__ = ["DoorContext"]


@dataclass
class DoorContext:
    opening: DoorOpening
    backend: Backend
    latest: DoorEstimate | None = None
    approved: DoorEstimate | None = None
    angle: float = 0.0          # rad, as left by the last executed door motion
    planned_angle: float = 0.0  # rad, at the end of the motion being executed
    approach_hand: Side | None = None  # the arm of the last proposed approach (the optimiser's choice)

    def footstep_request(self, action: act.RequestFootsteps) -> FootstepRequest:
        return FootstepRequest(action.request_id, action.goal, self.opening, self.angle,
                               self._approved_stamp(), self._approved_json(), attempt=action.attempt)

    def motion_request(self, action: act.RequestMotion) -> MotionRequest:
        return MotionRequest(action.request_id, action.motion, self.opening, self.backend, self.angle,
                             self._approved_stamp(), self._approved_json(), attempt=action.attempt,
                             hand=self.approach_hand)

    def grasp_hand(self) -> Side:
        """The hand the approach moved (the optimiser picks the arm on the handle's side:
        :func:`door_trajopt.requests.grasping_hand`), else the one a facing robot opens with."""
        if self.approach_hand is not None:
            return self.approach_hand
        door = self.approved or self.latest
        return grasp_hand(door.hinge_side, self.opening) if door else Side.RIGHT

    def planned(self, outcome: PlanningOutcome) -> None:
        """A motion proposal says where it leaves the door."""
        if outcome.door_angle is not None:
            self.planned_angle = outcome.door_angle

    def executed(self) -> None:
        self.angle = self.planned_angle

    def _approved_stamp(self) -> float:
        return self.approved.stamp if self.approved is not None else -1.0

    def _approved_json(self) -> str:
        return encode(self.approved) if self.approved is not None else ""
