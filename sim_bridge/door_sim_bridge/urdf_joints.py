"""A URDF's joints as kinematics (ROS-free): parent and child links, origin and axis, and the
transform each joint makes at a given position — what ``robot_state_publisher`` computes.

A joint's child frame in its parent's frame is ``parent_T_child(q) = O · M(q)``: ``O`` the
joint's ``<origin xyz rpy>`` (rotation ``Rz(yaw) Ry(pitch) Rx(roll)``), and ``M(q)`` a rotation
by ``q`` about the unit ``<axis>`` (revolute, continuous: Rodrigues,
``R = I + sin q · K + (1 − cos q) · K²`` with ``K`` the axis's cross-product matrix) or a
translation by ``q · axis`` (prismatic); ``M = I`` for fixed joints.
"""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from door_sim_bridge.errors import SimulationError
from door_sim_bridge.urdf_elements import required_child

__all__ = ["UrdfJoint", "joint_transforms", "root_link", "urdf_joints"]

ROTATING = frozenset({"revolute", "continuous"})
SLIDING = frozenset({"prismatic"})


@dataclass(frozen=True, eq=False)
class UrdfJoint:
    """One joint of a URDF: name, type, parent and child links, origin (4×4) and unit axis."""

    name: str
    kind: str
    parent: str
    child: str
    origin: np.ndarray
    axis: np.ndarray

    @property
    def moving(self) -> bool:
        return self.kind in ROTATING | SLIDING


def _vector(element: ElementTree.Element | None, attribute: str, default: str) -> np.ndarray:
    text = element.get(attribute, default) if element is not None else default
    try:
        return np.array([float(v) for v in text.split()], dtype=float).reshape(3)
    except ValueError:
        raise SimulationError(f"robot description: {attribute}={text!r} is not three numbers") from None


def _joint(element: ElementTree.Element) -> UrdfJoint:
    origin_element = element.find("origin")
    origin = np.eye(4)
    origin[:3, :3] = Rotation.from_euler("xyz", _vector(origin_element, "rpy", "0 0 0")).as_matrix()
    origin[:3, 3] = _vector(origin_element, "xyz", "0 0 0")
    kind = element.get("type", "")
    axis = _vector(element.find("axis"), "xyz", "1 0 0")
    if np.linalg.norm(axis) < 1e-12:
        if kind in ROTATING | SLIDING:
            raise SimulationError(f"robot description: joint {element.get('name')!r} has a zero axis")
        axis = np.array([1.0, 0.0, 0.0])  # a fixed joint's axis means nothing (TALOS writes 0 0 0)
    return UrdfJoint(element.get("name", ""), kind, required_child(element, "parent").get("link", ""),
                     required_child(element, "child").get("link", ""), origin, axis / np.linalg.norm(axis))


def urdf_joints(urdf_text: str) -> tuple[UrdfJoint, ...]:
    """The joints of a URDF document; SimulationError if it is not a URDF with joints."""
    try:
        robot = ElementTree.fromstring(urdf_text)
    except ElementTree.ParseError as error:
        raise SimulationError(f"robot description is not XML: {error}") from None
    # a <joint> inside <transmission> has no parent/child: not a kinematic joint
    joints = tuple(_joint(e) for e in robot.iter("joint") if e.find("parent") is not None and e.find("child") is not None)
    if robot.tag != "robot" or not joints:
        raise SimulationError("robot description has no <robot> with joints")
    return joints


def root_link(joints: Sequence[UrdfJoint]) -> str:
    """The one link that is no joint's child."""
    roots = {j.parent for j in joints} - {j.child for j in joints}
    if len(roots) != 1:
        raise SimulationError(f"robot description must have one root link, found {sorted(roots)}")
    return roots.pop()


def joint_transforms(joints: Sequence[UrdfJoint], positions: np.ndarray) -> np.ndarray:
    """(N, 4, 4) ``parent_T_child`` of moving ``joints`` at ``positions`` (N,), all at once."""
    origins = np.array([j.origin for j in joints]).reshape(-1, 4, 4)
    axes = np.array([j.axis for j in joints]).reshape(-1, 3)
    q = np.asarray(positions, dtype=float).reshape(-1)
    motion = np.repeat(np.eye(4)[None], len(q), axis=0)
    rotating = np.array([j.kind in ROTATING for j in joints], dtype=bool)
    k = np.zeros((len(q), 3, 3))
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -axes[:, 2], axes[:, 1], -axes[:, 0]
    k -= np.transpose(k, (0, 2, 1))  # the cross-product matrices of the axes
    rotation = (np.eye(3) + np.sin(q)[:, None, None] * k + (1.0 - np.cos(q))[:, None, None] * (k @ k))
    motion[rotating, :3, :3] = rotation[rotating]
    motion[~rotating, :3, 3] = axes[~rotating] * q[~rotating, None]
    return origins @ motion
