"""Every profile's turn per step is one its hips can walk (door_robot.hip_yaw)."""

import dataclasses

import pytest

from door_contract.vocabulary import Side
from door_robot.errors import RobotModelError
from door_robot.hip_yaw import TOE_IN_TRUNK_LAG, hip_yaw_joint, inward_hip_yaw_range, max_turn_of_hips
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile

PROFILES = ["talos", "atlas_v4", "drc_hubo", "g1"]


SHARED_DATA = {"atlas_v4", "drc_hubo"}  # URDFs read from ../shared/data (tests skip without it)


def _kinematics(name: str) -> RobotKinematics:
    return RobotKinematics(load_profile(name))


@pytest.mark.parametrize("name", PROFILES)
def test_a_toe_in_step_stays_within_the_hip_yaw_range(name, request):
    if name in SHARED_DATA:
        request.getfixturevalue("shared_data")  # skips when ../shared/data is absent
    kinematics = _kinematics(name)
    assert TOE_IN_TRUNK_LAG * kinematics.profile.walking.max_turn <= min(
        inward_hip_yaw_range(kinematics, side) for side in Side)
    assert kinematics.profile.walking.max_turn <= max_turn_of_hips(kinematics)


def test_talos_hip_yaws_turn_each_foot_0_349_rad_inward():
    """TALOS's URDF: leg_left_1_joint in [-0.349, 1.571], leg_right_1_joint in [-1.571, 0.349]."""
    kinematics = _kinematics("talos")
    assert hip_yaw_joint(kinematics, Side.LEFT) == "leg_left_1_joint"
    assert hip_yaw_joint(kinematics, Side.RIGHT) == "leg_right_1_joint"
    for side in Side:
        assert inward_hip_yaw_range(kinematics, side) == pytest.approx(0.349, abs=1e-3)


def test_g1_hip_yaw_is_found_although_its_axis_is_tilted():
    """G1's hip yaw follows its hip pitch and roll: the axis is 27° off vertical standing."""
    kinematics = _kinematics("g1")
    assert hip_yaw_joint(kinematics, Side.LEFT) == "left_hip_yaw_joint"
    assert inward_hip_yaw_range(kinematics, Side.RIGHT) == pytest.approx(2.758, abs=1e-3)


def test_a_leg_without_a_vertical_joint_is_a_clear_error():
    """A sole frame on the pelvis itself: its chain has no joint at all, so no hip yaw."""
    profile = load_profile("talos")
    pelvis_feet = dataclasses.replace(profile, feet={side: profile.base_frame for side in Side})
    with pytest.raises(RobotModelError, match="left leg has no joint with a vertical axis"):
        max_turn_of_hips(RobotKinematics(pelvis_feet))
