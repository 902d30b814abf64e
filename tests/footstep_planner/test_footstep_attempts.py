"""Repeats that change something: attempt n searches with a larger budget, a greedier weight
and a wider region than attempt n - 1, so a request that ran out of budget can succeed when
repeated, and an identical search is never run twice."""

from __future__ import annotations

from dataclasses import replace

import pytest
from footstep_scenes import door_facing_robot, profile_options

from door_contract.vocabulary import DoorOpening
from footstep_planner.astar import FootstepPlanner
from footstep_planner.attempts import MAX_ATTEMPT, options_for_attempt
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.goals import pull_passage_waypoints, stand_pose_for_opening
from footstep_planner.legs import plan_legs
from footstep_planner.plan import PlanOutcome
from footstep_planner.world import World

OPTIONS = profile_options(heuristic_weight=1.5, max_expansions=1000)


def test_the_first_attempt_is_the_options_themselves() -> None:
    assert options_for_attempt(OPTIONS, 0) is OPTIONS


def test_every_repeat_searches_differently_from_its_predecessor() -> None:
    previous = OPTIONS
    for attempt in range(1, 6):
        repeated = options_for_attempt(OPTIONS, attempt)
        assert repeated != previous
        assert repeated.max_expansions > previous.max_expansions
        assert repeated.heuristic_weight > previous.heuristic_weight or repeated.heuristic_weight == 10.0
        assert repeated.search_margin > previous.search_margin or repeated.search_margin == 50.0
        # nothing else changes: the robot's limits and the costs are the request's
        assert replace(repeated, max_expansions=OPTIONS.max_expansions, heuristic_weight=OPTIONS.heuristic_weight,
                       search_margin=OPTIONS.search_margin) == OPTIONS
        previous = repeated


def test_a_repeat_that_could_not_change_anything_is_refused() -> None:
    capped = replace(OPTIONS, max_expansions=10_000_000, heuristic_weight=10.0, search_margin=50.0)
    with pytest.raises(FootstepPlannerError, match="exactly as attempt 0") as error:
        options_for_attempt(capped, 1)
    assert error.value.field == "attempt"


@pytest.mark.parametrize("attempt", [-1, MAX_ATTEMPT + 1, 1.0, True, "1"])
def test_an_attempt_out_of_range_or_not_an_integer_is_refused_with_the_field_named(attempt: object) -> None:
    with pytest.raises(FootstepPlannerError) as error:
        options_for_attempt(OPTIONS, attempt)  # type: ignore[arg-type]
    assert error.value.field == "attempt"


def test_a_search_out_of_budget_succeeds_when_repeated() -> None:
    """A* (w = 1) with 300 expansions cannot finish a 1 m sideways walk-and-turn; the repeat
    has twice the budget and weight 2, and plans it. The same attempt repeated gives the
    same answer: nothing depends on the clock."""
    planner = FootstepPlanner(World(), replace(OPTIONS, heuristic_weight=1.0, max_expansions=300))
    start, goal = Stance.nominal(Pose2D(0.0, 0.0, 0.0), OPTIONS.nominal_foot_separation), Pose2D(0.3, 1.0, 0.6)
    first = planner.plan(start, goal)
    assert first.outcome is PlanOutcome.EXPANSION_LIMIT and first.expansions == 300
    again = planner.plan(start, goal)
    assert (again.outcome, again.expansions) == (first.outcome, first.expansions)
    repeat = planner.plan(start, goal, attempt=1)
    assert repeat.succeeded, repeat.reason
    assert repeat.expansions <= 600


def test_every_leg_of_a_walk_gets_the_attempts_settings() -> None:
    door = door_facing_robot(DoorOpening.PULL, leaf_width=0.914, clear_opening=0.87, handle_offset=0.136)
    options = replace(OPTIONS, snap_to_goal=True, max_expansions=2)
    stand = stand_pose_for_opening(door, options, reach=0.65, sweep_half_depth=0.15)
    legs = pull_passage_waypoints(door, stand)
    planner = FootstepPlanner(World(), options)
    start = Stance.nominal(stand, options.nominal_foot_separation)
    first = plan_legs(planner, start, legs)
    assert first.outcome is PlanOutcome.EXPANSION_LIMIT and "leg 1 of 4" in first.reason
    repeated = plan_legs(planner, start, legs, attempt=3)  # a budget of 16 per leg
    assert repeated.succeeded, repeated.reason
