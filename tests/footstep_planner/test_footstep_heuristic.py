"""The heuristic never overestimates, checked against random feasible step sequences, for the
default options, the TALOS profile and the profile with a 30 % shorter stride and turn."""

from __future__ import annotations

import math

import numpy as np
import pytest
from footstep_scenes import profile_options

from door_contract.vocabulary import Foot
from footstep_planner.actions import ActionSet, StepAction
from footstep_planner.astar import FootstepPlanner
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.geometry import wrap_angle
from footstep_planner.heuristic import FootstepHeuristic, is_goal_centre
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.pruning import LegPruning
from footstep_planner.world import World

OPTION_SETS = {"defaults": FootstepPlannerOptions(heuristic_weight=1.0), "talos": profile_options(heuristic_weight=1.0),
               "talos, 30 % shorter": profile_options(0.7, heuristic_weight=1.0)}
PLANNERS = {name: FootstepPlanner(World(), options) for name, options in OPTION_SETS.items()}


def _take(support: Footstep, action: StepAction, separation: float) -> Footstep:
    """The footstep ``action`` places, swinging the foot opposite ``support``."""
    swing = support.foot.other
    x, y, yaw = action.swing_offset(swing, separation)
    world_x, world_y = support.pose.transform(x, y)
    return Footstep(world_x, world_y, support.yaw + yaw, swing)


def _heuristic(planner: FootstepPlanner, goal: Pose2D, yaw_window: float = math.pi) -> FootstepHeuristic:
    return FootstepHeuristic(goal, planner.options, planner.progress_table_within(yaw_window),
                             planner.actions.max_turn)


def _random_sequence(rng: np.random.Generator, planner: FootstepPlanner, steps: int,
                     ) -> tuple[Footstep, list[Footstep], float]:
    """A random start foot, a random walk of actions (biased to long strides), its cost."""
    options, actions = planner.options, planner.actions.actions
    start = Footstep(*rng.uniform(-1.0, 1.0, 2), rng.uniform(-math.pi, math.pi),
                     Foot.LEFT if rng.random() < 0.5 else Foot.RIGHT)
    bias = np.array([1.0 + 4.0 * max(a.forward, 0.0) / options.max_stride + 2.0 * abs(a.outward) / 0.1
                     for a in actions])
    feet, cost = [start], options.step_cost  # the closing step
    for _ in range(steps):
        action = actions[int(rng.choice(len(actions), p=bias / bias.sum()))]
        feet.append(_take(feet[-1], action, options.nominal_foot_separation))
        cost += action.cost(options)
    return start, feet, cost


def _goal_satisfied_by(rng: np.random.Generator, centre: Pose2D, options: FootstepPlannerOptions) -> Pose2D:
    """Any goal the stance centre satisfies: perturbed within the tolerances."""
    angle, radius = rng.uniform(-math.pi, math.pi), rng.uniform(0.0, options.goal_position_tolerance)
    goal = Pose2D(centre.x + radius * math.cos(angle), centre.y + radius * math.sin(angle),
                  centre.yaw + rng.uniform(-1.0, 1.0) * options.goal_yaw_tolerance)
    assert is_goal_centre(centre, goal, options)
    return goal


@pytest.mark.parametrize("name", list(OPTION_SETS))
def test_heuristic_is_a_lower_bound_of_every_sampled_plan(name: str) -> None:
    planner, rng = PLANNERS[name], np.random.default_rng(2024)
    separation = planner.options.nominal_foot_separation
    for _ in range(800):
        start, feet, cost = _random_sequence(rng, planner, int(rng.integers(0, 20)))
        goal = _goal_satisfied_by(rng, feet[-1].stance_centre(separation), planner.options)
        estimate = _heuristic(planner, goal).estimate_one(start.stance_centre(separation), start.foot.other)
        assert estimate <= cost + 1e-9, (start, goal, estimate, cost)


@pytest.mark.parametrize("name", list(OPTION_SETS))
def test_windowed_heuristic_is_a_lower_bound_of_every_plan_within_the_window(name: str) -> None:
    """Sequences whose every foot stays within 0.1 rad of the goal's heading, bounded by the
    table built for that window (it is tighter: it knows the leg cannot turn to walk forwards)."""
    planner, rng, window = PLANNERS[name], np.random.default_rng(7), 0.1
    separation, checked = planner.options.nominal_foot_separation, 0
    while checked < 300:
        start, feet, cost = _random_sequence(rng, planner, int(rng.integers(0, 24)))
        goal = _goal_satisfied_by(rng, feet[-1].stance_centre(separation), planner.options)
        if any(abs(wrap_angle(foot.yaw - goal.yaw)) > window for foot in feet):
            continue
        estimate = _heuristic(planner, goal, window).estimate_one(start.stance_centre(separation), start.foot.other)
        assert estimate <= cost + 1e-9, (start, goal, estimate, cost)
        checked += 1


