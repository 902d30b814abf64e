"""What a planning request returns: a footstep plan or a failure outcome with its reason."""

from __future__ import annotations

import time
from dataclasses import dataclass
from enum import Enum

from footstep_planner.footstep import Footstep, Pose2D, Stance

__all__ = ["FootstepPlan", "InputProblem", "PlanOutcome", "PlanResult", "failed"]


class PlanOutcome(Enum):
    """How a planning request ended."""

    SUCCESS = "success"
    UNREACHABLE = "unreachable"
    """No collision-free footstep sequence reaches the goal (proved before or by the search)."""
    EXPANSION_LIMIT = "expansion_limit"
    """The search expanded ``max_expansions`` states without reaching the goal."""
    TIME_LIMIT = "time_limit"
    """The search ran for ``max_planning_time`` without reaching the goal."""
    INVALID_START = "invalid_start"
    """The start stance is not finite or collides."""
    INVALID_GOAL = "invalid_goal"
    """The goal pose is not finite or its stance collides."""


class InputProblem(Enum):
    """Which check refused an INVALID_START / INVALID_GOAL request before any search: the
    structured cause callers branch on (the result's ``reason`` is text for people)."""

    START_NOT_FINITE = "start_not_finite"
    GOAL_NOT_FINITE = "goal_not_finite"
    START_COLLIDES = "start_collides"
    """The start stance itself collides (e.g. a walk stopped inside the safety margins)."""
    GOAL_COLLIDES = "goal_collides"
    NO_FIRST_STEP = "no_first_step"
    """The start stance is free, but the body over either start foot would collide."""


@dataclass(frozen=True)
class FootstepPlan:
    """A collision-free footstep sequence from ``start`` to a stance at ``goal``.

    ``steps`` are placed in order (each foot alternately); the last step
    closes the stance, so the final two steps form the nominal stance within
    the goal tolerances.  ``cost`` is the sum of the step costs.
    """

    start: Stance
    goal: Pose2D
    steps: tuple[Footstep, ...]
    cost: float
    expansions: int
    planning_time: float
    """Wall time of the request (s)."""

    @property
    def final_stance(self) -> Stance:
        """Both feet after the last step."""
        stance = self.start
        for step in self.steps:
            stance = stance.with_footstep(step)
        return stance

    def stances(self) -> tuple[Stance, ...]:
        """The stance after each step (the start stance excluded)."""
        stance, result = self.start, []
        for step in self.steps:
            stance = stance.with_footstep(step)
            result.append(stance)
        return tuple(result)


@dataclass(frozen=True)
class PlanResult:
    """The answer to one planning request: an outcome, a reason, and the plan on success."""

    outcome: PlanOutcome
    reason: str
    plan: FootstepPlan | None
    expansions: int
    planning_time: float
    """Wall time of the request (s)."""
    input_problem: InputProblem | None = None
    """Why the request was refused before any search (INVALID_START / INVALID_GOAL), else None."""

    @property
    def succeeded(self) -> bool:
        """True when a plan was found."""
        return self.outcome is PlanOutcome.SUCCESS


def failed(outcome: PlanOutcome, reason: str, expansions: int, started: float,
           input_problem: InputProblem | None = None) -> PlanResult:
    """A failed :class:`PlanResult` timed from ``started`` (a ``time.perf_counter()`` value)."""
    return PlanResult(outcome, reason, None, expansions, time.perf_counter() - started, input_problem)
