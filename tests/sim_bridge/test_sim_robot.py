"""The robot in PyBullet agrees with Pinocchio; base teleporting; joint targets; head pitch.

The kinematic robot (fixed base) is teleported to random poses here; the physical robot's
placement and standing are tested in test_sim_walking.py.
"""

import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest
import yaml

from door_contract.geometry import planar_pose
from door_contract.vocabulary import Foot, Side
from door_robot.kinematics import RobotKinematics
from door_robot.locations import params_dir
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.world import DoorWorld, RobotMode, StanceConfig, WorldConfig
from door_sim_bridge.world.camera import optical_offset
from door_sim_bridge.world.transforms import invert

STANCE = StanceConfig(distance=2.0, lateral_offset=0.35, yaw=0.4)


@pytest.fixture(scope="module")
def world():
    with DoorWorld(WorldConfig(stance=STANCE, robot_mode=RobotMode.KINEMATIC)) as sim:
        yield sim


@pytest.fixture(scope="module")
def kinematics(world):
    return RobotKinematics(world.profile)


def _pinocchio_tcp(world: DoorWorld, kinematics: RobotKinematics, side: Side) -> np.ndarray:
    positions = world.joint_positions()
    q = kinematics.configuration({name: positions[name] for name in kinematics.joint_names})
    return world.base_pose() @ kinematics.frame_pose(q, kinematics.profile.tcp_frame(side))


def test_starts_at_the_stance_in_the_walking_posture(world):
    base = world.base_pose()
    np.testing.assert_allclose(base, planar_pose(-2.0, 0.35, 0.4, world.profile.base_height), atol=1e-6)
    positions = world.joint_positions()
    for name, value in {**world.profile.nominal_posture, **world.profile.walking_posture}.items():
        assert positions[name] == pytest.approx(value, abs=1e-6)
    feet = world.foot_placements()
    for placement in feet.values():
        assert placement.yaw == pytest.approx(0.4, abs=1e-6)
    left, right = feet[Foot.LEFT], feet[Foot.RIGHT]
    separation = np.hypot(left.x - right.x, left.y - right.y)
    assert separation == pytest.approx(world.profile.walking.foot_separation, abs=0.01)


def test_head_is_pitched_down_to_see_the_handle(world):
    camera = world.link_pose(world.profile.head_camera_frame)
    pitch = np.arcsin(-camera[2, 2])  # optical z below the horizon
    assert pitch == pytest.approx(world.config.camera.head_pitch, abs=0.02)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_tcp_pose_agrees_with_pinocchio(world, kinematics, seed):
    rng = np.random.default_rng(seed)
    arm_joints = [j for side in Side for j in world.profile.arm(side).joints]
    limits = world.joint_limits()
    posture = {name: rng.uniform(limits[name].lower, limits[name].upper) for name in arm_joints}
    world.robot.reset_joints(posture)
    world.set_base_pose(planar_pose(-1.0 + seed, 0.2 * seed, 0.3 * seed - 0.5, world.profile.base_height))
    for side in Side:
        ours, reference = world.tcp_pose(side), _pinocchio_tcp(world, kinematics, side)
        assert np.linalg.norm(ours[:3, 3] - reference[:3, 3]) < 1e-3
        np.testing.assert_allclose(ours[:3, :3], reference[:3, :3], atol=1e-5)


def test_base_pose_round_trips(world):
    target = planar_pose(0.7, -1.2, 2.5, world.profile.base_height)
    world.set_base_pose(target)
    np.testing.assert_allclose(world.base_pose(), target, atol=1e-9)
    with pytest.raises(SimulationError):
        world.set_base_pose(np.full((4, 4), np.nan))
    with pytest.raises(SimulationError):
        world.set_base_pose(2.0 * target)


def test_joint_targets_are_validated_and_clipped(world):
    with pytest.raises(SimulationError, match="no movable joint 'elbow_of_doom'"):
        world.set_joint_targets({"elbow_of_doom": 0.0})
    with pytest.raises(SimulationError, match="NaN"):
        world.set_joint_targets({"arm_left_4_joint": float("nan")})
    world.set_joint_targets({"arm_left_4_joint": 5.0})
    assert world.joint_targets()["arm_left_4_joint"] == world.joint_limits()["arm_left_4_joint"].upper


