"""Goal-directed pruning keeps a leg's search to the states it can need, and never admits a
state the full search would refuse."""

from __future__ import annotations

import math

import numpy as np
import pytest
from footstep_scenes import kinematic_violations, profile_options

from footstep_planner.astar import FootstepPlanner
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.geometry import wrap_angle
from footstep_planner.obstacles import Obstacle
from footstep_planner.plan import PlanOutcome
from footstep_planner.pruning import LegPruning
from footstep_planner.world import World

OPTIONS = profile_options()


def test_the_default_keeps_every_state() -> None:
    assert not LegPruning().prunes
    keep = LegPruning().keeps((0.0, 0.0), Pose2D(1.0, 0.0, 0.0), np.array([5.0, -3.0]), np.array([2.0, 9.0]),
                              np.array([3.0, -3.0]))
    assert keep.all()


def test_window_and_corridor_drop_what_they_say() -> None:
    pruning = LegPruning(yaw_window=0.1, corridor=0.05)
    goal = Pose2D(2.0, 0.0, 0.0)
    centres_x, centres_y = np.array([1.0, 1.0, 1.0, 1.0]), np.array([0.0, 0.04, 0.06, 0.0])
    yaws = np.array([0.0, 0.09, 0.0, 0.11])
    assert pruning.keeps((0.0, 0.0), goal, centres_x, centres_y, yaws).tolist() == [True, True, False, False]


@pytest.mark.parametrize(("field", "value"), [("yaw_window", 0.0), ("yaw_window", 4.0), ("corridor", 0.0),
                                              ("corridor", -1.0), ("yaw_window", math.nan)])
def test_out_of_range_pruning_is_refused_with_the_field_named(field: str, value: float) -> None:
    with pytest.raises(FootstepPlannerError) as error:
        LegPruning(**{field: value})
    assert error.value.field == field


def test_a_sideways_leg_pruned_to_its_line_plans_within_it_and_expands_less() -> None:
    planner = FootstepPlanner(World(), OPTIONS)
    start, goal = Stance.nominal(Pose2D(0.0, 0.0, 0.0), OPTIONS.nominal_foot_separation), Pose2D(0.0, 1.2, 0.0)
    pruning = LegPruning(yaw_window=0.1, corridor=0.05)
    free = planner.plan(start, goal)
    pruned = planner.plan(start, goal, pruning)
    assert free.succeeded and pruned.succeeded, (free.reason, pruned.reason)
    assert pruned.expansions < free.expansions
    assert kinematic_violations(pruned.plan, OPTIONS) == []
    for stance in pruned.plan.stances()[:-3]:  # the snapping steps are not searched
        assert abs(stance.body_pose.x) <= 0.05 + OPTIONS.nominal_foot_separation
    assert all(abs(wrap_angle(step.yaw - goal.yaw)) <= 0.1 + 1e-9 for step in pruned.plan.steps)


def test_a_wrong_assumption_fails_rather_than_passing_through_a_wall() -> None:
    """A crate stands in the corridor, beside the line: the pruned search cannot go round it and
    says so; the full search goes round."""
    wall = World((Obstacle.rectangle("crate", (0.35, 0.58), 0.0, 0.2, 0.2),))
    planner = FootstepPlanner(wall, OPTIONS)
    start, goal = Stance.nominal(Pose2D(0.0, 0.0, 0.0), OPTIONS.nominal_foot_separation), Pose2D(0.0, 1.2, 0.0)
    pruned = planner.plan(start, goal, LegPruning(yaw_window=0.1, corridor=0.05))
    assert pruned.outcome in (PlanOutcome.UNREACHABLE, PlanOutcome.EXPANSION_LIMIT)
    assert planner.plan(start, goal).succeeded
