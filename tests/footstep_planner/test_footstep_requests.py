"""From a request to a planning problem without ROS: options from the robot profile, the
start stance, the legs of each goal; and every request of the task plans within the
profile's limits, as they are and 30 % shorter."""

from __future__ import annotations

import pytest
from footstep_scenes import SHRINKS, collisions_along, door_facing_robot, kinematic_violations, profile_options

from door_contract.vocabulary import DoorOpening, HingeSide, WalkGoal
from door_robot.profile import load_profile
from footstep_planner.astar import FootstepPlanner
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.legs import plan_legs
from footstep_planner.narrow import PASSAGE_CLEARANCE, PullPassage
from footstep_planner.pull_passage import PULL_LEG_NAMES
from footstep_planner.requests import (
    GoalSettings,
    options_for_problem,
    passage_angle,
    start_stance,
    walk_problem,
)
from footstep_planner.robot_limits import STEP_LIMIT_MARGIN, options_for_walking

SETTINGS = GoalSettings()


@pytest.mark.parametrize("profile", ["talos", "atlas_v4", "drc_hubo"])
def test_options_come_from_the_robot_profile_within_its_margins(profile: str, request: pytest.FixtureRequest) -> None:
    if profile != "talos":  # their URDFs are real files in ../shared/data, not in a package
        request.getfixturevalue("shared_data")
    walking = load_profile(profile).walking
    options = options_for_walking(walking, 2.5, 20_000, 30.0)
    assert options.max_stride == pytest.approx(walking.max_stride * STEP_LIMIT_MARGIN)
    assert options.max_turn == pytest.approx(walking.max_turn * STEP_LIMIT_MARGIN)
    assert options.max_side_step == pytest.approx(walking.max_side_step * STEP_LIMIT_MARGIN)
    assert options.nominal_foot_separation == walking.foot_separation
    assert options.body_half_width == walking.body_width / 2 and options.body_half_depth == walking.body_depth / 2
    assert (options.heuristic_weight, options.max_expansions, options.max_planning_time) == (2.5, 20_000, 30.0)


def test_the_start_is_the_measured_feet_else_the_walked_plan_else_the_nominal_stance() -> None:
    body = Pose2D(1.0, 2.0, 0.3)
    measured = (Pose2D(1.0, 2.1, 0.3), Pose2D(1.02, 1.9, 0.25))
    stance = start_stance(body, 0.17, feet=measured)
    assert (stance.left.x, stance.right.yaw) == (1.0, 0.25)
    walked = Stance.nominal(Pose2D(1.01, 2.0, 0.31), 0.17)
    assert start_stance(body, 0.17, planned=walked) == walked
    elsewhere = Stance.nominal(Pose2D(1.5, 2.0, 0.3), 0.17)
    assert start_stance(body, 0.17, planned=elsewhere) == Stance.nominal(body, 0.17)
    assert start_stance(body, 0.17) == Stance.nominal(body, 0.17)


def test_goal_settings_are_read_from_the_node_parameters() -> None:
    settings = GoalSettings.from_parameters({"stand_reach": 0.55, "beyond_door": 2, "heuristic_weight": 2.5})
    assert settings.stand_reach == 0.55 and settings.beyond_door == 2.0 and settings.stand_reach_pull == 0.65
    assert passage_angle(0.2, settings) == settings.passage_door_angle and passage_angle(1.9, settings) == 1.9


def test_a_robots_profile_stance_sets_its_stand_distances_over_the_parameters() -> None:
    """G1's hands reach less than TALOS's: its profile's ``stance`` replaces the parameters'
    stand distances (TALOS's), the other settings stay the parameters'."""
    parameters = {"stand_reach_pull": 0.65, "push_side_reach": 0.5, "beyond_door": 2.0}
    g1 = GoalSettings.for_robot("g1", parameters)
    assert (g1.push_side_reach, g1.stand_reach_pull, g1.beyond_door) == (0.42, 0.45, 2.0)
    assert GoalSettings.for_robot("talos", parameters) == GoalSettings.from_parameters(parameters)


def _start(options, distance: float = 2.5, lateral: float = 0.3, yaw: float = 0.3) -> Stance:
    return Stance.nominal(Pose2D(2.0 - distance, lateral, yaw), options.nominal_foot_separation)


