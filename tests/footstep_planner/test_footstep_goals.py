"""Goal poses from a door estimate, and the re-planning trigger."""

from __future__ import annotations

import math

import pytest

from footstep_planner.door import DoorOpening, HingeSide
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.footprint import FootprintChecker
from footstep_planner.footstep import Stance
from footstep_planner.goals import replan_needed, stand_pose_for_opening, through_door_pose
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.world import World

from footstep_scenes import door_facing_robot

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


def test_pull_stand_pose_with_the_body_far_enough_keeps_the_push_offset() -> None:
    door = door_facing_robot(DoorOpening.PULL)
    far = stand_pose_for_opening(door, OPTIONS, reach=1.4)
    along, _ = door.to_door(far.x, far.y)
    assert along == pytest.approx(door.leaf_width - door.handle_offset - 0.2)


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
