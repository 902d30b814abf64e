"""How the footstep planner node serves a request, without ROS.

The node hands every request to a :class:`WalkService` in two halves:

* :meth:`WalkService.solve`, on the planning worker's thread: the problem of the request
  from the snapshot of the inputs (:func:`~footstep_planner.requests.problem_for_request`),
  its options, and the search (:class:`~footstep_planner.requests.WalkPlanners`, once more
  without the safety margins from a start inside them). A push passage remembers the door
  angle it was planned for, and says when the angle changed since the last one (the
  passage is re-planned around the leaf where it now is: :func:`~footstep_planner.goals.replan_needed`).
* :meth:`WalkService.answer`, on the executor's thread: how the request is answered.
  A dropped request is SUPERSEDED, one refused for bad input (:data:`BAD_INPUT`) REJECTED,
  one for a walk the door's passage does not have (:class:`~footstep_planner.errors.NoWalkForDoor`)
  SKIPPED, one a bug ended FAILURE ``"internal error: …"``; a search that failed is a FAILURE with the
  planner's outcome and reason; a plan is proposed (footsteps in the /footstep_plan
  convention, their markers, a stamp strictly after the last one) and answered SUCCESS with
  its figures. Where a proposed plan leaves the feet is the start of the next request
  (:func:`~footstep_planner.requests.start_stance`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from door_contract.converters.footsteps import FootPlacement
from door_contract.errors import ContractError
from door_contract.marker_shapes import MarkerShape
from door_contract.payloads import DoorEstimate, FootstepFigures, FootstepRequest, OutcomeStatus, PlanningOutcome
from door_contract.planner_service import Finished
from door_contract.stamps import UniqueStamps
from door_contract.vocabulary import DoorOpening, WalkGoal
from footstep_planner.errors import FootstepPlannerError, NoWalkForDoor
from footstep_planner.footstep import Stance
from footstep_planner.goals import replan_needed
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import PlanResult
from footstep_planner.proposal import contract_footsteps, footstep_shapes, walked_length
from footstep_planner.requests import (
    GoalSettings,
    Snapshot,
    WalkPlanners,
    WalkProblem,
    options_for_problem,
    passage_angle,
    problem_for_request,
)

__all__ = ["BAD_INPUT", "Answer", "Solved", "WalkService"]

BAD_INPUT = (FootstepPlannerError, ContractError)
"""What a request's planning raises for bad input (answered REJECTED, e.g. ``RequestRefused``);
anything else is a bug."""


@dataclass(frozen=True)
class Solved:
    """A request's problem and the search's result; ``relaxed_from`` says why the safety margins
    were dropped (else ""), ``angle_change`` the (previous, new) passage angle (rad) when a push
    passage is planned for a door angle that changed."""

    problem: WalkProblem
    result: PlanResult
    relaxed_from: str = ""
    angle_change: tuple[float, float] | None = None


@dataclass(frozen=True)
class Answer:
    """How one request is answered: the search's figures (None when no search ran) and what is
    proposed with it (SUCCESS only: the footsteps, even index = left foot, their markers and the
    stamp, ns, the proposal carries)."""

    status: OutcomeStatus
    reason: str = ""
    planning_time_s: float = 0.0
    figures: FootstepFigures | None = None
    footsteps: tuple[FootPlacement, ...] = ()
    shapes: tuple[MarkerShape, ...] = ()
    stamp_ns: int = -1
    bug: str = ""
    """The exception's repr when a bug ended the request (it is then a FAILURE)."""

    def outcome(self, request_id: int) -> PlanningOutcome:
        """The PlanningOutcome of ``request_id``: the stamp of the proposal and the figures."""
        return PlanningOutcome(request_id, self.status, self.reason, self.planning_time_s, stamp_ns=self.stamp_ns,
                               footsteps=self.figures)


class WalkService:
    """The footstep planner between requests: its options, the planners (tables built once per
    options), the push passage's last door angle and where the last proposed plan left the feet."""

    def __init__(self, options: FootstepPlannerOptions, settings: GoalSettings) -> None:
        self.options, self.settings = options, settings
        self.planners = WalkPlanners()
        self.passage_angle: float | None = None
        self.planned_stance: Stance | None = None
        self._stamps = UniqueStamps()

    def snapshot(self, base_pose: np.ndarray | None, feet: list[FootPlacement] | None,
                 estimate: DoorEstimate | None) -> Snapshot:
        """The inputs a request is planned from, copied now (the measured state)."""
        return Snapshot(None if base_pose is None else base_pose.copy(), None if feet is None else list(feet),
                        estimate, self.planned_stance)

    def solve(self, request: FootstepRequest, snapshot: Snapshot) -> Solved:
        """The problem from the snapshot, then the search (on the worker thread)."""
        problem = problem_for_request(request, snapshot, self.options, self.settings)
        change = None
        if request.goal is WalkGoal.THROUGH and request.opening is DoorOpening.PUSH:
            angle = passage_angle(request.door_angle, self.settings)
            if self.passage_angle is not None and replan_needed(self.passage_angle, angle):
                change = (self.passage_angle, angle)
            self.passage_angle = angle
        options = options_for_problem(problem, request.goal, self.options)
        result, relaxed_from = self.planners.plan(problem, options, request.attempt)
        return Solved(problem, result, relaxed_from, change)

    def answer(self, finished: Finished, now_ns: int) -> Answer:
        """How ``finished`` is answered (on the executor thread; ``now_ns``: the node's clock)."""
        if isinstance(finished.error, NoWalkForDoor) and not finished.dropped:
            return Answer(OutcomeStatus.SKIPPED, str(finished.error))
        settled = finished.answer_without_result(BAD_INPUT)
        if settled is not None:
            bug = repr(finished.error) if settled[0] is OutcomeStatus.FAILURE else ""
            return Answer(*settled, bug=bug)
        solved: Solved = finished.result
        result, start = solved.result, solved.problem.start
        if not result.succeeded or result.plan is None:
            return Answer(OutcomeStatus.FAILURE, f"{result.outcome.value}: {result.reason}", result.planning_time,
                          FootstepFigures(result.expansions))
        self.planned_stance = result.plan.final_stance
        footsteps = contract_footsteps(start, result.plan)
        shapes = footstep_shapes(footsteps, self.options.foot_length, self.options.foot_width)
        stamp = self._stamps.next(now_ns)
        length = walked_length(start, result.plan.goal)  # the last leg's goal, or where a cut plan stops
        figures = FootstepFigures(result.expansions, len(result.plan.steps), round(length, 3))
        return Answer(OutcomeStatus.SUCCESS, "", result.planning_time, figures, tuple(footsteps), tuple(shapes),
                      stamp)
