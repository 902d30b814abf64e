"""A push door passed sideways, its back to the hinge (footstep_planner.push_passage, the default)."""

import math
from dataclasses import replace

import pytest
from footstep_scenes import collisions_along, door_facing_robot, kinematic_violations, profile_options

from door_contract.vocabulary import DoorOpening, HingeSide, WalkGoal
from footstep_planner.astar import FootstepPlanner
from footstep_planner.errors import FootstepPlannerError, NoWalkForDoor
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.goals import PUSH_LINE_CLEARANCE, push_line, push_stand_pose
from footstep_planner.legs import plan_legs
from footstep_planner.plan import InputProblem
from footstep_planner.proposal import contract_footsteps
from footstep_planner.push_passage import PUSH_LEG_NAMES, DoorwayCut, PushPassage
from footstep_planner.requests import GoalSettings, WalkPlanners, options_for_problem, walk_problem
from footstep_planner.world import World

SIDEWAYS = GoalSettings.from_parameters({"push_passage": "sideways"})


def test_sideways_is_the_default_and_facing_is_read_from_the_parameters() -> None:
    assert GoalSettings().push_passage is PushPassage.SIDEWAYS == SIDEWAYS.push_passage
    assert GoalSettings.from_parameters({"push_passage": "facing"}).push_passage is PushPassage.FACING


def test_from_anywhere_but_the_stand_pose_the_passage_first_walks_to_its_line() -> None:
    options = profile_options()
    door = door_facing_robot(DoorOpening.PUSH)
    elsewhere = Stance.nominal(Pose2D(1.4, 0.0, 0.0), options.nominal_foot_separation)  # facing, 0.6 m out
    problem = walk_problem(WalkGoal.THROUGH, door, elsewhere, options, SIDEWAYS)
    assert [leg.name for leg in problem.legs] == ["to the side-step line", *PUSH_LEG_NAMES]
    through = plan_legs(FootstepPlanner(problem.world, options_for_problem(problem, WalkGoal.THROUGH, options)),
                        problem.start, problem.legs)
    assert through.succeeded, through.reason


@pytest.mark.parametrize("hinge", list(HingeSide))
def test_the_stand_pose_is_sideways_beside_the_opening_its_back_to_the_hinge(hinge: HingeSide) -> None:
    """Reach in front of the plane, offset towards the latch, facing along the wall towards the
    latch; the door on the side of the hinge-side hand (the one that opens it)."""
    options = profile_options()
    door = door_facing_robot(DoorOpening.PUSH, hinge_side=hinge)
    stand = push_stand_pose(door, options, reach=0.45, offset=0.05)
    along, normal = door.to_door(stand.x, stand.y)
    assert (along, normal) == pytest.approx((door.clear_opening / 2.0 + 0.05, 0.45))
    heading = (math.cos(stand.yaw), math.sin(stand.yaw))
    assert heading == pytest.approx(door.latch_direction)
    assert heading[0] * (door.hinge_x - stand.x) + heading[1] * (door.hinge_y - stand.y) < 0.0  # hinge behind
    left = (-heading[1], heading[0])
    hinge_hand = 1.0 if hinge is HingeSide.LEFT else -1.0  # the robot's left hand for a left hinge
    handle_x, handle_y = door.handle_point
    assert hinge_hand * (left[0] * (handle_x - stand.x) + left[1] * (handle_y - stand.y)) > 0.0


@pytest.mark.parametrize("width", [0.80, 0.90, 1.00])
def test_the_line_keeps_the_body_box_off_the_latch_side_post(width: float) -> None:
    options = profile_options()
    door = door_facing_robot(DoorOpening.PUSH, leaf_width=width, clear_opening=width, handle_offset=0.07)
    line = push_line(door, options, offset=0.12)
    front = options.body_half_depth + options.body_offset + options.body_margin
    assert width / 2.0 <= line <= width / 2.0 + 0.12 + 1e-12
    assert line + front <= width - PUSH_LINE_CLEARANCE + 1e-9
    assert push_line(door, options, offset=-0.05) == pytest.approx(width / 2.0 - 0.05)  # towards the hinge: as asked


