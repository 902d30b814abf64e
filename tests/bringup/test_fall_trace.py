"""The passage rig's fall trace: the stance leg's samples around the first pelvis dip, and the
sole contacts it reads (door_sim_bridge.world.DoorWorld.sole_contacts)."""

from __future__ import annotations

import pytest

from door_bringup.fall_trace import FallTrace, FallTraceError, StanceSample, dip_onset, leg_joints
from door_contract.vocabulary import Side
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.world import DoorWorld, RobotMode, StanceConfig, WorldConfig

FAR_FROM_THE_DOOR = StanceConfig(distance=3.5)


def sample_at(time: float, pelvis_height: float) -> StanceSample:
    both = {Side.LEFT: 0.0, Side.RIGHT: 0.0}
    return StanceSample(time, pelvis_height, {side: (0.0, 0.0) for side in Side}, both, both,
                        ("leg_right_4_joint", 0.3), ("leg_right_6_joint", -0.01))


@pytest.fixture(scope="module")
def world():
    with DoorWorld(WorldConfig(stance=FAR_FROM_THE_DOOR)) as sim:
        yield sim


def test_a_dip_is_the_first_sample_far_enough_below_the_recent_highest():
    heights = [1.019, 1.019, 1.018, 1.012, 1.003, 0.990, 0.975]  # the lift-off of stop 26's trace
    samples = [sample_at(0.1 * k, height) for k, height in enumerate(heights)]
    assert dip_onset(samples) == pytest.approx(0.4)  # 1.6 cm below 1.019
    assert dip_onset(samples, depth=0.05) is None
    slow = [sample_at(1.0 * k, 1.019 - 0.01 * k) for k in range(5)]  # 1 cm a second: a crouch, not a dip
    assert dip_onset(slow) is None


def test_a_sample_line_names_the_sole_loads_the_strain_and_the_lag():
    line = sample_at(46.5, 1.003).line()
    assert line.startswith("t   46.500 s  pelvis 1.003 m")
    assert "strained leg_right_4_joint  30 %" in line and "lagging leg_right_6_joint -0.010 rad" in line


def test_the_legs_are_the_joints_between_the_base_and_the_soles(world):
    legs = leg_joints(world)
    assert len(legs) == 12 and all(name.startswith("leg_") for name in legs)


def test_a_standing_robot_carries_its_weight_on_both_soles_and_sinks_into_nothing(world):
    world.step(int(0.5 * world.config.physics_rate))
    contacts = world.sole_contacts()
    total = sum(contact.load for contact in contacts.values())
    assert 850.0 < total < 1100.0  # TALOS is ~95 kg
    for contact in contacts.values():
        assert contact.load > 0.3 * total and contact.points >= 3 and contact.sinking < 0.002


def test_a_shoved_robots_trace_reports_the_dip_before_its_fall():
    with DoorWorld(WorldConfig(stance=FAR_FROM_THE_DOOR)) as shoved:  # its own: it stays fallen
        trace = FallTrace(shoved, every=2, window_s=4.0)
        shoved.push_robot("torso_2_link", [0.0, 300.0, 0.0], steps=int(0.5 * shoved.config.physics_rate))
        for _ in range(int(5.0 * shoved.config.physics_rate)):
            shoved.step()
            trace.step()
            if shoved.fallen:
                break
        assert shoved.fallen
        report = trace.report()
    assert report[0].startswith("pelvis dip at t = ") and len(report) > 5
    assert all(line.startswith("t ") and "strained leg_" in line for line in report[1:])


def test_a_trace_that_cannot_sample_is_refused(world):
    with pytest.raises(FallTraceError, match="every"):
        FallTrace(world, every=0)
    with pytest.raises(FallTraceError, match="window_s"):
        FallTrace(world, window_s=float("nan"))


def test_a_kinematic_robot_has_no_sole_contacts():
    with DoorWorld(WorldConfig(robot_mode=RobotMode.KINEMATIC, stance=FAR_FROM_THE_DOOR)) as kinematic:
        with pytest.raises(SimulationError, match="physical robot"):
            kinematic.sole_contacts()
