"""The simulator benchmark's walking rows measure a walk that succeeds (no timing asserted)."""

from __future__ import annotations

import pytest

from door_contract.vocabulary import Foot
from door_evaluation.sim.benchmark import WALK_STANCE, physics_walking, straight_walk
from door_sim_bridge.world import CameraConfig, DoorWorld, WorldConfig


def test_the_benchmark_walk_strides_straight_ahead_and_ends_with_the_feet_together():
    with DoorWorld(WorldConfig(stance=WALK_STANCE)) as world:
        feet = world.foot_placements()
        plan = straight_walk(world, strides=3, stride=0.2)
    assert [step.foot for step in plan] == [Foot.LEFT, Foot.RIGHT, Foot.LEFT, Foot.RIGHT]
    assert plan[-1].x - feet[Foot.RIGHT].x == pytest.approx(0.6, abs=1e-6)
    assert plan[-2].x - feet[Foot.LEFT].x == pytest.approx(0.6, abs=1e-6)


def test_the_walking_real_time_factor_is_of_a_walk_that_succeeded_with_the_camera_rendering():
    camera = CameraConfig(width=64, height=48)
    with DoorWorld(WorldConfig(stance=WALK_STANCE, camera=camera)) as world:
        start = world.base_pose()[0, 3]
        factor = physics_walking(world, camera_hz=2.0, strides=2)  # raises unless the walk succeeded
        assert factor > 0.0 and world.base_pose()[0, 3] - start > 0.3  # 2 × 0.2 m