@pytest.mark.parametrize("hinge", list(HingeSide))
@pytest.mark.parametrize("width", [0.80, 0.90, 1.00])
def test_the_door_is_walked_to_and_passed_sideways_within_the_step_limits(width: float, hinge: HingeSide) -> None:
    """Approach from 2.5 m, 0.3 m aside, turned 0.3 rad, to the sideways stand pose; then the three
    legs: side-step through, step away from the leaf, turn to face away; clear of wall and posts."""
    options = profile_options()
    door = door_facing_robot(DoorOpening.PUSH, hinge_side=hinge, leaf_width=width, clear_opening=width,
                             handle_offset=0.07)
    start = Stance.nominal(Pose2D(-0.5, 0.3, 0.3), options.nominal_foot_separation)
    approach = walk_problem(WalkGoal.STAND, door, start, options, SIDEWAYS)
    walked = FootstepPlanner(approach.world, options_for_problem(approach, WalkGoal.STAND, options)).plan(
        approach.start, approach.legs[0].goal)
    assert walked.succeeded, walked.reason
    assert walked.plan is not None and collisions_along(walked.plan, approach.world, options) == []
    passage = walk_problem(WalkGoal.THROUGH, door, walked.plan.final_stance, options, SIDEWAYS)
    assert [leg.name for leg in passage.legs] == list(PUSH_LEG_NAMES)
    assert all(o.name.startswith(("wall", "post")) for o in passage.world.obstacles)  # the robot pushes the leaf
    through = plan_legs(FootstepPlanner(passage.world, options_for_problem(passage, WalkGoal.THROUGH, options)),
                        passage.start, passage.legs)
    assert through.succeeded, through.reason
    assert through.plan is not None
    assert collisions_along(through.plan, passage.world, options) == []
    assert kinematic_violations(through.plan, options) == []
    end = through.plan.final_stance.body_pose
    beyond = passage.door.to_door(end.x, end.y)[1]
    assert beyond <= -SIDEWAYS.beyond_door + options.goal_position_tolerance
    assert abs(math.remainder(end.yaw - door.facing_yaw, 2 * math.pi)) <= options.goal_yaw_tolerance


@pytest.mark.parametrize("hinge", list(HingeSide))
def test_a_passage_from_inside_the_margins_by_the_latch_post_is_planned_without_them_for_its_first_leg(
        hinge: HingeSide) -> None:
    """The robot stands 3 cm nearer the latch post than its stand pose (as a measured stance
    after the opening once did): with the margins the body box touches the post and the
    passage is refused; WalkPlanners plans the first leg without the margins, says why, and the
    plan steps away from the post. (Each of the three repeats had failed alike.)"""
    options = profile_options()
    door = door_facing_robot(DoorOpening.PUSH, hinge_side=hinge, leaf_width=0.80, clear_opening=0.80,
                             handle_offset=0.07)
    stand = push_stand_pose(door, options, reach=SIDEWAYS.push_side_reach, offset=SIDEWAYS.push_stand_offset)
    towards_latch = PUSH_LINE_CLEARANCE + options.body_margin / 2.0  # inside the margin, clear of the body
    crowded = Pose2D(stand.x + towards_latch * math.cos(stand.yaw), stand.y + towards_latch * math.sin(stand.yaw),
                     stand.yaw)
    passage = walk_problem(WalkGoal.THROUGH, door, Stance.nominal(crowded, options.nominal_foot_separation),
                           options, SIDEWAYS)
    search = options_for_problem(passage, WalkGoal.THROUGH, options)
    refused = plan_legs(FootstepPlanner(passage.world, search), passage.start, passage.legs)
    assert refused.input_problem is InputProblem.START_COLLIDES, refused.reason
    through, relaxed_from = WalkPlanners().plan(passage, search)
    assert through.succeeded, through.reason
    assert "post" in relaxed_from
    assert through.plan is not None and kinematic_violations(through.plan, options) == []


