"""The URDF the physical robot is simulated with: the profile's URDF with box soles.

Walking needs flat, convex soles: TALOS's mesh soles made the floating-base robot fall within
a second of stepping, box soles walked reliably (ENVIRONMENT.md, "Walking physically"). For
each foot of the profile the collision shapes of the link carrying the sole frame are replaced
by one box ``foot_length × foot_width × SOLE_THICKNESS`` whose underside lies in the sole
plane, centred under the sole frame. Nothing else changes (inertias, limits, meshes), so the
Pinocchio model of :mod:`door_robot.kinematics` stays the exact kinematic twin.

Mesh references are made absolute in the copy (PyBullet resolves ``package://`` only
relative to the URDF's own folder, and the copy lives elsewhere).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from door_robot.locations import cmeel_share_dir
from door_robot.profile import RobotProfile
from door_sim_bridge.errors import SimulationError

SOLE_THICKNESS = 0.02  # m


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
    parent_joint = {joint.find("child").get("link"): joint for joint in root.findall("joint")}
    links = {link.get("name"): link for link in root.findall("link")}
    if sole_frame not in links:
        raise SimulationError(f"URDF has no link {sole_frame!r} (a foot of the profile)")
    offset, link = np.eye(4), sole_frame
    while link in parent_joint and parent_joint[link].get("type") == "fixed" \
            and links[link].find("collision") is None:
        joint = parent_joint[link]
        offset = _origin_matrix(joint) @ offset
        link = joint.find("parent").get("link")
    return SolePlacement(link, offset)


def box_sole_urdf(profile: RobotProfile) -> str:
    """The profile's URDF text with box soles (see the module docstring)."""
    tree = ET.parse(profile.urdf_path)
    root = tree.getroot()
    links = {link.get("name"): link for link in root.findall("link")}
    walking = profile.walking
    for sole_frame in profile.feet.values():
        placement = sole_placement(root, sole_frame)
        carrier = links[placement.carrier_link]
        for collision in carrier.findall("collision"):
            carrier.remove(collision)
        centre = placement.offset @ np.array([0.0, 0.0, SOLE_THICKNESS / 2.0, 1.0])
        collision = ET.SubElement(carrier, "collision", name=f"{sole_frame}_box")
        ET.SubElement(collision, "origin", xyz=" ".join(f"{v:.6f}" for v in centre[:3]),
                      rpy=_rpy_text(placement.offset[:3, :3]))
        geometry = ET.SubElement(collision, "geometry")
        ET.SubElement(geometry, "box", size=f"{walking.foot_length:.4f} {walking.foot_width:.4f} "
                                            f"{SOLE_THICKNESS:.4f}")
    _absolute_meshes(root, profile.urdf_path.parent)
    return ET.tostring(root, encoding="unicode")


def _rpy_text(rotation: np.ndarray) -> str:
    from scipy.spatial.transform import Rotation

    return " ".join(f"{v:.6f}" for v in Rotation.from_matrix(rotation).as_euler("xyz"))


def resolve_mesh(filename: str, urdf_folder: Path) -> str:
    """An absolute path for a mesh reference (``package://pkg/…`` or relative), else unchanged.

    ``package://pkg/rest`` is looked up under ``cmeel.prefix/share/pkg`` (example-robot-data),
    then under a folder named ``pkg`` above the URDF, then as ``rest`` beside it.
    """
    if filename.startswith("package://"):
        package, _, rest = filename[len("package://"):].partition("/")
        candidates = [cmeel_share_dir() / package / rest]
        candidates += [ancestor / rest for ancestor in urdf_folder.parents if ancestor.name == package]
        candidates += [urdf_folder / rest, urdf_folder.parent / rest]
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


def sole_placement_link(robot, sole_frame: str) -> int:
    """PyBullet link index of the link whose (box) sole touches the floor under ``sole_frame``
    (``robot`` is a :class:`~door_sim_bridge.world.robot.SimRobot`)."""
    return robot.link_index(sole_placement(ET.fromstring(robot.urdf_text), sole_frame).carrier_link)