def test_heuristic_is_tight_for_straight_walking() -> None:
    """k full strides then the closing step cost k (s + stride w_d) + s; h misses only the
    0.05 m goal tolerance."""
    planner = PLANNERS["defaults"]
    options = planner.options
    stride = StepAction(options.max_stride, 0.0, 0.0)
    start = Footstep(0.0, 0.1, 0.0, Foot.LEFT)
    foot, cost = start, options.step_cost
    for _ in range(10):
        foot, cost = _take(foot, stride, options.nominal_foot_separation), cost + stride.cost(options)
    estimate = _heuristic(planner, foot.stance_centre(options.nominal_foot_separation)).estimate_one(
        start.stance_centre(options.nominal_foot_separation), Foot.RIGHT)
    assert estimate == pytest.approx(cost - options.distance_weight * options.goal_position_tolerance)


def test_heuristic_at_the_goal_is_the_closing_step() -> None:
    goal = Pose2D(1.0, 2.0, 0.5)
    for foot in Foot:
        assert _heuristic(PLANNERS["talos"], goal).estimate_one(goal, foot) == pytest.approx(1.0)


def test_heuristic_knows_sideways_is_slower_than_forwards() -> None:
    planner = PLANNERS["talos"]
    here = Pose2D(0.0, 0.0, 0.0)
    aside = _heuristic(planner, Pose2D(0.0, 2.0, 0.0)).estimate_one(here, Foot.LEFT)
    ahead = _heuristic(planner, Pose2D(2.0, 0.0, 0.0)).estimate_one(here, Foot.LEFT)
    assert aside > ahead + 2.0  # turning to walk forwards and back takes steps too


def test_heuristic_does_not_exceed_the_optimal_plan_cost() -> None:
    for name in ("talos", "talos, 30 % shorter"):
        planner = PLANNERS[name]
        separation = planner.options.nominal_foot_separation
        for goal, pruning in ((Pose2D(1.2, 0.4, 0.3), LegPruning()), (Pose2D(-0.6, 0.2, 0.0), LegPruning()),
                              (Pose2D(0.5, -0.8, -1.0), LegPruning()), (Pose2D(0.0, 0.7, 0.0), LegPruning(0.1))):
            start = Stance.nominal(Pose2D(0.0, 0.0, 0.0), separation)
            result = planner.plan(start, goal, pruning)
            assert result.plan is not None, result.reason
            estimate = min(_heuristic(planner, goal, pruning.yaw_window).estimate_one(f.stance_centre(separation),
                                                                                       f.foot.other)
                           for f in (start.left, start.right))
            assert estimate <= result.plan.cost + 1e-9


def test_the_progress_bound_never_shrinks_with_more_steps() -> None:
    table = PLANNERS["talos"].progress_table
    for foot in Foot:
        rows = np.maximum(table.rows[foot], -1e6)  # -inf: the goal heading is out of reach
        assert np.all(np.diff(rows, axis=1) >= -1e-12)
        assert rows[:, 0].max() == 0.0


def test_turning_in_place_counts_its_steps() -> None:
    """A quarter turn in place: every step turns at most A, so at least ceil((pi/2 - e_y) / A)
    steps, plus the closing one."""
    planner = PLANNERS["talos"]
    options = planner.options
    goal = Pose2D(0.0, 0.0, math.pi / 2.0)
    estimate = _heuristic(planner, goal).estimate_one(Pose2D(0.0, 0.0, 0.0), Foot.LEFT)
    turns = math.ceil((math.pi / 2.0 - options.goal_yaw_tolerance) / planner.actions.max_turn)
    assert estimate >= options.step_cost * (1 + turns)
    assert ActionSet.from_options(options).max_turn == pytest.approx(options.max_turn)


def test_a_side_step_cannot_also_turn_the_body_to_walk_forwards() -> None:
    """1 m sideways, TALOS: without turning a pair of steps advances at most 0.131 m; turning
    to walk forwards costs steps that advance little. The bound that couples each step's
    advance to its own turn needs at least 8 steps (one that let every step take the best
    advance of any heading reachable by then said 7); the optimum is 13."""
    planner = PLANNERS["talos"]
    estimate = _heuristic(planner, Pose2D(0.0, 1.0, 0.0)).estimate_one(Pose2D(0.0, 0.0, 0.0), Foot.LEFT)
    distance = 1.0 - planner.options.goal_position_tolerance
    assert estimate >= planner.options.step_cost * (1 + 8) + planner.options.distance_weight * distance - 1e-9
