"""The planner's door built from a detector estimate lies where the simulated door is: the
hinge-side jamb, the opening's width and the handle's place along the leaf come from the
measured edges (a fixed DRC door put the opening 6.6 cm towards the hinge: the estimate's
handle is the lever's grasp point, 0.136 m from the free edge, not 0.07 m)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from door_contract.payloads import DoorEstimate
from door_contract.vocabulary import DoorOpening, HingeSide
from door_sim_bridge.world import DoorConfig, DoorWorld, WorldConfig
from footstep_planner.goals import through_door_pose
from footstep_planner.requests import door_geometry_from_estimate


def _estimate(world: DoorWorld, with_edges: bool = True) -> DoorEstimate:
    truth = world.door_ground_truth()
    hinge = world.config.door.hinge_side
    corners = tuple(tuple(c) for c in truth.corners) if with_edges else ((math.nan,) * 3,) * 4
    return DoorEstimate(world.time, "odom", tuple(truth.handle_grasp_pose[:3, 3]), tuple(truth.normal), hinge,
                        truth.width if with_edges else math.nan, corners, 1.0, 10, "automatic")


@pytest.mark.parametrize("width, hinge", [(0.86, "left"), (0.914, "right"), (0.96, "left")])
def test_the_opening_is_where_the_simulated_door_is(width: float, hinge: str) -> None:
    with DoorWorld(WorldConfig(door=DoorConfig(width=width, hinge_side=HingeSide(hinge)))) as world:
        estimate = _estimate(world)
        truth = world.door_ground_truth()
    door = door_geometry_from_estimate(estimate, DoorOpening.PUSH, 0.0, handle_standoff=0.06)
    assert door.clear_opening == pytest.approx(width, abs=0.005)
    hinge_edge = np.asarray(truth.corners[0][:2])
    np.testing.assert_allclose(door.to_world(0.0, 0.0), hinge_edge, atol=0.01)
    middle = np.mean([truth.corners[0][:2], truth.corners[1][:2]], axis=0)
    passage = through_door_pose(door, 1.0)
    across = np.asarray(door.latch_direction)
    assert abs((np.array([passage.x, passage.y]) - middle) @ across) < 0.01


def test_without_edges_the_drc_door_is_assumed() -> None:
    with DoorWorld(WorldConfig()) as world:
        estimate = _estimate(world, with_edges=False)
    door = door_geometry_from_estimate(estimate, DoorOpening.PULL, 0.1, handle_standoff=0.06)
    assert door.leaf_width == pytest.approx(0.914) and door.angle == pytest.approx(0.1)
