"""Doorways narrower than the body are passed sideways along the centre line, in three legs
that each plan quickly; doors the body fits keep their single leg."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from footstep_scenes import SHRINKS, collisions_along, door_facing_robot, kinematic_violations, profile_options

from door_contract.vocabulary import DoorOpening, HingeSide
from footstep_planner.astar import FootstepPlanner
from footstep_planner.door import wall_obstacles
from footstep_planner.footprint import FootprintChecker
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.geometry import wrap_angle
from footstep_planner.goals import through_door_pose
from footstep_planner.legs import plan_legs
from footstep_planner.narrow import PASSAGE_CLEARANCE, SIDEWAYS, hold_leaf_line, passage_legs, passage_turn
from footstep_planner.world import World

OPTIONS = profile_options()
BODY_ACROSS = 2.0 * (OPTIONS.body_half_width + OPTIONS.body_margin)  # 0.84 m for TALOS
BODY_DEEP = 2.0 * OPTIONS.body_reach_depth  # 0.60 m


def _door(width: float, opening: DoorOpening, hinge: HingeSide = HingeSide.LEFT):
    return door_facing_robot(opening, hinge_side=hinge, leaf_width=width, clear_opening=width, handle_offset=0.07)


def test_the_body_passes_facing_sideways_or_not_at_all() -> None:
    fits_facing = BODY_ACROSS + 2 * PASSAGE_CLEARANCE
    fits_sideways = BODY_DEEP + 2 * PASSAGE_CLEARANCE
    assert passage_turn(_door(fits_facing + 0.01, DoorOpening.PUSH), OPTIONS) == 0.0
    assert passage_turn(_door(fits_facing - 0.01, DoorOpening.PUSH), OPTIONS) == pytest.approx(math.pi / 2)
    assert passage_turn(_door(fits_sideways - 0.01, DoorOpening.PUSH), OPTIONS) is None


@pytest.mark.parametrize("opening", list(DoorOpening))
def test_sideways_along_the_centre_line_clears_the_frame(opening: DoorOpening) -> None:
    """The band the turned body sweeps through the wall fits between the jambs: every body
    pose on the centre line between the side-step leg's ends is collision-free."""
    door = _door(0.80, opening).with_angle(1.57 if opening is DoorOpening.PUSH else 0.0)
    world = World.from_door(door) if opening is DoorOpening.PUSH else World(wall_obstacles(door))
    before, through, _ = passage_legs(door, OPTIONS, 1.0)
    start_s, end_s = door.to_door(before.goal.x, before.goal.y)[1], door.to_door(through.goal.x, through.goal.y)[1]
    checker = FootprintChecker(world, OPTIONS)
    for s in np.linspace(start_s, end_s, 60):
        x, y = door.to_world(door.clear_opening / 2.0, float(s))
        assert not checker.body_collides(Pose2D(x, y, before.goal.yaw)), s


def test_a_door_the_body_fits_keeps_one_leg() -> None:
    door = _door(0.95, DoorOpening.PUSH).with_angle(1.57)
    (leg,) = passage_legs(door, OPTIONS, 1.0)
    assert leg.goal == through_door_pose(door, 1.0) and not leg.pruning.prunes


@pytest.mark.parametrize("hinge", list(HingeSide))
def test_narrow_legs_turn_towards_the_hinge_then_side_step_then_face_away(hinge: HingeSide) -> None:
    door = _door(0.80, DoorOpening.PUSH, hinge).with_angle(1.57)
    before, through, final = passage_legs(door, OPTIONS, 1.0)
    latch_x, latch_y = door.latch_direction
    towards_hinge = math.atan2(-latch_y, -latch_x)
    assert abs(wrap_angle(before.goal.yaw - towards_hinge)) < 1e-9 and through.goal.yaw == before.goal.yaw
    assert through.pruning == SIDEWAYS
    assert final.goal.yaw == pytest.approx(door.facing_yaw)
    s_values = [door.to_door(leg.goal.x, leg.goal.y)[1] for leg in (before, through, final)]
    assert s_values[0] > 0.0 > s_values[1] >= s_values[2] - 1e-9
    # past the open leaf (within W + thickness of the hinge) with room to turn
    assert -s_values[1] > door.leaf_width


@pytest.mark.parametrize("shrink", SHRINKS)
@pytest.mark.parametrize("opening", list(DoorOpening))
@pytest.mark.parametrize("width", [0.80, 0.84])
def test_a_narrow_passage_plans_collision_free_within_the_limits(width: float, opening: DoorOpening,
                                                                 shrink: float) -> None:
    options = profile_options(shrink)
    door = _door(width, opening).with_angle(1.57 if opening is DoorOpening.PUSH else 0.35)
    world = World.from_door(door) if opening is DoorOpening.PUSH else World(wall_obstacles(door))
    legs = passage_legs(door, options, 1.0)
    assert len(legs) == 3
    start = Stance.nominal(Pose2D(*door.to_world(door.clear_opening / 2.0, 1.0), door.facing_yaw),
                           options.nominal_foot_separation)
    result = plan_legs(FootstepPlanner(world, replace(options, snap_to_goal=True)), start, legs)
    assert result.succeeded, result.reason
    assert collisions_along(result.plan, world, options) == []
    assert kinematic_violations(result.plan, options) == []
    assert result.plan.final_stance.body_pose.distance_to(legs[-1].goal) < 1e-9


@pytest.mark.parametrize("hinge", list(HingeSide))
def test_a_held_pull_leaf_is_passed_sideways_towards_the_body_s_back(hinge: HingeSide) -> None:
    """hold_leaf: sideways although the body fits facing, on the line shifted towards the
    body's back (the latch: it faces the hinge)."""
    door = _door(0.95, DoorOpening.PULL, hinge)
    assert len(passage_legs(door, OPTIONS, 1.0)) == 1
    before, through, _ = passage_legs(door, OPTIONS, 1.0, hold_leaf=0.12)
    latch_x, latch_y = door.latch_direction
    assert abs(wrap_angle(before.goal.yaw - math.atan2(-latch_y, -latch_x))) < 1e-9
    line = door.to_door(through.goal.x, through.goal.y)[0]
    assert line == pytest.approx(door.clear_opening / 2.0 + 0.12)  # towards the latch: the body's back
    assert door.to_door(before.goal.x, before.goal.y)[0] == pytest.approx(line)
    assert hold_leaf_line(door, OPTIONS, through.goal.yaw + math.pi, 0.12) == pytest.approx(door.clear_opening / 2.0 - 0.12)


def test_a_held_leaf_too_narrow_for_the_body_sideways_gets_the_direct_leg() -> None:
    door = _door(BODY_DEEP + 2 * PASSAGE_CLEARANCE - 0.01, DoorOpening.PULL)
    assert passage_turn(door, OPTIONS, sideways=True) is None
    assert len(passage_legs(door, OPTIONS, 1.0, hold_leaf=0.1)) == 1
