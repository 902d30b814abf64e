"""The URDF the physical robot is simulated with: the profile's URDF with box soles.

Walking needs flat, convex soles: TALOS's mesh soles made the floating-base robot fall within
a second of stepping, box soles walked reliably (ENVIRONMENT.md, "Walking physically"). For
each foot of the profile the collision shapes of the link carrying the sole frame are replaced
by one box ``foot_length × foot_width × SOLE_THICKNESS`` whose underside lies in the sole
plane, centred under the sole frame, and the sole link's moments of inertia are raised to at
least ``MIN_FOOT_INERTIA``. The profile's extra frames (sole frames a URDF lacks) are added as
fixed links, and links without an ``<inertial>`` get a negligible one (PyBullet would make
them 1 kg). Nothing else changes (limits, meshes, other inertias), so the Pinocchio model of
:mod:`door_robot.kinematics` stays the exact kinematic twin.

Mesh references are made absolute in the copy (PyBullet resolves ``package://`` only
relative to the URDF's own folder, and the copy lives elsewhere).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from door_robot.locations import cmeel_share_dir
from door_robot.profile import RobotProfile
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.urdf_elements import joint_link, required_child

if TYPE_CHECKING:  # world.robot imports this module (for the URDF it loads)
    from door_sim_bridge.world.robot import SimRobot

__all__ = ["SolePlacement", "add_extra_frames", "box_sole_urdf", "give_frames_negligible_mass", "profile_urdf",
           "resolve_mesh", "sole_placement", "sole_placement_link"]

SOLE_THICKNESS = 0.02  # m
# kg·m², least moment of inertia of a sole link about each of its axes. The foot stands in
# for what PyBullet's joints lack: the ankle rotors' reflected inertia (armature). With its
# URDF foot (0.6 kg, ixx 2.2e-4) G1 tipped over in its first steps at 240 Hz (at 1 kHz after
# five); with 0.003 (about TALOS's foot, ixx 0.0038, which walked unchanged) it walks.
MIN_FOOT_INERTIA = 0.003
FRAME_LINK_MASS = 1e-3  # kg: PyBullet gives a link without <inertial> 1 kg and unit inertia


@dataclass(frozen=True)
class SolePlacement:
    """Where a sole frame sits on the link that carries it (a chain of fixed joints)."""

    carrier_link: str
    offset: np.ndarray  # 4×4, sole frame in the carrier link's frame


def _origin_matrix(joint: ET.Element) -> np.ndarray:
    origin = joint.find("origin")
    xyz = [float(v) for v in (origin.get("xyz", "0 0 0") if origin is not None else "0 0 0").split()]
    rpy = [float(v) for v in (origin.get("rpy", "0 0 0") if origin is not None else "0 0 0").split()]
    from scipy.spatial.transform import Rotation

    matrix = np.eye(4)
    matrix[:3, :3] = Rotation.from_euler("xyz", rpy).as_matrix()
    matrix[:3, 3] = xyz
    return matrix


def sole_placement(root: ET.Element, sole_frame: str) -> SolePlacement:
    """Follow fixed joints up from ``sole_frame`` to the first link with a collision shape
    or a movable parent joint: the link whose shapes touch the floor."""
    parent_joint = {required_child(joint, "child").get("link"): joint for joint in root.findall("joint")}
    links = {link.get("name"): link for link in root.findall("link")}
    if sole_frame not in links:
        raise SimulationError(f"URDF has no link {sole_frame!r} (a foot of the profile)")
    offset, link = np.eye(4), sole_frame
    while link in parent_joint and parent_joint[link].get("type") == "fixed" \
            and links[link].find("collision") is None:
        joint = parent_joint[link]
        offset = _origin_matrix(joint) @ offset
        link = joint_link(joint, "parent")
    return SolePlacement(link, offset)


def add_extra_frames(root: ET.Element, profile: RobotProfile) -> None:
    """Add the profile's extra frames (e.g. sole frames on the sole plane) as fixed links."""
    names = {link.get("name") for link in root.findall("link")}
    for name, extra in profile.extra_frames.items():
        if extra.parent not in names:
            raise SimulationError(f"{profile.name}: extra frame {name!r} has no parent link {extra.parent!r}")
        if name in names:
            raise SimulationError(f"{profile.name}: extra frame {name!r} is already a link of the URDF")
        ET.SubElement(root, "link", name=name)
        joint = ET.SubElement(root, "joint", name=f"{name}_frame_joint", type="fixed")
        ET.SubElement(joint, "parent", link=extra.parent)
        ET.SubElement(joint, "child", link=name)
        ET.SubElement(joint, "origin", xyz=" ".join(f"{v:.6f}" for v in extra.xyz), rpy="0 0 0")


