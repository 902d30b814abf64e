"""The heuristic never overestimates, checked against random feasible step sequences."""

from __future__ import annotations

import math

import numpy as np
import pytest

from footstep_planner.actions import ActionSet, StepAction
from footstep_planner.astar import FootstepPlanner
from footstep_planner.footstep import Foot, Footstep, Pose2D, Stance
from footstep_planner.heuristic import FootstepHeuristic, is_goal_centre
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.world import World

OPTIONS = FootstepPlannerOptions()
PLANNER = FootstepPlanner(World(), OPTIONS)
SEPARATION = OPTIONS.nominal_foot_separation


def _take(support: Footstep, action: StepAction) -> Footstep:
    """The footstep ``action`` places, swinging the foot opposite ``support``."""
    swing = support.foot.other
    x, y, yaw = action.swing_offset(swing, SEPARATION)
    world_x, world_y = support.pose.transform(x, y)
    return Footstep(world_x, world_y, support.yaw + yaw, swing)


def _heuristic(goal: Pose2D) -> FootstepHeuristic:
    return FootstepHeuristic(goal, OPTIONS, PLANNER.progress_table, PLANNER.actions.max_turn)


def _random_sequence(rng: np.random.Generator, actions: tuple[StepAction, ...],
                     ) -> tuple[Footstep, Footstep, float]:
    """A random start foot, a random walk of actions (biased to long strides), its cost."""
    start = Footstep(*rng.uniform(-1.0, 1.0, 2), rng.uniform(-math.pi, math.pi),
                     Foot.LEFT if rng.random() < 0.5 else Foot.RIGHT)
    forward_bias = np.array([1.0 + 4.0 * max(a.forward, 0.0) / OPTIONS.max_stride
                             for a in actions])
    probabilities = forward_bias / forward_bias.sum()
    foot, cost = start, 0.0
    for _ in range(int(rng.integers(0, 14))):
        action = actions[int(rng.choice(len(actions), p=probabilities))]
        foot, cost = _take(foot, action), cost + action.cost(OPTIONS)
    return start, foot, cost + OPTIONS.step_cost  # + the closing step


def test_heuristic_is_a_lower_bound_of_every_sampled_plan() -> None:
    rng = np.random.default_rng(2024)
    actions = ActionSet.from_options(OPTIONS).actions
    for _ in range(1500):
        start, last, cost = _random_sequence(rng, actions)
        centre = last.stance_centre(SEPARATION)
        # any goal the last stance satisfies: perturb within the tolerances
        angle = rng.uniform(-math.pi, math.pi)
        radius = rng.uniform(0.0, OPTIONS.goal_position_tolerance)
        goal = Pose2D(centre.x + radius * math.cos(angle), centre.y + radius * math.sin(angle),
                      centre.yaw + rng.uniform(-1.0, 1.0) * OPTIONS.goal_yaw_tolerance)
        assert is_goal_centre(centre, goal, OPTIONS)
        estimate = _heuristic(goal).estimate_one(start.stance_centre(SEPARATION))
        assert estimate <= cost + 1e-9, (start, goal, estimate, cost)


def test_heuristic_is_tight_for_straight_walking() -> None:
    """k full strides then the closing step cost k (s + 0.3 w_d) + s; h misses only the
    0.05 m goal tolerance."""
    stride = StepAction(OPTIONS.max_stride, 0.0, 0.0)
    start = Footstep(0.0, 0.1, 0.0, Foot.LEFT)
    foot, cost = start, OPTIONS.step_cost
    for _ in range(10):
        foot, cost = _take(foot, stride), cost + stride.cost(OPTIONS)
    estimate = _heuristic(foot.stance_centre(SEPARATION)).estimate_one(
        start.stance_centre(SEPARATION))
    slack = OPTIONS.distance_weight * OPTIONS.goal_position_tolerance
    assert estimate == pytest.approx(cost - slack)


def test_heuristic_at_the_goal_is_the_closing_step() -> None:
    goal = Pose2D(1.0, 2.0, 0.5)
    assert _heuristic(goal).estimate_one(goal) == pytest.approx(OPTIONS.step_cost)


def test_heuristic_knows_sideways_is_slower_than_forwards() -> None:
    goal_ahead = Pose2D(2.0, 0.0, 0.0)
    goal_aside = Pose2D(0.0, 2.0, 0.0)
    here = Pose2D(0.0, 0.0, 0.0)
    assert _heuristic(goal_aside).estimate_one(here) > _heuristic(goal_ahead).estimate_one(here)


def test_progress_bound_grows_with_the_step_count() -> None:
    progress = PLANNER.progress_table.progress
    assert np.all(np.diff(progress, axis=0) >= -1e-12)
    assert progress[0].max() == 0.0


def test_heuristic_does_not_exceed_the_optimal_plan_cost() -> None:
    for goal in (Pose2D(1.2, 0.4, 0.3), Pose2D(-0.6, 0.2, 0.0), Pose2D(0.5, -0.8, -1.0)):
        result = PLANNER.plan(Stance.nominal(Pose2D(0.0, 0.0, 0.0), SEPARATION), goal)
        assert result.plan is not None, result.reason
        start_centres = (result.plan.start.left.stance_centre(SEPARATION),
                         result.plan.start.right.stance_centre(SEPARATION))
        estimate = min(_heuristic(goal).estimate_one(c) for c in start_centres)
        assert estimate <= result.plan.cost + 1e-9