def test_each_goal_has_its_legs_and_snapping() -> None:
    options = profile_options()
    facing = GoalSettings.from_parameters({"pull_passage": "facing"})
    wide_pull = walk_problem(WalkGoal.THROUGH, door_facing_robot(DoorOpening.PULL), _start(options), options, facing)
    assert [leg.name for leg in wide_pull.legs] == list(PULL_LEG_NAMES)
    assert facing.pull_passage is PullPassage.FACING and SETTINGS.pull_passage is PullPassage.SIDEWAYS
    held = walk_problem(WalkGoal.THROUGH, door_facing_robot(DoorOpening.PULL), _start(options), options, SETTINGS)
    assert [leg.name for leg in held.legs] == [*PULL_LEG_NAMES[:2], "turn sideways before the doorway",
                                                "side-step through the doorway", "turn to face away"]
    assert all(o.name.startswith(("wall", "post")) for o in wide_pull.world.obstacles)  # the leaf is pushed
    narrow = door_facing_robot(DoorOpening.PULL, leaf_width=0.8, clear_opening=0.8, handle_offset=0.07)
    narrow_pull = walk_problem(WalkGoal.THROUGH, narrow, _start(options), options, facing)
    assert [leg.name for leg in narrow_pull.legs][:2] == list(PULL_LEG_NAMES[:2]) and len(narrow_pull.legs) == 5
    facing_push = GoalSettings.from_parameters({"push_passage": "facing"})
    push = walk_problem(WalkGoal.THROUGH, door_facing_robot(DoorOpening.PUSH), _start(options), options, facing_push)
    assert len(push.legs) == 1 and push.door.angle == SETTINGS.passage_door_angle
    assert options_for_problem(push, WalkGoal.THROUGH, options) is options
    stand = walk_problem(WalkGoal.STAND, door_facing_robot(DoorOpening.PUSH), _start(options), options, SETTINGS)
    assert any(o.name == "door_leaf" for o in stand.world.obstacles)
    assert options_for_problem(stand, WalkGoal.STAND, options).snap_to_goal
    assert options_for_problem(wide_pull, WalkGoal.THROUGH, options).snap_to_goal


@pytest.mark.parametrize("shrink", SHRINKS)
@pytest.mark.parametrize("opening", list(DoorOpening))
@pytest.mark.parametrize("hinge", list(HingeSide))
@pytest.mark.parametrize("width", [0.80, 0.90, 1.00])
def test_the_task_plans_from_the_profile_even_with_a_shorter_stride_and_turn(
        width: float, hinge: HingeSide, opening: DoorOpening, shrink: float) -> None:
    """Approach from 2.5 m, 0.3 m aside, turned 0.3 rad; then the passage from the stand pose.
    Every plan within the (scaled) step limits and clear of the wall, posts and leaf."""
    options = profile_options(shrink)
    door = door_facing_robot(opening, hinge_side=hinge, leaf_width=width, clear_opening=width, handle_offset=0.07)
    approach = walk_problem(WalkGoal.STAND, door, _start(options), options, SETTINGS)
    stand_options = options_for_problem(approach, WalkGoal.STAND, options)
    result = FootstepPlanner(approach.world, stand_options).plan(approach.start, approach.legs[0].goal)
    assert result.succeeded, result.reason
    assert collisions_along(result.plan, approach.world, options) == []
    assert kinematic_violations(result.plan, options) == []
    opened = door.with_angle(0.35 if opening is DoorOpening.PULL else 0.0)
    passage = walk_problem(WalkGoal.THROUGH, opened, result.plan.final_stance, options, SETTINGS)
    through = plan_legs(FootstepPlanner(passage.world, options_for_problem(passage, WalkGoal.THROUGH, options)),
                        passage.start, passage.legs)
    assert through.succeeded, through.reason
    assert collisions_along(through.plan, passage.world, options) == []
    assert kinematic_violations(through.plan, options) == []
    beyond = passage.door.to_door(through.plan.final_stance.body_pose.x, through.plan.final_stance.body_pose.y)[1]
    assert beyond <= -SETTINGS.beyond_door + options.goal_position_tolerance + 1e-6


@pytest.mark.parametrize("hinge", list(HingeSide))
@pytest.mark.parametrize("width", [0.80, 0.87, 1.00])
@pytest.mark.parametrize("shift", [0.0, 0.14])
def test_a_held_pull_leaf_passage_plans_clear_of_the_frame(width: float, hinge: HingeSide, shift: float) -> None:
    """pull_passage = sideways: from the stand pose, the five legs plan within the step limits,
    clear of wall and posts (the body box with its offset), every side-step on the line moved
    towards the body's back by the shift (capped so the box's back clears the latch post)."""
    options = profile_options()
    settings = GoalSettings.from_parameters({"pull_passage": "sideways", "pull_passage_shift": shift})
    door = door_facing_robot(DoorOpening.PULL, hinge_side=hinge, leaf_width=width, clear_opening=width,
                             handle_offset=0.07).with_angle(0.35)
    stand = walk_problem(WalkGoal.STAND, door, _start(options), options, settings).legs[0].goal
    start = Stance.nominal(stand, options.nominal_foot_separation)
    passage = walk_problem(WalkGoal.THROUGH, door, start, options, settings)
    assert len(passage.legs) == 5
    through = plan_legs(FootstepPlanner(passage.world, options_for_problem(passage, WalkGoal.THROUGH, options)),
                        passage.start, passage.legs)
    assert through.succeeded, through.reason
    assert collisions_along(through.plan, passage.world, options) == []
    assert kinematic_violations(through.plan, options) == []
    line = door.to_door(passage.legs[3].goal.x, passage.legs[3].goal.y)[0]
    back = options.body_half_depth - options.body_offset + options.body_margin
    assert door.clear_opening / 2.0 <= line <= door.clear_opening / 2.0 + shift + 1e-9
    assert line + back <= door.clear_opening - PASSAGE_CLEARANCE + 1e-9
