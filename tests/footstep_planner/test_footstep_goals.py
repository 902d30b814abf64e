"""Goal poses from a door estimate, and the re-planning trigger."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest
from footstep_scenes import collisions_along, door_facing_robot, in_front_of, kinematic_violations

from door_contract.vocabulary import DoorOpening, HingeSide
from footstep_planner.astar import FootstepPlanner
from footstep_planner.door import wall_obstacles
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.footprint import FootprintChecker
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.goals import pull_passage_waypoints, replan_needed, stand_pose_for_opening, through_door_pose
from footstep_planner.legs import plan_legs
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import PlanOutcome
from footstep_planner.world import World

OPTIONS = FootstepPlannerOptions()


@pytest.mark.parametrize("hinge_side", list(HingeSide))
def test_push_stand_pose_faces_the_door_at_arm_reach_towards_the_handle(
        hinge_side: HingeSide) -> None:
    door = door_facing_robot(DoorOpening.PUSH, hinge_side=hinge_side)
    stand = stand_pose_for_opening(door, OPTIONS, reach=0.5)
    along, normal = door.to_door(stand.x, stand.y)
    assert normal == pytest.approx(0.5)
    assert stand.yaw == pytest.approx(0.0)  # facing +x, the door
    handle_along = door.leaf_width - door.handle_offset
    assert door.clear_opening / 2.0 < along < handle_along  # shifted towards the handle
    # the handle is on the robot's right for a left hinge, on its left otherwise
    handle_side = -1.0 if hinge_side is HingeSide.LEFT else 1.0
    assert handle_side * (door.handle_point[1] - stand.y) > 0.0


@pytest.mark.parametrize("hinge_side", list(HingeSide))
def test_pull_stand_pose_lies_outside_the_doors_sweep(hinge_side: HingeSide) -> None:
    door = door_facing_robot(DoorOpening.PULL, hinge_side=hinge_side)
    stand = stand_pose_for_opening(door, OPTIONS)
    sweep = World.from_door(door, sweep=(0.0, math.pi / 2.0))
    only_sweep = World((sweep.obstacles[-1],))
    stance = Stance.nominal(stand, OPTIONS.nominal_foot_separation)
    assert FootprintChecker(only_sweep, OPTIONS).stance_collision(stance) is None
    assert FootprintChecker(sweep, OPTIONS).stance_collision(stance) is None
    # beside the handle side, further from the hinge than the door is wide
    along, normal = door.to_door(stand.x, stand.y)
    assert along > door.leaf_width
    assert math.hypot(along, normal) > door.leaf_width
    assert normal == pytest.approx(0.5)


def test_pull_stand_pose_far_enough_from_the_plane_is_just_past_the_latch_edge() -> None:
    """Beyond reach R·sin(sweep angle) + half depth the pulled leaf never reaches the torso:
    the base stands ``beyond_latch`` past the latch edge, where one hand reaches the handle
    and the other the gap at the free edge."""
    door = door_facing_robot(DoorOpening.PULL)
    stand = stand_pose_for_opening(door, OPTIONS, reach=0.65, sweep_half_depth=0.15, beyond_latch=0.05)
    along, normal = door.to_door(stand.x, stand.y)
    assert (along, normal) == pytest.approx((door.leaf_width + 0.05, 0.65))
    torso = replace(OPTIONS, body_half_depth=0.15 - OPTIONS.body_margin)
    pulled = World((World.from_door(door, sweep=(0.0, 0.45)).obstacles[-1],))
    body = Stance.nominal(stand, OPTIONS.nominal_foot_separation)
    assert FootprintChecker(pulled, torso).stance_collision(body) is None
    # 5 cm closer to the door the leaf would reach the torso: the pose moves beside the arc
    near = stand_pose_for_opening(door, OPTIONS, reach=0.55, sweep_half_depth=0.15)
    assert door.to_door(near.x, near.y)[0] > door.leaf_width + 0.3


@pytest.mark.parametrize("hinge_side", list(HingeSide))
def test_pull_passage_turns_towards_the_hinge_then_walks_through(hinge_side: HingeSide) -> None:
    door = door_facing_robot(DoorOpening.PULL, hinge_side=hinge_side)
    stand = stand_pose_for_opening(door, OPTIONS, reach=0.65, sweep_half_depth=0.15)
    turn, along_wall, facing, through = pull_passage_waypoints(door, stand)
    hinge_x, hinge_y = door.hinge_x, door.hinge_y
    # the turn keeps the stand position and looks along the wall at the hinge
    assert (turn.x, turn.y) == pytest.approx((stand.x, stand.y))
    heading = (math.cos(turn.yaw), math.sin(turn.yaw))
    assert heading[0] * (hinge_x - stand.x) + heading[1] * (hinge_y - stand.y) > 0.5
    assert door.to_door(along_wall.x, along_wall.y) == pytest.approx((door.clear_opening / 2.0, 0.65))
    assert facing.yaw == pytest.approx(door.facing_yaw)
    assert door.to_door(through.x, through.y)[1] == pytest.approx(-1.0)


def test_legs_join_into_one_alternating_collision_free_plan() -> None:
    door = door_facing_robot(DoorOpening.PULL, leaf_width=0.914, clear_opening=0.87, handle_offset=0.136)
    options = replace(OPTIONS, snap_to_goal=True, heuristic_weight=1.5)
    stand = stand_pose_for_opening(door, options, reach=0.65, sweep_half_depth=0.15)
    waypoints = pull_passage_waypoints(door, stand)
    world = World(wall_obstacles(door))
    result = plan_legs(FootstepPlanner(world, options), Stance.nominal(stand, options.nominal_foot_separation),
                       waypoints)
    assert result.succeeded, result.reason
    steps = result.plan.steps
    assert all(a.foot is not b.foot for a, b in zip(steps, steps[1:]))
    assert collisions_along(result.plan, world) == [] and kinematic_violations(result.plan) == []
    final = result.plan.final_stance.body_pose
    assert final.distance_to(waypoints[-1]) < 1e-9
    # it did turn in place first: some stance faces along the wall before any goes past it
    stances = result.plan.stances()
    first_turned = next(i for i, s in enumerate(stances) if abs(s.body_pose.yaw_difference(waypoints[0])) < 0.05)
    assert all(door.to_door(s.body_pose.x, s.body_pose.y)[1] > 0.3 for s in stances[:first_turned + 1])


def test_a_failing_leg_names_itself() -> None:
    door = door_facing_robot(DoorOpening.PULL)
    world = World(wall_obstacles(door))
    inside_wall = Pose2D(*door.to_world(-1.0, 0.0), 0.0)
    stand = in_front_of(door, 1.0)
    result = plan_legs(FootstepPlanner(world, OPTIONS), Stance.nominal(stand, OPTIONS.nominal_foot_separation),
                       (stand, inside_wall))
    assert not result.succeeded and result.reason.startswith("leg 2 of 2:")
    assert plan_legs(FootstepPlanner(world, OPTIONS), Stance.nominal(stand, 0.2), ()).outcome \
        is PlanOutcome.INVALID_GOAL


def test_through_door_pose_is_centred_one_metre_beyond() -> None:
    door = door_facing_robot(DoorOpening.PUSH, angle=math.pi / 2.0)
    goal = through_door_pose(door)
    assert (goal.x, goal.y) == pytest.approx((3.0, 0.0))
    assert goal.yaw == pytest.approx(0.0)


def test_replan_when_the_door_moves_beyond_the_threshold() -> None:
    assert not replan_needed(1.50, 1.45, threshold=0.1)
    assert replan_needed(1.50, 1.30, threshold=0.1)
    assert replan_needed(-3.1, 3.1, threshold=0.05)  # 0.083 rad apart across the wrap
    assert not replan_needed(-3.1, 3.1, threshold=0.1)


def test_replan_rejects_a_nan_measurement() -> None:
    with pytest.raises(FootstepPlannerError) as caught:
        replan_needed(0.0, math.nan)
    assert caught.value.field == "measured_door_angle"


@pytest.mark.parametrize("reach", [0.0, -0.5, math.nan, 3.0])
def test_unreachable_arm_reach_is_rejected(reach: float) -> None:
    with pytest.raises(FootstepPlannerError) as caught:
        stand_pose_for_opening(door_facing_robot(), OPTIONS, reach=reach)
    assert caught.value.field == "reach"


@pytest.mark.parametrize(("field", "value"), [("pull_sweep_angle", 0.0), ("pull_sweep_angle", 2.0),
                                              ("pull_sweep_angle", math.nan), ("beyond_latch", 1.5),
                                              ("beyond_latch", math.inf)])
def test_bad_pull_stand_parameters_are_rejected(field: str, value: float) -> None:
    with pytest.raises(FootstepPlannerError) as caught:
        stand_pose_for_opening(door_facing_robot(DoorOpening.PULL), OPTIONS, **{field: value})
    assert caught.value.field == field


@pytest.mark.parametrize("hinge_side", list(HingeSide))
def test_each_leg_starts_with_the_other_foot_so_no_foot_steps_in_place(hinge_side: HingeSide) -> None:
    """A walk and its mirror image step alike: the right-hinged pull passage used to begin its
    walk along the wall with the foot that had ended the turn, and then stepped in place."""
    door = door_facing_robot(DoorOpening.PULL, hinge_side=hinge_side, leaf_width=0.914, clear_opening=0.87,
                             handle_offset=0.136)
    options = replace(OPTIONS, snap_to_goal=True)
    stand = stand_pose_for_opening(door, options, reach=0.65, sweep_half_depth=0.15)
    start = Stance.nominal(stand, options.nominal_foot_separation)
    result = plan_legs(FootstepPlanner(World(wall_obstacles(door)), options), start, pull_passage_waypoints(door, stand))
    assert result.succeeded, result.reason
    where = {start.left.foot: start.left.pose, start.right.foot: start.right.pose}
    in_place = 0
    for step in result.plan.steps:
        in_place += where[step.foot].distance_to(step.pose) < 1e-3 and where[step.foot].yaw_difference(step.pose) < 1e-3
        where[step.foot] = step.pose
    assert in_place == 0
