"""Every robot profile through the same checks: what the door task takes from a profile must be
true of the robot's model (issue #14: no TALOS assumptions in the cores).

* the postures (nominal, walking, look) name URDF joints and lie within their limits, and the
  soles are ``base_height`` below the base;
* the robot as it starts (walking and look postures, every link, hands included) lies inside
  the footstep planner's ``body_width`` × ``body_depth`` rectangle (its centre ``body_offset``
  ahead of the base);
* the head camera looks forward and down, with the image's x to the robot's right;
* each arm (the joints a door may hold off) is seven joints of its own, ending at the wrist;
* each hand's grasp orientation is a rotation that puts ``into_door`` into the door and ``up``
  up, and the hand reaches it at the handle from the stand pose of a push door, facing it and
  sideways (IK from several seeds; the motion library's own problem adds the path and its
  constraints), with the lever as grasped and turned down, each robot at its own stand distances
  (the profile's ``stance``).

Atlas v4 and DRC-HUBO come from ../shared/data and skip without it.
"""

from __future__ import annotations

import numpy as np
import pytest

from door_bringup.passage_rig import NODE_DEFAULTS, motion_setup, opening_hand, perfect_estimate, stand_world
from door_contract.vocabulary import DoorOpening, HingeSide
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_sim_bridge.world import DoorConfig, DoorWorld, RobotMode, StanceConfig, WorldConfig
from door_trajopt.ik import IkOptions, solve_ik_multistart
from door_trajopt.motions import MotionOptions

PROFILES = ("talos", "g1", "atlas_v4", "drc_hubo")
SHARED_DATA = {"atlas_v4", "drc_hubo"}  # URDFs read from ../shared/data


@pytest.fixture(params=PROFILES)
def robot(request) -> str:
    if request.param in SHARED_DATA:
        request.getfixturevalue("shared_data")  # skips when ../shared/data is absent
    return request.param


def test_postures_are_the_models_and_within_its_limits(robot):
    kinematics = RobotKinematics(load_profile(robot))
    profile = kinematics.profile
    look_q = kinematics.configuration(profile.look_posture, base=kinematics.walking_q)
    for q in (kinematics.nominal_q, kinematics.walking_q, look_q):
        assert kinematics.within_limits(q)
    for sole in profile.feet.values():
        assert -kinematics.frame_pose(kinematics.nominal_q, sole)[2, 3] == pytest.approx(profile.base_height, abs=0.02)


def test_the_starting_posture_fits_the_profiles_body_rectangle(robot):
    """The footstep planner keeps a body_width × body_depth rectangle, its centre body_offset
    ahead of the base, clear of the door frame: every link of the robot as it walks (grippers
    included) must lie inside it."""
    with DoorWorld(WorldConfig(robot_profile=robot, stance=StanceConfig(distance=3.0, yaw=0.3),
                               robot_mode=RobotMode.KINEMATIC)) as sim:
        extents = sim.body_extents()
    walking = sim.profile.walking
    assert max(extents["left"], extents["right"]) <= walking.body_width / 2.0
    assert extents["ahead"] <= walking.body_depth / 2.0 + walking.body_offset
    assert extents["behind"] <= walking.body_depth / 2.0 - walking.body_offset
    assert min(extents.values()) > 0.1  # the probes did touch the robot


def test_the_head_camera_looks_forward_and_down(robot):
    with DoorWorld(WorldConfig(robot_profile=robot, robot_mode=RobotMode.KINEMATIC)) as world:
        optical, base = world.camera.pose(), world.base_pose()
    assert optical[:3, 2] @ base[:3, 0] > 0.5  # within 60° of forward
    assert 0.15 < -optical[2, 2] < 0.9  # 9-64° below the horizon
    assert optical[:3, 0] @ base[:3, 1] < -0.95  # image x to the right
    np.testing.assert_allclose(optical[:3, :3].T @ optical[:3, :3], np.eye(3), atol=1e-6)


