"""The TF tree (ROS-free): composing /tf_static and /tf from odom down to any link gives the
sim's pose of that link (the URDF's joint kinematics agree with PyBullet's), for the physical
robot (box soles, floating base) and the teleported kinematic one; the description is the URDF
the sim loaded with the profile's mesh names; fixed joints are static, moving joints are not;
joints the sim lacks are named; bad URDFs are refused."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest

from door_contract.frames import Frame
from door_contract.geometry import planar_pose
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.robot_description import loaded_urdf
from door_sim_bridge.tf_tree import RobotTfTree, compose, world_tf_tree
from door_sim_bridge.urdf_joints import joint_transforms, root_link, urdf_joints
from door_sim_bridge.world import DoorWorld, RobotMode, StanceConfig, WorldConfig

STANCE = StanceConfig(distance=2.0, lateral_offset=0.3, yaw=0.4)


@pytest.fixture(scope="module")
def world():
    """The physical robot (the default): what the sim bridge runs."""
    with DoorWorld(WorldConfig(stance=STANCE)) as world:
        yield world


@pytest.fixture(scope="module")
def kinematic_world():
    with DoorWorld(WorldConfig(stance=STANCE, robot_mode=RobotMode.KINEMATIC)) as world:
        yield world


def _all_transforms(tree: RobotTfTree):
    return [*tree.static_transforms(), *tree.moving_transforms()]


def _assert_every_link_composes_to_the_sims_pose(world, tree: RobotTfTree) -> None:
    transforms = _all_transforms(tree)
    links = {j.child for j in tree.joints} | {tree.root}
    assert len(links) == 60 and not tree.skipped
    for link in links:
        np.testing.assert_allclose(compose(transforms, Frame.ODOM.value, link), world.link_pose(link),
                                   atol=1e-6, err_msg=link)  # PyBullet quaternions are unit to ~1e-7


def test_every_link_of_the_physical_robot_composes_to_the_sims_pose(world):
    tree = world_tf_tree(world, loaded_urdf(world)[0])
    world.set_joint_targets({"arm_right_4_joint": -1.2, "torso_1_joint": 0.3, "head_2_joint": 0.2})
    world.step(240)
    assert not world.fallen
    _assert_every_link_composes_to_the_sims_pose(world, tree)


def test_every_link_of_the_teleported_kinematic_robot_composes_to_the_sims_pose(kinematic_world):
    tree = world_tf_tree(kinematic_world, loaded_urdf(kinematic_world)[0])
    kinematic_world.set_joint_targets({"arm_right_4_joint": -1.2, "torso_1_joint": 0.3, "head_2_joint": 0.2})
    kinematic_world.step(240)
    kinematic_world.set_base_pose(planar_pose(-1.5, 0.2, -0.3, kinematic_world.profile.base_height))
    _assert_every_link_composes_to_the_sims_pose(kinematic_world, tree)


def _meshes(text: str, element: str = "") -> list[str]:
    return [mesh.get("filename") for mesh in ET.fromstring(text).iterfind(f".//{element}//mesh" if element else ".//mesh")]


def test_the_description_is_the_loaded_urdf_with_the_profiles_mesh_names(world, kinematic_world):
    text, path = loaded_urdf(world)
    loaded = world.robot.urdf_text
    assert all(name.startswith("/") for name in _meshes(loaded))  # the sim's copy: absolute paths
    assert _meshes(text, "visual") == _meshes(path.read_text(), "visual")  # what a viewer draws
    assert set(_meshes(text)) <= set(_meshes(path.read_text())) and all(m.startswith("package://") for m in _meshes(text))
    assert [(j.name, j.parent, j.child) for j in urdf_joints(text)] == \
        [(j.name, j.parent, j.child) for j in urdf_joints(loaded)]
    soles = {c.get("name") for c in ET.fromstring(text).iter("collision") if c.find("geometry/box") is not None}
    assert {f"{frame}_box" for frame in world.profile.feet.values()} <= soles  # the box soles the sim stands on
    assert loaded_urdf(kinematic_world)[0] == path.read_text()  # the kinematic sim loads the profile's file


def test_camera_optical_frame_is_the_images_frame(world):
    tree = world_tf_tree(world, loaded_urdf(world)[0])
    world.set_joint_targets({"head_1_joint": 0.4})
    world.step(240)
    optical = compose(_all_transforms(tree), Frame.ODOM.value, Frame.HEAD_CAMERA_OPTICAL.value)
    np.testing.assert_allclose(optical, world.camera.pose(), atol=1e-6)


def test_fixed_joints_are_static_and_moving_ones_are_not(world):
    tree = world_tf_tree(world, loaded_urdf(world)[0])
    static = {t.child for t in tree.static_transforms()}
    moving = {t.child for t in tree.moving_transforms()}
    assert "left_sole_link" in static and "rgbd_rgb_optical_frame" in static
    assert {"arm_right_4_link", "head_2_link", Frame.BASE_LINK.value} <= moving
    assert not static & moving
    assert len(moving) == 1 + sum(j.moving for j in tree.joints)  # odom → base_link + each moving joint


class _World:
    """A world that simulates only some joints (as if it had merged the others away)."""

    def __init__(self, positions):
        self.positions = positions

    def joint_positions(self):
        return dict(self.positions)

    def base_pose(self):
        return np.eye(4)


URDF = """<robot name="r"><link name="base_link"/><link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="revolute"><parent link="base_link"/><child link="a"/>
    <origin xyz="0 0 1" rpy="0 0 1.5707963267948966"/><axis xyz="0 0 2"/></joint>
  <joint name="j2" type="fixed"><parent link="a"/><child link="b"/><origin xyz="1 0 0"/></joint>
  <joint name="j3" type="prismatic"><parent link="b"/><child link="c"/><axis xyz="0 1 0"/></joint>
  <transmission name="t"><joint name="j1"/></transmission></robot>"""


def test_joint_kinematics_follow_origin_and_axis():
    j1, _, j3 = urdf_joints(URDF)
    np.testing.assert_allclose(j1.axis, (0.0, 0.0, 1.0))
    turned, slid = joint_transforms([j1, j3], np.array([np.pi / 2, 0.25]))
    np.testing.assert_allclose(turned[:3, 3], (0.0, 0.0, 1.0), atol=1e-12)
    np.testing.assert_allclose(turned[:3, 0], (-1.0, 0.0, 0.0), atol=1e-12)  # yaw 90° of the origin + 90° of q
    np.testing.assert_allclose(slid[:3, 3], (0.0, 0.25, 0.0), atol=1e-12)


def test_joints_the_sim_lacks_are_skipped_and_named():
    tree = RobotTfTree(_World({"j1": 0.0}), URDF, "a", np.eye(4))
    assert tree.skipped == ("j3",)
    assert [t.child for t in tree.moving_transforms()] == [Frame.BASE_LINK.value, "a"]
    np.testing.assert_allclose(compose([*tree.static_transforms(), *tree.moving_transforms()], "odom", "b")[:3, 3],
                               (0.0, 1.0, 1.0), atol=1e-12)


def test_a_root_not_named_base_link_gets_an_alias():
    text = URDF.replace("base_link", "pelvis")
    tree = RobotTfTree(_World({"j1": 0.0, "j3": 0.0}), text, "a", np.eye(4))
    alias = [t for t in tree.static_transforms() if t.child == "pelvis"]
    assert alias and alias[0].parent == Frame.BASE_LINK.value
    np.testing.assert_allclose(alias[0].matrix, np.eye(4))


@pytest.mark.parametrize("text, match", [
    ("not xml <", "not XML"),
    ("<robot name='r'><link name='a'/></robot>", "no <robot> with joints"),
    ("<robot><joint name='j' type='fixed'><parent link='a'/><child link='b'/></joint>"
     "<joint name='k' type='fixed'><parent link='c'/><child link='d'/></joint></robot>", "one root link"),
    ("<robot><joint name='j' type='fixed'><parent link='a'/><child link='b'/><origin xyz='1 2'/></joint></robot>",
     "three numbers"),
    ("<robot><joint name='j' type='revolute'><parent link='a'/><child link='b'/><axis xyz='0 0 0'/></joint></robot>",
     "zero axis"),
])
def test_bad_descriptions_are_refused(text, match):
    with pytest.raises(SimulationError, match=match):
        root_link(urdf_joints(text))
