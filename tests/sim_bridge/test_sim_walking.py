"""The physical robot: comes to rest after a walk, walks with an arm held out, stops at a
stance, falls when shoved, refuses bad plans.

Floating-base TALOS on the floor under position control with the URDF efforts; the walking
controller of door_sim_bridge.walking keeps it up. Issue #11's standing, straight-walk and
turn figures are checked for every walking robot, TALOS included, in
test_sim_walking_robots.py; here a 200 N shove at the torso is a fall, reported as FELL, and
nothing executes afterwards.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from walk_plans import sole_error, straight_plan, turn_plan

from door_contract.payloads import OutcomeStatus
from door_contract.vocabulary import Foot
from door_robot.crouch import MAX_RISE
from door_sim_bridge.execution import FootstepExecution, TrajectoryExecution
from door_sim_bridge.execution.footsteps import STILL_RADIUS, STILL_TIME, STILL_TIMEOUT
from door_sim_bridge.walking.controller import Measurement, stance_frame
from door_sim_bridge.walking.stabilizer import ContactWrench
from door_sim_bridge.world import DoorWorld, EventKind, StanceConfig, WorldConfig

FAR_FROM_THE_DOOR = StanceConfig(distance=3.5)


@pytest.fixture
def world():
    with DoorWorld(WorldConfig(stance=FAR_FROM_THE_DOOR)) as sim:
        yield sim


def test_a_walk_ends_with_the_base_at_rest(world):
    """A walk ends once the pelvis has stopped (footsteps.STILL_RADIUS for STILL_TIME): after a
    90° turn it rocked ±8 cm for 4 s, and an arm motion planned from it missed the handle."""
    pairs = 4  # 45° at 11.25° per pair, within TALOS's max_turn (0.20 rad)
    plan = turn_plan(world, math.radians(45.0) / pairs, pairs)
    started = world.time
    result = FootstepExecution(world, plan).run()
    assert result.status is OutcomeStatus.SUCCESS, result.reason
    assert world.time - started <= pairs * 2 * world.profile.walking.step_duration + 1.0 + STILL_TIMEOUT + 0.1
    at_end = world.base_pose()[:2, 3].copy()
    world.step(int(STILL_TIME * world.config.physics_rate))
    assert np.linalg.norm(world.base_pose()[:2, 3] - at_end) < 2 * STILL_RADIUS


def test_walks_with_an_arm_held_out(world):
    """The pull passage walks with the blocking hand where BLOCK left it."""
    held = {"arm_left_1_joint": -0.6, "arm_left_2_joint": 0.4, "arm_left_4_joint": -1.2}
    assert TrajectoryExecution(world, [2.0], list(held), [list(held.values())]).run().status is OutcomeStatus.SUCCESS
    plan = straight_plan(world, 0.2, 4)
    result = FootstepExecution(world, plan).run()
    assert result.status is OutcomeStatus.SUCCESS, result.reason
    positions = world.joint_positions()
    assert all(positions[name] == pytest.approx(value, abs=0.05) for name, value in held.items())
    assert sole_error(world, plan)[0] < 0.03
    assert world.balance is not None and world.balance.controller.pattern_departure is None  # on its pattern


def test_a_stop_ends_the_walk_at_the_next_stable_stance(world):
    plan = straight_plan(world, 0.2, 10)
    execution = FootstepExecution(world, plan)
    execution.advance(int(2.5 * world.config.physics_rate))  # into the walk
    assert world.walking
    result = execution.cancel("operator stop")
    assert result.status is OutcomeStatus.FAILURE and result.reason == "operator stop"
    for _ in range(int((3.0 + world.config.gait.settle_s) * world.config.physics_rate)):
        if not world.walking:  # stepped and settled (the CoM over the feet)
            break
        world.step()
    assert not world.walking and not world.fallen
    before = world.base_pose()
    world.step(int(1.0 * world.config.physics_rate))  # standing still now
    assert np.linalg.norm(world.base_pose()[:2, 3] - before[:2, 3]) < 0.01
    assert world.base_pose()[0, 3] < plan[-1].x - 0.8  # it did not walk the whole plan


def test_a_stop_before_the_first_step_stands_where_it_is(world):
    plan = straight_plan(world, 0.2, 6)
    feet = world.foot_placements()
    execution = FootstepExecution(world, plan)
    execution.advance(int(0.3 * world.config.physics_rate))  # in the first double support
    execution.stop("operator pause")
    result = execution.run(max_steps=int(3.0 * world.config.physics_rate))
    assert result.status is OutcomeStatus.STOPPED and "after step 0 of" in result.reason
    after = world.foot_placements()
    assert all(math.hypot(after[f].x - feet[f].x, after[f].y - feet[f].y) < 0.01 for f in feet)


def test_a_200_N_shove_at_the_torso_is_a_fall_reported_as_fell(world):
    plan = straight_plan(world, 0.2, 6)
    execution = FootstepExecution(world, plan)
    execution.advance(int(1.0 * world.config.physics_rate))
    world.push_robot("torso_2_link", [0.0, 200.0, 0.0], steps=int(0.5 * world.config.physics_rate))
    result = execution.run(max_steps=int(5.0 * world.config.physics_rate))
    assert result.status is OutcomeStatus.FELL and "base tilted" in result.reason
    assert "capture point left its pattern" in result.reason  # knocked off it before the tilt
    assert world.fallen and [e.kind for e in world.events()].count(EventKind.FELL) == 1
    world.step(int(2.0 * world.config.physics_rate))
    assert world.fallen  # a fallen robot stays fallen
    again = TrajectoryExecution(world, [1.0], ["arm_left_1_joint"], [[0.1]]).run()
    assert again.status is OutcomeStatus.FELL
    assert FootstepExecution(world, straight_plan(world, 0.1, 2)).run().status is OutcomeStatus.FELL


@pytest.mark.parametrize("names, reason", [
    (["leg_left_4_joint"], "leg joint"),
    (["arm_left_1_joint"], "outside its limits"),
])
def test_bad_trajectories_are_rejected_and_nothing_moves(world, names, reason):
    before = world.joint_positions()
    value = 10.0 if reason == "outside its limits" else before[names[0]] + 0.1
    result = TrajectoryExecution(world, [1.0], names, [[value]]).run()
    assert result.status is OutcomeStatus.REJECTED and reason in result.reason
    after = world.joint_positions()
    assert all(after[name] == pytest.approx(before[name], abs=1e-3) for name in world.commandable_joints())


def test_a_footstep_plan_beyond_the_limits_is_rejected_and_the_robot_stands(world):
    start = world.base_pose()
    plan = straight_plan(world, world.profile.walking.max_stride + 0.1, 2)
    result = FootstepExecution(world, plan).run()
    assert result.status is OutcomeStatus.REJECTED and "max_stride" in result.reason
    world.step(int(0.5 * world.config.physics_rate))
    assert np.linalg.norm(world.base_pose()[:2, 3] - start[:2, 3]) < 0.005 and not world.walking


def test_a_walk_starts_from_a_com_leaning_beyond_the_soles(world):
    """Leaning 10 cm forward against a force (the stabiliser's largest offset: a Monte-Carlo pull
    door's leaf on the robot), the CoM is beyond the region where the pattern's ZMP may start;
    placo then found no pattern ("Failed to plan CoM trajectory", 4 refusals of one walk
    through). The walk is planned from the nearest point inside that region instead."""
    controller = world.balance.controller
    soles = {Foot.LEFT: controller.robot.get_T_world_left(), Foot.RIGHT: controller.robot.get_T_world_right()}
    stance = stance_frame(soles)
    heading, torso = stance[:3, 0], stance[:3, 3] + [0.0, 0.0, 1.2]
    leaning = Measurement(soles, None, ContactWrench(-100.0 * heading, torso))  # pushed back at the chest
    for _ in range(int(2.0 / controller.dt)):
        controller.tick(leaning)
    com = np.array(controller.robot.com_world())
    ahead = float(heading[:2] @ (com[:2] - stance[:2, 3]))
    walking = world.profile.walking
    assert ahead > walking.foot_length / 2 - world.config.gait.zmp_margin  # beyond where the ZMP may be
    assert controller.walk(straight_plan(world, 0.1, 2), soles) > 0.0


def test_a_crouched_walk_lowers_the_pelvis_and_the_next_upright_walk_raises_it_again(world):
    """Through a push door whose lever meets the pelvis the robot walks lower
    (door_robot.profile.PassageCrouch): the pelvis ends the crouch below its standing height
    and stays there standing; the next walk at crouch 0 brings it back. Both land on the plan."""
    standing = world.base_pose()[2, 3]
    plan = straight_plan(world, 0.2, 4)
    result = FootstepExecution(world, plan, crouch=0.06).run()
    assert result.status is OutcomeStatus.SUCCESS, result.reason
    assert world.base_pose()[2, 3] == pytest.approx(standing - 0.06, abs=0.01)
    assert sole_error(world, plan)[0] < 0.03
    world.step(int(1.0 * world.config.physics_rate))
    assert world.base_pose()[2, 3] == pytest.approx(standing - 0.06, abs=0.01)  # it stays down standing
    plan = straight_plan(world, 0.2, 2)
    assert FootstepExecution(world, plan).run().status is OutcomeStatus.SUCCESS
    assert world.base_pose()[2, 3] == pytest.approx(standing, abs=0.01)
    assert sole_error(world, plan)[0] < 0.03


def test_a_risen_walk_raises_the_pelvis_and_lands_on_the_plan(world):
    """Through a narrow push door whose lever would meet the pelvis's notch the robot walks
    higher (a negative crouch, door_robot.crouch.PassageCrouch.narrow_rise): the pelvis ends the
    walk MAX_RISE above its standing height, the soles on the plan."""
    standing = world.base_pose()[2, 3]
    plan = straight_plan(world, 0.2, 4)
    result = FootstepExecution(world, plan, crouch=-MAX_RISE).run()
    assert result.status is OutcomeStatus.SUCCESS, result.reason
    assert world.base_pose()[2, 3] == pytest.approx(standing + MAX_RISE, abs=0.01)
    assert sole_error(world, plan)[0] < 0.03


@pytest.mark.parametrize("crouch", [-0.06, 0.5, math.nan])
def test_a_walk_at_a_crouch_it_cannot_take_is_rejected_and_the_robot_stands(world, crouch):
    start = world.base_pose()
    result = FootstepExecution(world, straight_plan(world, 0.2, 2), crouch=crouch).run()
    assert result.status is OutcomeStatus.REJECTED and "crouch" in result.reason
    world.step(int(0.5 * world.config.physics_rate))
    assert np.linalg.norm(world.base_pose()[:3, 3] - start[:3, 3]) < 0.005 and not world.walking
