"""The robot's TF tree from the simulation (ROS-free): what /tf and /tf_static carry.

Frames follow REP-105 and the URDF, as ``robot_state_publisher`` publishes them:

* ``odom → base_link``: the robot's base pose in the world, which is ``odom`` (the sim's
  ground truth stands in for odometry). If the URDF's root link has another name
  (``pelvis``), ``base_link → <root>`` is a static identity.
* one transform per URDF joint, ``parent link → child link``, ``O · M(q)`` from the joint's
  origin and axis at the sim's joint position (:mod:`door_sim_bridge.urdf_joints`): fixed
  joints once on /tf_static, moving joints on /tf at every publication (one batch read of the
  joint positions and one vectorised product: the robot's 32 joints cost well under a
  physics step).
* ``<camera link> → head_camera_optical_frame`` (the frame of the head camera's images and
  CameraInfo): the constant offset of the optical frame (z forward, x right, y down) from
  the profile's camera link, on /tf_static.

Composing the transforms from ``odom`` down to a link gives back the sim's own pose of that
link (tests/sim_bridge check it for every link of TALOS).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol

import numpy as np

from door_contract.frames import Frame, FrameTransform
from door_sim_bridge.urdf_joints import joint_transforms, root_link, urdf_joints
from door_sim_bridge.world import DoorWorld
from door_sim_bridge.world.transforms import invert

__all__ = ["RobotState", "RobotTfTree", "compose", "world_tf_tree"]


class RobotState(Protocol):
    """What the tree reads from the world (``DoorWorld`` has both)."""

    def joint_positions(self) -> Mapping[str, float]: ...

    def base_pose(self) -> np.ndarray: ...


class RobotTfTree:
    """The static and moving transforms of one robot in one world.

    ``optical_offset`` is ``camera_link_T_optical``. Moving joints the sim does not simulate
    (absent from its joint positions) are left out and named in ``skipped``.
    """

    def __init__(self, world: RobotState, urdf_text: str, camera_link: str, optical_offset: np.ndarray) -> None:
        self._world = world
        joints = urdf_joints(urdf_text)
        self.root = root_link(joints)
        simulated = set(world.joint_positions())
        self.joints = tuple(j for j in joints if not j.moving or j.name in simulated)
        self.skipped = tuple(j.name for j in joints if j.moving and j.name not in simulated)
        self._moving = tuple(j for j in self.joints if j.moving)
        statics = [FrameTransform(j.parent, j.child, j.origin) for j in self.joints if not j.moving]
        statics.append(FrameTransform(camera_link, Frame.HEAD_CAMERA_OPTICAL.value, np.array(optical_offset)))
        if self.root != Frame.BASE_LINK.value:
            statics.append(FrameTransform(Frame.BASE_LINK.value, self.root, np.eye(4)))
        self._static = tuple(statics)

    def static_transforms(self) -> tuple[FrameTransform, ...]:
        """For /tf_static: fixed joints, the camera's optical frame, a base_link alias if needed."""
        return self._static

    def moving_transforms(self) -> tuple[FrameTransform, ...]:
        """For /tf, now: ``odom → base_link`` and every moving joint at the sim's positions."""
        positions = self._world.joint_positions()
        matrices = joint_transforms(self._moving, np.array([positions[j.name] for j in self._moving]))
        base = FrameTransform(Frame.ODOM.value, Frame.BASE_LINK.value, self._world.base_pose())
        return (base, *(FrameTransform(j.parent, j.child, m) for j, m in zip(self._moving, matrices)))


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


def world_tf_tree(world: DoorWorld, urdf_text: str) -> RobotTfTree:
    """The tree of a ``DoorWorld``: its robot's URDF and its head camera's optical offset,
    ``camera_link_T_optical = (odom_T_camera_link)⁻¹ · odom_T_optical``."""
    camera_link = world.profile.head_camera_frame
    offset = invert(world.link_pose(camera_link)) @ world.camera.pose()
    return RobotTfTree(world, urdf_text, camera_link, offset)
