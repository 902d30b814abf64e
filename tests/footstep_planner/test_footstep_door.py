"""Door geometry: where the hinge, latch, leaf, wall and sweep are."""

from __future__ import annotations

import math

import numpy as np
import pytest
from footstep_scenes import door_facing_robot

from door_contract.vocabulary import DoorOpening, HingeSide
from footstep_planner.door import DoorGeometry, door_obstacles, sweep_obstacle
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.world import World


def _names(door: DoorGeometry) -> list[str]:
    return [obstacle.name for obstacle in door_obstacles(door)]


def test_left_hinge_is_on_the_robots_left() -> None:
    door = door_facing_robot(hinge_side=HingeSide.LEFT)
    assert door.hinge_y > 0.0  # robot faces +x, its left is +y
    assert door.latch_direction == pytest.approx((0.0, -1.0))
    assert door.handle_point[1] < 0.0  # handle on the robot's right


def test_right_hinge_mirrors_the_left() -> None:
    door = door_facing_robot(hinge_side=HingeSide.RIGHT)
    assert door.hinge_y < 0.0
    assert door.latch_direction == pytest.approx((0.0, 1.0))


def test_door_world_has_wall_posts_and_leaf() -> None:
    door = door_facing_robot()
    assert _names(door) == ["wall_hinge_side", "wall_latch_side", "post_hinge_side",
                            "post_latch_side", "door_leaf"]
    with_sweep = door_obstacles(door, sweep=(0.0, math.pi / 2.0))
    assert with_sweep[-1].name == "door_sweep"


def test_closed_door_blocks_the_opening_and_open_door_clears_it() -> None:
    probe = (np.array([2.0]), np.array([0.0]), np.array([0.0]))
    closed = World.from_door(door_facing_robot(angle=0.0))
    open_door = World.from_door(door_facing_robot(angle=math.pi / 2.0))
    # a thin probe across the doorway plane, in the middle of the opening
    assert closed.rectangles_collide(*probe, 0.4, 0.02)[0]
    assert not open_door.rectangles_collide(*probe, 0.4, 0.02)[0]


@pytest.mark.parametrize("opening, side", [(DoorOpening.PUSH, 1.0), (DoorOpening.PULL, -1.0)])
def test_leaf_at_90_degrees_lies_beside_the_opening_on_the_swing_side(
        opening: DoorOpening, side: float) -> None:
    door = door_facing_robot(opening, angle=math.pi / 2.0)
    leaf = next(o for o in door_obstacles(door) if o.name == "door_leaf").array
    # PUSH swings away from the robot (x > 2), PULL towards it (x < 2)
    assert np.all(side * (leaf[:, 0] - 2.0) >= -1e-9)
    assert np.max(np.abs(leaf[:, 0] - 2.0)) == pytest.approx(door.leaf_width)
    # beside the opening, on the hinge side (y >= hinge y)
    assert np.all(leaf[:, 1] >= door.hinge_y - 1e-9)


def test_sweep_contains_every_leaf_pose() -> None:
    door = door_facing_robot(DoorOpening.PULL)
    sweep = World((sweep_obstacle(door, 0.0, math.pi / 2.0),))
    for angle in np.linspace(0.0, math.pi / 2.0, 13):
        leaf = next(o for o in door_obstacles(door.with_angle(float(angle)))
                    if o.name == "door_leaf").array
        inside = sweep.near_obstacles(leaf, 1e-9)
        assert inside.all(), f"leaf corner outside the sweep at {angle:.2f} rad"


def test_from_handle_recovers_the_hinge() -> None:
    door = door_facing_robot(DoorOpening.PULL, hinge_side=HingeSide.RIGHT)
    handle_x, handle_y = door.handle_point
    rebuilt = DoorGeometry.from_handle(handle_x, handle_y, door.normal_yaw, door.hinge_side,
                                       door.opening)
    assert (rebuilt.hinge_x, rebuilt.hinge_y) == pytest.approx((door.hinge_x, door.hinge_y))


def test_to_door_inverts_to_world() -> None:
    door = DoorGeometry(1.0, -2.0, 0.7, HingeSide.RIGHT, DoorOpening.PULL)
    x, y = door.to_world(0.3, -0.4)
    assert door.to_door(x, y) == pytest.approx((0.3, -0.4))


@pytest.mark.parametrize("field, value", [("hinge_x", math.nan), ("angle", 3.5),
                                          ("leaf_width", 0.1), ("clear_opening", 1.2),
                                          ("wall_thickness", 0.0)])
def test_invalid_door_names_the_field(field: str, value: float) -> None:
    arguments = {"hinge_x": 0.0, "hinge_y": 0.0, "normal_yaw": 0.0, field: value}
    with pytest.raises(FootstepPlannerError) as caught:
        DoorGeometry(**arguments)
    assert caught.value.field == field
