"""A* footstep planning: optimal step counts, collision-free plans, bounded failures."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest
from footstep_scenes import (
    DEFAULT_OPTIONS,
    SEPARATION,
    alternates,
    collisions_along,
    door_facing_robot,
    in_front_of,
    kinematic_violations,
    relative_step,
    stance_at,
)

from door_contract.vocabulary import DoorOpening, Foot, HingeSide
from footstep_planner.astar import FootstepPlanner, plan_footsteps
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.goals import stand_pose_for_opening, through_door_pose
from footstep_planner.obstacles import Obstacle
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import InputProblem, PlanOutcome, PlanResult
from footstep_planner.world import World

OPEN_SPACE = FootstepPlanner(World())


def _succeeded(result: PlanResult) -> PlanResult:
    assert result.outcome is PlanOutcome.SUCCESS, result.reason
    assert result.plan is not None
    return result


def test_straight_walk_uses_the_fewest_steps() -> None:
    """2 m straight ahead takes ceil(2.0 / 0.30) + 1 = 8 steps, the minimum possible.

    A step puts the swing foot at most max_stride ahead of the support foot,
    so the k-th foot placed is at most 0.30 k m ahead of the start.  The
    final stance has both feet beside each other at x = 2.0 +- 0.05, so the
    second-to-last foot placed needs 0.30 (k - 1) >= 1.95, i.e. k >= 8:
    7 steps (ceil(2.0 / 0.30)) to bring one foot there, 1 closing step.
    """
    result = _succeeded(OPEN_SPACE.plan(stance_at(0.0, 0.0), Pose2D(2.0, 0.0, 0.0)))
    plan = result.plan
    assert len(plan.steps) == math.ceil(2.0 / DEFAULT_OPTIONS.max_stride) + 1 == 8
    final = plan.final_stance.body_pose
    assert math.hypot(final.x - 2.0, final.y) <= DEFAULT_OPTIONS.goal_position_tolerance + 1e-9
    assert all(abs(step.yaw) < 1e-9 for step in plan.steps)
    assert alternates(plan)
    assert kinematic_violations(plan) == []


def test_turning_in_place_by_90_degrees() -> None:
    """Each step turns at most 0.35 rad; the last foot must end within 0.1 rad of pi/2, so
    ceil((pi/2 - 0.1) / 0.35) = 5 turning steps, then 1 closing step."""
    result = _succeeded(OPEN_SPACE.plan(stance_at(0.0, 0.0), Pose2D(0.0, 0.0, math.pi / 2.0)))
    plan = result.plan
    expected = math.ceil((math.pi / 2.0 - DEFAULT_OPTIONS.goal_yaw_tolerance)
                         / DEFAULT_OPTIONS.max_turn) + 1
    assert len(plan.steps) == expected == 6
    final = plan.final_stance.body_pose
    assert abs(final.yaw - math.pi / 2.0) <= DEFAULT_OPTIONS.goal_yaw_tolerance + 1e-9
    assert math.hypot(final.x, final.y) <= DEFAULT_OPTIONS.goal_position_tolerance + 1e-9
    assert kinematic_violations(plan) == []
    # the final two feet form the nominal stance
    support, closing = plan.steps[-2], plan.steps[-1]
    forward, lateral, turn = relative_step(support, closing)
    assert (forward, lateral, turn) == pytest.approx((0.0, 0.20, 0.0), abs=1e-9)


def test_already_at_the_goal_one_step_squares_the_feet() -> None:
    """Never an empty plan (it proposes nothing: the FSM waited for a proposal until its
    planning timeout): the foot farther from the nominal stance steps beside the other."""
    result = _succeeded(OPEN_SPACE.plan(stance_at(1.0, 1.0, 0.5), Pose2D(1.01, 1.0, 0.5)))
    assert len(result.plan.steps) == 1 and result.expansions == 0
    start = stance_at(1.0, 1.0, 0.0)
    off = Stance(start.left, Footstep(start.right.x + 0.03, start.right.y, 0.0, Foot.RIGHT))
    squared = _succeeded(OPEN_SPACE.plan(off, Pose2D(1.0, 1.0, 0.0))).plan.steps
    assert len(squared) == 1
    kept = off.right if squared[0].foot is Foot.LEFT else off.left
    assert squared[0] == kept.nominal_partner(SEPARATION)  # the feet stand nominal again
    assert squared[0].pose.distance_to(off.foot(squared[0].foot).pose) == pytest.approx(0.03)


@pytest.mark.parametrize("opening", list(DoorOpening))
@pytest.mark.parametrize("hinge_side", list(HingeSide))
def test_doorway_passage_through_an_open_door(opening: DoorOpening, hinge_side: HingeSide) -> None:
    door = door_facing_robot(opening, angle=math.pi / 2.0, hinge_side=hinge_side)
    world = World.from_door(door)
    start = stance_at(2.0 - 1.5, 0.0)  # 1.5 m in front of the door plane, facing it
    goal = through_door_pose(door)      # 1 m beyond, centred
    result = _succeeded(FootstepPlanner(world).plan(start, goal))
    plan = result.plan
    assert plan.final_stance.body_pose.x > 2.9
    assert collisions_along(plan, world) == []
    assert kinematic_violations(plan) == []
    assert alternates(plan)


def test_doorway_passage_from_an_offset_start() -> None:
    door = door_facing_robot(DoorOpening.PUSH, angle=math.pi / 2.0)
    world = World.from_door(door)
    options = FootstepPlannerOptions(heuristic_weight=1.5)
    result = _succeeded(FootstepPlanner(world, options).plan(stance_at(0.4, -0.5, 0.3),
                                                             through_door_pose(door)))
    assert collisions_along(result.plan, world) == []
    assert kinematic_violations(result.plan) == []


def test_approach_to_the_stand_pose_is_collision_free() -> None:
    door = door_facing_robot(DoorOpening.PULL)
    world = World.from_door(door, sweep=(0.0, math.pi / 2.0))
    stand = stand_pose_for_opening(door, DEFAULT_OPTIONS)
    start = stance_at(stand.x - 4.0, stand.y)
    result = _succeeded(FootstepPlanner(world).plan(start, stand))
    assert collisions_along(result.plan, world) == []
    assert kinematic_violations(result.plan) == []
    final = result.plan.final_stance.body_pose
    assert final.distance_to(stand) <= DEFAULT_OPTIONS.goal_position_tolerance + 1e-9


def test_goal_beyond_a_closed_door_is_unreachable_without_searching() -> None:
    door = door_facing_robot(DoorOpening.PUSH, angle=0.0)
    result = FootstepPlanner(World.from_door(door)).plan(stance_at(0.5, 0.0),
                                                         through_door_pose(door))
    assert result.outcome is PlanOutcome.UNREACHABLE
    assert result.plan is None
    assert result.expansions == 0
    assert "walled off" in result.reason


def test_goal_enclosed_by_walls_is_unreachable() -> None:
    walls = World((
        Obstacle.rectangle("north", (3.0, 1.0), 0.0, 2.1, 0.1),
        Obstacle.rectangle("south", (3.0, -1.0), 0.0, 2.1, 0.1),
        Obstacle.rectangle("east", (4.0, 0.0), math.pi / 2.0, 2.1, 0.1),
        Obstacle.rectangle("west", (2.0, 0.0), math.pi / 2.0, 2.1, 0.1),
    ))
    result = FootstepPlanner(walls).plan(stance_at(0.0, 0.0), Pose2D(3.0, 0.0, 0.0))
    assert result.outcome is PlanOutcome.UNREACHABLE


def test_too_narrow_a_gap_ends_at_the_expansion_bound() -> None:
    """A 0.32 m gap is wider than the coarse corridor check needs, narrower than the body's
    0.34 m depth with margins: only the search can tell, and it stops at its bound."""
    door = door_facing_robot(DoorOpening.PUSH, angle=math.pi / 2.0, clear_opening=0.32,
                             leaf_width=0.36, handle_offset=0.05)
    options = FootstepPlannerOptions(max_expansions=300, heuristic_weight=2.0)
    result = FootstepPlanner(World.from_door(door), options).plan(stance_at(0.5, 0.0),
                                                                  through_door_pose(door))
    assert result.outcome is PlanOutcome.EXPANSION_LIMIT
    assert result.expansions == 300
    assert "max_expansions" in result.reason


def test_time_bound_ends_the_search() -> None:
    options = FootstepPlannerOptions(max_planning_time=1e-9)
    result = FootstepPlanner(World(), options).plan(stance_at(0.0, 0.0), Pose2D(5.0, 0.0, 0.0))
    assert result.outcome is PlanOutcome.TIME_LIMIT
    assert "max_planning_time" in result.reason


@pytest.mark.parametrize("goal", [Pose2D(math.nan, 0.0, 0.0), Pose2D(1.0, math.inf, 0.0),
                                  Pose2D(1.0, 0.0, math.nan)])
def test_non_finite_goal_is_rejected_before_searching(goal: Pose2D) -> None:
    result = OPEN_SPACE.plan(stance_at(0.0, 0.0), goal)
    assert result.outcome is PlanOutcome.INVALID_GOAL
    assert result.expansions == 0
    assert "not finite" in result.reason


def test_goal_inside_an_obstacle_is_rejected() -> None:
    world = World((Obstacle.rectangle("pillar", (2.0, 0.0), 0.0, 0.4, 0.4),))
    result = FootstepPlanner(world).plan(stance_at(0.0, 0.0), Pose2D(2.0, 0.1, 0.0))
    assert result.outcome is PlanOutcome.INVALID_GOAL
    assert "pillar" in result.reason


def test_goal_in_the_door_wall_is_rejected() -> None:
    door = door_facing_robot(DoorOpening.PUSH, angle=math.pi / 2.0)
    result = FootstepPlanner(World.from_door(door)).plan(stance_at(0.5, 0.0),
                                                         Pose2D(2.05, 1.5, 0.0))
    assert result.outcome is PlanOutcome.INVALID_GOAL
    assert "wall_hinge_side" in result.reason


def test_start_in_collision_or_not_finite_is_rejected() -> None:
    world = World((Obstacle.rectangle("crate", (0.0, 0.3), 0.0, 0.3, 0.3),))
    colliding = FootstepPlanner(world).plan(stance_at(0.0, 0.0), Pose2D(1.0, 0.0, 0.0))
    assert colliding.outcome is PlanOutcome.INVALID_START
    assert colliding.input_problem is InputProblem.START_COLLIDES
    assert "crate" in colliding.reason
    not_finite = OPEN_SPACE.plan(stance_at(math.nan, 0.0), Pose2D(1.0, 0.0, 0.0))
    assert not_finite.outcome is PlanOutcome.INVALID_START
    assert not_finite.input_problem is InputProblem.START_NOT_FINITE
    assert OPEN_SPACE.plan(stance_at(0.0, 0.0), Pose2D(1.0, 0.0, 0.0)).input_problem is None


def test_snap_to_goal_ends_exactly_on_the_stand_pose() -> None:
    """The search stops within 5 cm / 0.1 rad of its goal; the arms need the stand pose
    itself. Snapping adds up to three checked steps that land both feet on it."""
    door = door_facing_robot(DoorOpening.PUSH, leaf_width=0.914, clear_opening=0.914, handle_offset=0.136)
    world = World.from_door(door)
    options = FootstepPlannerOptions(heuristic_weight=1.5, snap_to_goal=True)
    stand = stand_pose_for_opening(door, options)
    missed = 0
    for lateral, yaw in ((0.3, 0.25), (-0.25, -0.2), (0.05, 0.3), (-0.3, 0.1)):
        start = stance_at(-1.0, lateral, yaw)
        loose = _succeeded(FootstepPlanner(world, replace(options, snap_to_goal=False)).plan(start, stand)).plan
        missed += loose.final_stance.body_pose.distance_to(stand) > 0.005
        plan = _succeeded(FootstepPlanner(world, options).plan(start, stand)).plan
        final = plan.final_stance.body_pose
        assert final.distance_to(stand) < 1e-9 and abs(final.yaw_difference(stand)) < 1e-9
        assert kinematic_violations(plan) == [] and collisions_along(plan, world) == []
    assert missed > 0  # the scenarios do exercise the snapping


def test_a_start_inside_the_safety_margins_is_planned_without_them() -> None:
    """A walk stopped against the frame leaves the body within body_margin of the crate:
    plan() refuses, plan_from_within_margins() steps away and says why; a start that truly
    overlaps an obstacle stays refused."""
    options = FootstepPlannerOptions()
    near = options.body_half_width + options.body_margin / 2.0  # inside the margin, not the body
    world = World((Obstacle.rectangle("crate", (0.0, near + 0.15), 0.0, 0.3, 0.3),))
    planner = FootstepPlanner(world, options)
    start, goal = stance_at(0.0, 0.0), Pose2D(0.0, -0.6, 0.0)
    refused = planner.plan(start, goal)
    assert refused.outcome is PlanOutcome.INVALID_START and refused.input_problem is InputProblem.START_COLLIDES
    result, relaxed_from = planner.plan_from_within_margins(start, goal)
    _succeeded(result)
    assert "crate" in relaxed_from
    inside = World((Obstacle.rectangle("crate", (0.0, 0.3), 0.0, 0.3, 0.3),))
    result, relaxed_from = FootstepPlanner(inside, options).plan_from_within_margins(start, goal)
    assert result.outcome is PlanOutcome.INVALID_START and relaxed_from  # tried without margins, still refused


def test_only_a_colliding_start_is_planned_again_without_margins() -> None:
    """The retry branches on the structured cause, not on the reason's words: a non-finite
    start is refused once, without a second search."""
    result, relaxed_from = OPEN_SPACE.plan_from_within_margins(stance_at(math.nan, 0.0), Pose2D(1.0, 0.0, 0.0))
    assert result.input_problem is InputProblem.START_NOT_FINITE and relaxed_from == ""


@pytest.mark.parametrize("goal", [Pose2D(2.5, 0.3, 0.0), Pose2D(2.0, -0.4, 0.0),
                                  Pose2D(1.5, 0.5, 0.3)])
def test_weighted_astar_costs_at_least_astar_and_at_most_w_times(goal: Pose2D) -> None:
    weight = 2.0
    optimal = _succeeded(OPEN_SPACE.plan(stance_at(0.0, 0.0), goal)).plan
    weighted_planner = FootstepPlanner(World(), FootstepPlannerOptions(heuristic_weight=weight))
    weighted = _succeeded(weighted_planner.plan(stance_at(0.0, 0.0), goal)).plan
    assert weighted.cost >= optimal.cost - 1e-9
    assert weighted.cost <= weight * optimal.cost + 1e-9
    assert kinematic_violations(weighted) == []


def test_plan_reports_cost_and_statistics() -> None:
    result = _succeeded(plan_footsteps(stance_at(0.0, 0.0), Pose2D(1.0, 0.0, 0.0), World()))
    plan = result.plan
    assert plan.cost >= len(plan.steps) * DEFAULT_OPTIONS.step_cost
    assert plan.expansions == result.expansions > 0
    assert plan.planning_time == result.planning_time > 0.0
    assert plan.goal == Pose2D(1.0, 0.0, 0.0)


def test_with_world_reuses_the_planner_for_a_new_door_estimate() -> None:
    door = door_facing_robot(DoorOpening.PUSH, angle=math.pi / 2.0)
    planner = OPEN_SPACE.with_world(World.from_door(door))
    assert planner.options is OPEN_SPACE.options
    assert planner.world.obstacles
    result = _succeeded(planner.plan(stance_at(0.5, 0.0), through_door_pose(door)))
    assert collisions_along(result.plan, planner.world) == []
    closed = planner.with_world(World.from_door(door.with_angle(0.0)))
    assert closed.plan(stance_at(0.5, 0.0), through_door_pose(door)).outcome is \
        PlanOutcome.UNREACHABLE


def test_stand_pose_in_front_of_the_door_plane() -> None:
    door = door_facing_robot(DoorOpening.PUSH)
    stand = stand_pose_for_opening(door, DEFAULT_OPTIONS)
    start = in_front_of(door, 2.0)
    result = _succeeded(FootstepPlanner(World.from_door(door)).plan(
        stance_at(start.x, start.y, start.yaw), stand))
    assert result.plan.final_stance.body_pose.x < 2.0


def test_non_nominal_start_stance_is_planned_from() -> None:
    start = Stance(Footstep(0.0, 0.15, 0.2, Foot.LEFT), Footstep(0.1, -0.12, 0.0, Foot.RIGHT))
    result = _succeeded(OPEN_SPACE.plan(start, Pose2D(1.0, 0.0, 0.0)))
    assert kinematic_violations(result.plan) == []
    final = result.plan.final_stance
    assert relative_step(final.foot(result.plan.steps[-1].foot.other),
                         result.plan.steps[-1]) == pytest.approx((0.0, 0.2, 0.0), abs=1e-9)


def test_a_goal_kilometres_away_ends_within_the_bounds() -> None:
    wall = World((Obstacle.rectangle("wall", (5.0, 0.0), math.pi / 2.0, 3.0, 0.1),))
    options = FootstepPlannerOptions(max_expansions=200)
    result = FootstepPlanner(wall, options).plan(stance_at(0.0, 0.0), Pose2D(5.0e3, 0.0, 0.0))
    assert result.outcome is PlanOutcome.EXPANSION_LIMIT
    assert result.expansions == 200