@pytest.mark.parametrize("hinge", list(HingeSide))
@pytest.mark.parametrize("width", [0.90, 0.95, 1.0])
def test_a_wide_doors_doorway_walk_is_the_passage_cut_at_the_plane_and_the_walk_on_starts_there(
        width: float, hinge: HingeSide) -> None:
    """A door at least push_tuck_min_width wide: the doorway walk is the one-walk passage's plan
    from the same stance, cut at its first stance at most push_tuck_at before the door plane
    after an even number of /footstep_plan steps (the walk on starts with the left foot); a walk
    "through" from there plans the passage's legs without going back to the stand pose."""
    options = profile_options()
    door = door_facing_robot(DoorOpening.PUSH, hinge_side=hinge, leaf_width=width, clear_opening=width,
                             handle_offset=0.07)
    stand = push_stand_pose(door, options, reach=SIDEWAYS.push_side_reach, offset=SIDEWAYS.push_stand_offset)
    start = Stance.nominal(stand, options.nominal_foot_separation)
    planners = WalkPlanners()
    plans = {}
    for goal in (WalkGoal.THROUGH, WalkGoal.DOORWAY):
        problem = walk_problem(goal, door, start, options, SIDEWAYS)
        assert [leg.name for leg in problem.legs] == list(PUSH_LEG_NAMES)
        result, _ = planners.plan(problem, options_for_problem(problem, goal, options))
        assert result.succeeded and result.plan is not None, result.reason
        plans[goal] = result.plan
    whole, doorway = plans[WalkGoal.THROUGH], plans[WalkGoal.DOORWAY]
    count = len(doorway.steps)
    assert 0 < count < len(whole.steps) and doorway.steps == whole.steps[:count]
    assert len(contract_footsteps(start, doorway)) % 2 == 0
    normals = [door.to_door(s.body_pose.x, s.body_pose.y)[1] for s in whole.stances()]
    assert normals[count - 1] <= SIDEWAYS.push_tuck_at
    eligible = [i for i in range(count - 1) if len(contract_footsteps(start, replace(whole, steps=whole.steps[:i + 1]))) % 2 == 0]
    assert all(normals[i] > SIDEWAYS.push_tuck_at for i in eligible)  # the first such stance
    assert doorway.goal == doorway.final_stance.body_pose
    onward = walk_problem(WalkGoal.THROUGH, door, doorway.final_stance, options, SIDEWAYS)
    assert [leg.name for leg in onward.legs] == list(PUSH_LEG_NAMES)
    on, _ = planners.plan(onward, options_for_problem(onward, WalkGoal.THROUGH, options))
    assert on.succeeded and on.plan is not None, on.reason
    assert collisions_along(on.plan, onward.world, options) == []


@pytest.mark.parametrize("width", [0.80, 0.87])
def test_a_narrow_door_has_no_doorway_walk_and_says_why(width: float) -> None:
    """Narrower than push_tuck_min_width: the doorway walk is NoWalkForDoor (answered SKIPPED),
    naming the width and the parameter; a door passed facing has none either."""
    options = profile_options()
    door = door_facing_robot(DoorOpening.PUSH, leaf_width=width, clear_opening=width, handle_offset=0.07)
    start = Stance.nominal(push_stand_pose(door, options, reach=0.5, offset=0.12), options.nominal_foot_separation)
    with pytest.raises(NoWalkForDoor, match=rf"{width:.2f} m wide.*push_tuck_min_width"):
        walk_problem(WalkGoal.DOORWAY, door, start, options, SIDEWAYS)
    wide = door_facing_robot(DoorOpening.PUSH, leaf_width=1.0, clear_opening=1.0, handle_offset=0.07)
    with pytest.raises(NoWalkForDoor, match="facing"):
        walk_problem(WalkGoal.DOORWAY, wide, start, options, GoalSettings.from_parameters({"push_passage": "facing"}))
    assert not issubclass(NoWalkForDoor, FootstepPlannerError)  # not bad input: not REJECTED


def test_a_doorway_cut_validates_its_distance_and_keeps_a_plan_that_never_reaches_it() -> None:
    door = door_facing_robot(DoorOpening.PUSH, leaf_width=1.0, clear_opening=1.0, handle_offset=0.07)
    with pytest.raises(FootstepPlannerError, match="at"):
        DoorwayCut(door, math.nan)
    options = profile_options()
    start = Stance.nominal(Pose2D(0.5, 0.0, 0.0), options.nominal_foot_separation)  # 1.5 m before the plane
    short = FootstepPlanner(World(()), options).plan(start, Pose2D(0.9, 0.0, 0.0))
    assert short.plan is not None and DoorwayCut(door, 0.05).cut(short.plan) == short.plan
