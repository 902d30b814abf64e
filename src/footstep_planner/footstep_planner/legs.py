"""A walk through several body poses in order: one A* search per leg, joined into one plan.

Used where the order of the poses matters and a single search would cut the corner, as in
the pull door's passage (:func:`~footstep_planner.goals.pull_passage_waypoints`): the turn
in place is what sweeps the door open; and where one leg must keep the body's heading, as
through a doorway narrower than the body (:mod:`~footstep_planner.narrow`).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass

from door_contract.vocabulary import Foot
from footstep_planner.astar import FootstepPlanner
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.plan import FootstepPlan, PlanOutcome, PlanResult
from footstep_planner.pruning import LegPruning

__all__ = ["Leg", "plan_legs"]


@dataclass(frozen=True)
class Leg:
    """One search of a walk: to ``goal``, keeping the states ``pruning`` keeps (default:
    all; see :mod:`~footstep_planner.pruning`)."""

    goal: Pose2D
    name: str = ""
    pruning: LegPruning = LegPruning()

    @classmethod
    def of(cls, waypoint: Pose2D | Leg) -> Leg:
        """A leg to a bare pose, with any heading; a leg unchanged."""
        return waypoint if isinstance(waypoint, Leg) else cls(waypoint)


def plan_legs(planner: FootstepPlanner, start: Stance, waypoints: Sequence[Pose2D | Leg],
              attempt: int = 0, first_leg_planner: FootstepPlanner | None = None) -> PlanResult:
    """Plan start → waypoints[0] → … → waypoints[-1]; each leg starts from the stance the
    previous one ended in. The feet keep alternating across legs: a leg's first step is by
    the foot that did not end the previous one, so a walk and its mirror image step alike
    (free to choose, the search began a leg of the right-hinged pull passage with the other
    foot than the left-hinged one did, and a step in place made up for it). Only when that
    foot cannot start (its search fails) does the leg start with the other foot, after a step
    in place.

    The first leg that fails ends the request with its outcome, its reason prefixed by
    the leg's number (and name); expansions and time are totals over the legs planned.
    Every leg gets the expansion budget of ``attempt`` (:meth:`FootstepPlanner.plan`).
    ``first_leg_planner`` plans the first leg instead of ``planner`` (e.g. without the safety
    margins, for a robot that stands inside them: only the first leg starts where the robot
    stands, every later one where a leg planned with the margins ended).
    """
    started = time.perf_counter()
    if not waypoints:
        return PlanResult(PlanOutcome.INVALID_GOAL, "no waypoints to walk through", None, 0, 0.0)
    stance, cost, expansions = start, 0.0, 0
    steps: list[Footstep] = []
    legs = [Leg.of(waypoint) for waypoint in waypoints]
    for number, leg in enumerate(legs, start=1):
        leg_planner = first_leg_planner if number == 1 and first_leg_planner is not None else planner
        result = leg_planner.plan(stance, leg.goal, leg.pruning, attempt=attempt,
                                  first_foot=steps[-1].foot.other if steps else None)
        if not result.succeeded and steps:
            expansions += result.expansions
            result = leg_planner.plan(stance, leg.goal, leg.pruning, attempt=attempt)
        expansions += result.expansions
        if not result.succeeded or result.plan is None:  # a search that succeeded has a plan
            label = f"leg {number} of {len(legs)}" + (f" ({leg.name})" if leg.name else "")
            return PlanResult(result.outcome, f"{label}: {result.reason}", None,
                              expansions, time.perf_counter() - started, result.input_problem)
        steps.extend(_alternating(steps, stance, result.plan.steps))
        stance, cost = result.plan.final_stance, cost + result.plan.cost
    elapsed = time.perf_counter() - started
    plan = FootstepPlan(start, legs[-1].goal, tuple(steps), cost, expansions, elapsed)
    return PlanResult(PlanOutcome.SUCCESS, "", plan, expansions, elapsed)


def _alternating(done: list[Footstep], stance: Stance, leg: tuple[Footstep, ...]) -> list[Footstep]:
    """``leg`` with a step in place of the other foot first if it would repeat the last foot."""
    if done and leg and leg[0].foot is done[-1].foot:
        return [stance.left if leg[0].foot.other is Foot.LEFT else stance.right, *leg]
    return list(leg)
