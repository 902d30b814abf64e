"""The robot's TF tree from the simulation (ROS-free): what /tf and /tf_static carry.

Frames follow REP-105 and the URDF:

* ``odom → base_link``: the robot's base pose in the world, which is ``odom`` (the sim's
  ground truth stands in for odometry). If the URDF's root link has another name
  (``pelvis``), ``base_link → <root>`` is a static identity.
* one transform per URDF joint, ``parent link → child link``:
  ``parent_T_child = (odom_T_parent)⁻¹ · odom_T_child``, both link frames read from the sim.
  Fixed joints never change and go once to /tf_static; moving joints (revolute, continuous,
  prismatic, floating) go to /tf at every publication.
* ``<camera link> → head_camera_optical_frame`` (the frame of the head camera's images and
  CameraInfo): the constant offset of the optical frame (z forward, x right, y down) from
  the profile's camera link, on /tf_static.

Composing the transforms from ``odom`` down to a link gives back the sim's pose of that
link (tests/sim_bridge check it for every link).
"""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from door_contract.frames import Frame, FrameTransform
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.world.transforms import invert

FIXED_JOINT_TYPES = frozenset({"fixed"})


class LinkPoses(Protocol):
    """What the tree reads from the world (``DoorWorld`` has both)."""

    def link_pose(self, link: str) -> np.ndarray: ...

    def base_pose(self) -> np.ndarray: ...


@dataclass(frozen=True)
class UrdfJoint:
    """One joint of a URDF: its name, type, parent and child links."""

    name: str
    kind: str
    parent: str
    child: str

    @property
    def moving(self) -> bool:
        return self.kind not in FIXED_JOINT_TYPES


def urdf_joints(urdf_text: str) -> tuple[UrdfJoint, ...]:
    """The joints of a URDF document; SimulationError if it is not a URDF with a tree."""
    try:
        robot = ElementTree.fromstring(urdf_text)
    except ElementTree.ParseError as error:
        raise SimulationError(f"robot description is not XML: {error}") from None
    joints = []
    for element in robot.iter("joint"):
        parent, child = element.find("parent"), element.find("child")
        if parent is None or child is None:  # <joint> inside <transmission> has neither
            continue
        joints.append(UrdfJoint(element.get("name", ""), element.get("type", ""),
                                parent.get("link", ""), child.get("link", "")))
    if robot.tag != "robot" or not joints:
        raise SimulationError("robot description has no <robot> with joints")
    return tuple(joints)


def root_link(joints: tuple[UrdfJoint, ...]) -> str:
    """The one link that is no joint's child."""
    roots = {j.parent for j in joints} - {j.child for j in joints}
    if len(roots) != 1:
        raise SimulationError(f"robot description must have one root link, found {sorted(roots)}")
    return roots.pop()


class RobotTfTree:
    """The static and moving transforms of one robot in one world.

    ``optical_offset`` is ``camera_link_T_optical``; the static part is computed once, at
    construction, from the world's current link poses.
    """

    def __init__(self, world: LinkPoses, urdf_text: str, camera_link: str,
                 optical_offset: np.ndarray) -> None:
        self._world = world
        joints = urdf_joints(urdf_text)
        self.root = root_link(joints)
        known = self._links_known_to(world, {self.root} | {j.child for j in joints})
        self.joints = tuple(j for j in joints if j.parent in known and j.child in known)
        self.skipped = tuple(j.name for j in joints if j not in self.joints)
        self._moving = tuple(j for j in self.joints if j.moving)
        statics = [self._joint_transform(j) for j in self.joints if not j.moving]
        statics.append(FrameTransform(camera_link, Frame.HEAD_CAMERA_OPTICAL.value, np.array(optical_offset)))
        if self.root != Frame.BASE_LINK.value:
            statics.append(FrameTransform(Frame.BASE_LINK.value, self.root, np.eye(4)))
        self._static = tuple(statics)

    @staticmethod
    def _links_known_to(world: LinkPoses, links: set[str]) -> set[str]:
        known = set()
        for link in links:
            try:
                world.link_pose(link)
                known.add(link)
            except SimulationError:
                pass  # a link the simulator merged away: its joint is skipped
        return known

    def _joint_transform(self, joint: UrdfJoint) -> FrameTransform:
        parent, child = self._world.link_pose(joint.parent), self._world.link_pose(joint.child)
        return FrameTransform(joint.parent, joint.child, invert(parent) @ child)

    def static_transforms(self) -> tuple[FrameTransform, ...]:
        """For /tf_static: fixed joints, the camera's optical frame, a base_link alias if needed."""
        return self._static

    def moving_transforms(self) -> tuple[FrameTransform, ...]:
        """For /tf, now: ``odom → base_link`` and every moving joint."""
        base = FrameTransform(Frame.ODOM.value, Frame.BASE_LINK.value, self._world.base_pose())
        return (base, *(self._joint_transform(j) for j in self._moving))


def compose(transforms: tuple[FrameTransform, ...] | list[FrameTransform], source: str,
            target: str) -> np.ndarray:
    """``source_T_target`` by walking the tree from ``target`` up to ``source`` (tf2's lookup
    for a tree, without time); KeyError if ``target`` is not below ``source``."""
    parent_of = {t.child: t for t in transforms}
    result = np.eye(4)
    frame = target
    while frame != source:
        step = parent_of[frame]
        result = step.matrix @ result
        frame = step.parent
    return result


def world_tf_tree(world, urdf_text: str) -> RobotTfTree:
    """The tree of a ``DoorWorld``: its robot's URDF and its head camera's optical offset,
    ``camera_link_T_optical = (odom_T_camera_link)⁻¹ · odom_T_optical``."""
    camera_link = world.profile.head_camera_frame
    offset = invert(world.link_pose(camera_link)) @ world.camera.pose()
    return RobotTfTree(world, urdf_text, camera_link, offset)
