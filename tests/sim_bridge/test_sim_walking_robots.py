"""Every walking robot stands and walks physically with the same walking controller.

Everything robot-specific comes from the profile (sole frames, foot size, posture) or from
the model; the figures are issue #11's, set for TALOS: standing 10 s drifts < 1 cm, ten
strides end within 3 cm of the plan, a 30° turn within 3°. The stride is the robot's own
(``STRIDES``: TALOS's 0.2 m, the others' scaled from it by leg length). One world per robot:
the robot stands, then walks, then turns, as the tests run in order. TALOS's other walking
behaviour (stops, shoves, held arms, bad plans) is in test_sim_walking.py.

Atlas v4 walks with the ankle efforts of its original model (the profile's ``joint_efforts``:
the URDF copy in ../shared/data cut them, and with those it tipped over in its first steps).
A turn takes as many steps as the robot's ``max_turn`` needs (Atlas's hips: 0.11 rad a step).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from walk_plans import sole_error, straight_plan, turn_plan

from door_contract.payloads import OutcomeStatus
from door_sim_bridge.execution import FootstepExecution
from door_sim_bridge.world import DoorWorld, StanceConfig, WorldConfig

START = StanceConfig(distance=3.5)
STRIDES = {"talos": 0.2, "g1": 0.15, "drc_hubo": 0.2, "atlas_v4": 0.15}  # m: G1's legs (hip to sole 0.69 m) are 0.8 × TALOS's
SHARED_DATA = {"drc_hubo", "atlas_v4"}  # URDFs read from ../shared/data (tests skip without it)
TURN = math.radians(30.0)
MAX_TURN_PER_STEP = math.radians(10.0)
SETTLE_S = 1.0  # s after placement before standing is measured


@pytest.fixture(scope="module", params=sorted(STRIDES))
def world(request):
    if request.param in SHARED_DATA:
        request.getfixturevalue("shared_data")  # skips when ../shared/data is absent
    with DoorWorld(WorldConfig(robot_profile=request.param, stance=START)) as sim:
        yield sim


def test_stands_for_10_seconds_with_less_than_1_cm_of_drift(world):
    """Drift is measured once the placed robot has settled on its soles (1 s: Atlas v4's base
    moves 1.1 cm forward as its stabiliser centres the CoM, then stays)."""
    world.step(int(SETTLE_S * world.config.physics_rate))
    start = world.base_pose()
    world.step(int(10.0 * world.config.physics_rate))
    assert not world.fallen, world.fall_reason
    assert np.linalg.norm(world.base_pose()[:2, 3] - start[:2, 3]) < 0.01
    assert abs(world.base_pose()[2, 3] - start[2, 3]) < 0.01


def test_walks_ten_strides_within_3_cm_of_the_plan(world):
    stride = STRIDES[world.profile.name]
    assert stride <= world.profile.walking.max_stride
    x0 = world.base_pose()[0, 3]
    plan = straight_plan(world, stride, 10)
    result = FootstepExecution(world, plan).run()
    assert result.status is OutcomeStatus.SUCCESS, result.reason
    assert sole_error(world, plan)[0] < 0.03
    assert world.base_pose()[0, 3] - x0 > 0.9 * 10 * stride  # it really walked


def test_turns_30_degrees_in_place_within_3_degrees(world):
    yaw0 = math.atan2(world.base_pose()[1, 0], world.base_pose()[0, 0])
    pairs = math.ceil(TURN / min(MAX_TURN_PER_STEP, world.profile.walking.max_turn))
    plan = turn_plan(world, TURN / pairs, pairs)
    result = FootstepExecution(world, plan).run()
    assert result.status is OutcomeStatus.SUCCESS, result.reason
    distance, heading = sole_error(world, plan)
    assert heading < math.radians(3.0) and distance < 0.03
    yaw = math.atan2(world.base_pose()[1, 0], world.base_pose()[0, 0])
    assert math.remainder(yaw - yaw0, math.tau) == pytest.approx(math.radians(30.0), abs=math.radians(3.0))