def test_each_arm_is_seven_joints_of_its_own_and_ends_at_the_wrist(robot):
    """The joints a door may hold off (the trajectory judgement's yield): an arm chain's joints
    that move only its hand — every profile's 7-DOF arm, the torso left out — ending at the wrist."""
    with DoorWorld(WorldConfig(robot_profile=robot, robot_mode=RobotMode.KINEMATIC)) as world:
        arms = {side: world.robot.arm_joints(side) for side in world.profile.arms}
        for side, joints in arms.items():
            assert len(joints) == 7 and joints == world.profile.arm(side).joints[-7:]
            assert joints[-1] == world.robot.wrist_joint(side)
        assert not set.intersection(*(set(joints) for joints in arms.values()))


def _grasp_ik(robot: str, hinge: HingeSide, passage: str, handle: float):
    """IK (31 seeds) of the opening hand at a push door's handle turned ``handle`` rad, the robot
    at the stand pose of ``passage`` with its own stand distances (the profile's ``stance``)."""
    kinematics = RobotKinematics(load_profile(robot))
    parameters = {**NODE_DEFAULTS, "push_passage": passage}
    with stand_world(DoorConfig(opening=DoorOpening.PUSH, hinge_side=hinge), robot=robot,
                     parameters=parameters) as world:
        estimate = perfect_estimate(world)
        hand = opening_hand(world, estimate)
        setup = motion_setup(world, kinematics, estimate, hand, (0.0, 0.0))
    axes = kinematics.profile.arm(hand).grasp_axes_for(beside=passage == "sideways")
    rotation = axes.rotation_in_grasp()
    np.testing.assert_allclose(rotation @ axes.into_door, [-1.0, 0.0, 0.0], atol=1e-12)  # -x: into the door
    np.testing.assert_allclose(rotation @ axes.up, [0.0, 0.0, 1.0], atol=1e-12)
    assert np.linalg.det(rotation) == pytest.approx(1.0)
    target = setup.door.grasp_pose(0.0, handle)
    target[:3, :3] = target[:3, :3] @ rotation
    chain, rng = setup.chain, np.random.default_rng(0)
    seeds = [chain.chain_of(chain.body_q)] + [rng.uniform(chain.lower, chain.upper) for _ in range(30)]
    return hand, solve_ik_multistart(chain, target, seeds, IkOptions(max_iterations=300))


@pytest.mark.parametrize("passage", ["facing", "sideways"])
@pytest.mark.parametrize("hinge", [HingeSide.LEFT, HingeSide.RIGHT])
def test_each_hand_reaches_its_grasp_at_a_push_doors_handle(robot, hinge, passage):
    hand, result = _grasp_ik(robot, hinge, passage, 0.0)
    assert result.position_error < 0.005 and result.rotation_error < 0.02, (hand, result)


@pytest.mark.parametrize("passage", ["facing", "sideways"])
@pytest.mark.parametrize("hinge", [HingeSide.LEFT, HingeSide.RIGHT])
def test_each_hand_reaches_the_turned_lever(robot, hinge, passage, request):
    """The lever pressed down by the motion library's ``handle_turn``: G1's wrist reaches it
    beside the door only fingers-down (its ``grasp_axes_beside``)."""
    if (robot, passage) == ("atlas_v4", "sideways"):
        request.applymarker(pytest.mark.xfail(strict=True, reason=(
            "Atlas v4 beside a push door, upright (this stance is not crouched): no hand orientation "
            "(four tried) turns the lever 0.8 rad from 0.60-0.80 m, 2-9 cm off; crouched 0.15 m (its "
            "opening_crouch) on the passage rig the left hand turned it from 0.80 m, the right not (issue #14)")))
    hand, result = _grasp_ik(robot, hinge, passage, MotionOptions().handle_turn)
    assert result.position_error < 0.005 and result.rotation_error < 0.02, (hand, result)