@pytest.mark.parametrize("profile", ["atlas_v4", "drc_hubo"])
def test_the_seed_papers_robots_work_from_their_profiles(shared_data, profile):
    """Atlas v4 (head frame x forward) and DRC-HUBO (neck frame turned by pi) look forward-down."""
    with DoorWorld(WorldConfig(robot_profile=profile, stance=STANCE, robot_mode=RobotMode.KINEMATIC)) as world:
        kinematics = RobotKinematics(world.profile)
        for side in Side:
            ours, reference = world.tcp_pose(side), _pinocchio_tcp(world, kinematics, side)
            assert np.linalg.norm(ours[:3, 3] - reference[:3, 3]) < 1e-3
        optical = world.render().camera_pose
        forward = world.base_pose()[:3, 0]
        assert optical[:3, 2] @ forward == pytest.approx(np.cos(world.config.camera.head_pitch), abs=0.02)
        assert optical[2, 2] == pytest.approx(-np.sin(world.config.camera.head_pitch), abs=0.02)
        assert optical[:3, 0] @ world.base_pose()[:3, 1] == pytest.approx(-1.0, abs=0.05)  # x right


def _urdf_joint_pitch(urdf_text: str, child_link: str) -> float:
    """The pitch (rpy[1]) of the fixed joint whose child is ``child_link``."""
    for joint in ElementTree.fromstring(urdf_text).iter("joint"):
        if joint.find("child").get("link") == child_link:
            return float(joint.find("origin").get("rpy").split()[1])
    raise AssertionError(f"no joint with child {child_link}")


@pytest.mark.parametrize("waist", [0.0, None])
def test_g1_looks_down_by_its_camera_mounts_pitch_less_its_lean(waist):
    """G1's d435_link is an x-forward frame pitched down on the torso (no neck): the camera
    looks along its x, down by the URDF's pitch (waist upright) less the look posture's lean
    back (``waist`` None: the profile's), with the image's x to the robot's right; the head
    pitch moves no torso joint."""
    overrides = () if waist is None else (("waist_pitch_joint", waist),)
    config = WorldConfig(robot_profile="g1", stance=STANCE, robot_mode=RobotMode.KINEMATIC,
                         posture_overrides=overrides)
    with DoorWorld(config) as world:
        frame = world.profile.head_camera_frame
        lean = world.profile.look_posture["waist_pitch_joint"] if waist is None else waist
        pitch = _urdf_joint_pitch(world.profile.urdf_path.read_text(), frame) + lean
        optical, base = world.render().camera_pose, world.base_pose()
        link = world.link_pose(frame)
        np.testing.assert_allclose(optical[:3, 2], link[:3, 0], atol=1e-6)  # looks along the link's x
        assert np.arcsin(-optical[2, 2]) == pytest.approx(pitch, abs=1e-3)  # below the horizon
        assert optical[:3, 0] @ base[:3, 1] == pytest.approx(-1.0, abs=1e-3)  # x right
        assert world.joint_positions()["waist_pitch_joint"] == pytest.approx(lean, abs=1e-9)


def test_a_profile_without_camera_axes_guesses_them(shared_data):
    """The explicit axes of TALOS, Atlas and DRC-HUBO are what the simulator guessed before
    (the frame axes nearest forward and down in the zero posture): their cameras are unchanged."""
    for profile in ("talos", "atlas_v4", "drc_hubo"):
        with DoorWorld(WorldConfig(robot_profile=profile, stance=STANCE, robot_mode=RobotMode.KINEMATIC)) as world:
            frame = world.profile.head_camera_frame
            explicit = invert(world.link_pose(frame)) @ world.camera.pose()
            world.robot.reset_joints({name: 0.0 for name in world.joint_positions()})
            np.testing.assert_allclose(optical_offset(world.robot, frame), explicit, atol=1e-6, err_msg=profile)


def test_profile_joint_efforts_replace_the_urdfs_and_an_unknown_joint_is_refused(shared_data, tmp_path):
    """Atlas v4's ankles get the efforts of the original model (360 N·m roll, 740 N·m pitch; the
    copy in ../shared/data cut them to 45 and 92), every other joint keeps the URDF's; a profile
    naming a joint the URDF lacks is refused before anything runs."""
    with DoorWorld(WorldConfig(robot_profile="atlas_v4", stance=STANCE, robot_mode=RobotMode.KINEMATIC)) as world:
        limits = world.joint_limits()
    assert (limits["l_leg_aky"].effort, limits["r_leg_akx"].effort) == (740.0, 360.0)
    assert limits["l_leg_kny"].effort == 890.0  # the URDF's
    document = yaml.safe_load((params_dir() / "robot_g1.yaml").read_text())
    document["joint_efforts"] = {"wing_joint": 10.0}
    path = tmp_path / "robot_g1_wings.yaml"
    path.write_text(yaml.safe_dump(document))
    with pytest.raises(SimulationError, match=r"joint_efforts names joint\(s\) the URDF lacks: \['wing_joint'\]"):
        DoorWorld(WorldConfig(robot_profile=str(path), stance=STANCE, robot_mode=RobotMode.KINEMATIC))