def give_frames_negligible_mass(root: ET.Element) -> None:
    """Links without an ``<inertial>`` (sensor frames, the extra frames) get 1 g and a tiny
    inertia: PyBullet would make each of them 1 kg with unit inertia (G1's camera, lidar and IMU
    frames added 4 kg at the head and torso that the controller's Pinocchio model does not have)."""
    for link in root.findall("link"):
        if link.find("inertial") is None:
            inertial = ET.SubElement(link, "inertial")
            ET.SubElement(inertial, "mass", value=f"{FRAME_LINK_MASS:g}")
            ET.SubElement(inertial, "inertia", ixx="1e-7", iyy="1e-7", izz="1e-7", ixy="0", ixz="0", iyz="0")


def profile_urdf(profile: RobotProfile) -> str:
    """The profile's URDF text with its extra frames, meshes made absolute (no box soles)."""
    root = ET.parse(profile.urdf_path).getroot()
    add_extra_frames(root, profile)
    give_frames_negligible_mass(root)
    _absolute_meshes(root, profile.urdf_path.parent)
    return ET.tostring(root, encoding="unicode")


def box_sole_urdf(profile: RobotProfile) -> str:
    """The profile's URDF text with its extra frames and box soles (see the module docstring)."""
    tree = ET.parse(profile.urdf_path)
    root = tree.getroot()
    add_extra_frames(root, profile)
    give_frames_negligible_mass(root)
    links = {link.get("name"): link for link in root.findall("link")}
    walking = profile.walking
    for sole_frame in profile.feet.values():
        placement = sole_placement(root, sole_frame)
        carrier = links[placement.carrier_link]
        for collision in carrier.findall("collision"):
            carrier.remove(collision)
        _raise_inertia(carrier, MIN_FOOT_INERTIA)
        centre = placement.offset @ np.array([0.0, 0.0, SOLE_THICKNESS / 2.0, 1.0])
        collision = ET.SubElement(carrier, "collision", name=f"{sole_frame}_box")
        ET.SubElement(collision, "origin", xyz=" ".join(f"{v:.6f}" for v in centre[:3]),
                      rpy=_rpy_text(placement.offset[:3, :3]))
        geometry = ET.SubElement(collision, "geometry")
        ET.SubElement(geometry, "box", size=f"{walking.foot_length:.4f} {walking.foot_width:.4f} "
                                            f"{SOLE_THICKNESS:.4f}")
    _absolute_meshes(root, profile.urdf_path.parent)
    return ET.tostring(root, encoding="unicode")


def _raise_inertia(link: ET.Element, least: float) -> None:
    """Raise the diagonal of ``link``'s inertia to at least ``least`` (kg·m²)."""
    inertia = link.find("inertial/inertia")
    if inertia is None:
        raise SimulationError(f"sole link {link.get('name')!r} has no inertia: it cannot stand")
    for axis in ("ixx", "iyy", "izz"):
        inertia.set(axis, f"{max(float(inertia.get(axis, '0')), least):.6g}")


def _rpy_text(rotation: np.ndarray) -> str:
    from scipy.spatial.transform import Rotation

    return " ".join(f"{v:.6f}" for v in Rotation.from_matrix(rotation).as_euler("xyz"))


def resolve_mesh(filename: str, urdf_folder: Path) -> str:
    """An absolute path for a mesh reference (``package://pkg/…`` or relative), else unchanged.

    ``package://pkg/rest`` is looked up under ``cmeel.prefix/share/pkg`` (example-robot-data),
    then under a folder named ``pkg`` above the URDF, then as ``pkg/rest`` and ``rest`` beside it.
    """
    if filename.startswith("package://"):
        package, _, rest = filename[len("package://"):].partition("/")
        candidates = [cmeel_share_dir() / package / rest]
        candidates += [ancestor / rest for ancestor in urdf_folder.parents if ancestor.name == package]
        # beside the URDF as PyBullet itself resolves it (package:// stripped): Atlas's layout
        candidates += [urdf_folder / package / rest, urdf_folder / rest, urdf_folder.parent / rest]
    elif "://" in filename or filename.startswith("/"):
        return filename
    else:
        candidates = [urdf_folder / filename]
    found = next((path for path in candidates if path.is_file()), None)
    return str(found) if found is not None else filename


def _absolute_meshes(root: ET.Element, urdf_folder: Path) -> None:
    """Mesh references resolve from anywhere: the copy is written outside the URDF's folder."""
    for mesh in root.iter("mesh"):
        filename = mesh.get("filename", "")
        if filename:
            mesh.set("filename", resolve_mesh(filename, urdf_folder))


def sole_placement_link(robot: SimRobot, sole_frame: str) -> int:
    """PyBullet link index of the link whose (box) sole touches the floor under ``sole_frame``
    (``robot`` is a :class:`~door_sim_bridge.world.robot.SimRobot`)."""
    return robot.link_index(sole_placement(ET.fromstring(robot.urdf_text), sole_frame).carrier_link)
