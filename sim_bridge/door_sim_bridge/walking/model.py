"""The walking controller's kinematic model: placo's ``HumanoidRobot`` of a robot profile.

placo (Rhoban, on Pinocchio) wants three frames by name: ``left_foot`` and ``right_foot`` (the
soles, where the walk pattern places footsteps) and ``trunk`` (the floating base). They are
added as fixed child links of the profile's sole frames and base frame in a geometry-free
copy of the URDF (placo's model needs no meshes). The joints are split once from the URDF
tree: **leg joints** lie on the path from the base to a sole and belong to balance; every
other movable joint is **upper body** (torso, arms, neck, grippers) and follows commands.
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import tempfile
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import placo

from door_contract.vocabulary import Side
from door_robot.profile import RobotProfile
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.urdf_elements import joint_link, required_attribute, required_child

__all__ = ["PLACO_TRUNK_FRAME", "JointSplit", "joint_split", "load_placo_robot", "placo_urdf_text"]

PLACO_FOOT_FRAMES = {Side.LEFT: "left_foot", Side.RIGHT: "right_foot"}
PLACO_TRUNK_FRAME = "trunk"
MOVABLE = ("revolute", "prismatic", "continuous")


@dataclass(frozen=True)
class JointSplit:
    """Which movable joints balance the robot (legs) and which follow commands (upper body)."""

    legs: tuple[str, ...]
    upper_body: tuple[str, ...]


def joint_split(urdf_text: str, feet: dict[Side, str]) -> JointSplit:
    """Leg joints: movable joints on the paths from the root link to the sole frames."""
    root = ET.fromstring(urdf_text)
    parent_joint = {required_child(joint, "child").get("link"): joint for joint in root.findall("joint")}
    legs: list[str] = []
    for sole in feet.values():
        link = sole
        while link in parent_joint:
            joint = parent_joint[link]
            if joint.get("type") in MOVABLE and joint.get("name") not in legs:
                legs.append(required_attribute(joint, "name"))
            link = joint_link(joint, "parent")
    movable = [required_attribute(j, "name") for j in root.findall("joint")
               if j.get("type") in MOVABLE and j.find("mimic") is None]
    if not legs:
        raise SimulationError("no leg joints between the base and the soles")
    return JointSplit(tuple(name for name in movable if name in legs),
                      tuple(name for name in movable if name not in legs))


def placo_urdf_text(urdf_text: str, profile: RobotProfile) -> str:
    """Geometry-free URDF with placo's ``left_foot``, ``right_foot`` and ``trunk`` frames."""
    text = re.sub(r"<visual\b.*?</visual>", "", urdf_text, flags=re.S)
    text = re.sub(r"<collision\b.*?</collision>", "", text, flags=re.S)
    frames = [(PLACO_FOOT_FRAMES[side], profile.feet[side]) for side in (Side.LEFT, Side.RIGHT)]
    frames.append((PLACO_TRUNK_FRAME, profile.base_frame))
    extra = "".join(f'<link name="{name}"/><joint name="{name}_frame" type="fixed">'
                    f'<parent link="{parent}"/><child link="{name}"/>'
                    f'<origin xyz="0 0 0" rpy="0 0 0"/></joint>\n' for name, parent in frames)
    if "</robot>" not in text:
        raise SimulationError("URDF text has no </robot> end tag")
    return text.replace("</robot>", extra + "</robot>")


def load_placo_robot(urdf_text: str, profile: RobotProfile) -> placo.HumanoidRobot:
    """placo's HumanoidRobot of ``urdf_text`` (written to a temporary file: placo reads paths)."""
    with tempfile.TemporaryDirectory(prefix="door_walker_") as folder:
        path = Path(folder) / f"{profile.name}_placo.urdf"
        path.write_text(placo_urdf_text(urdf_text, profile))
        with _quiet_stderr():  # placo warns about frames (head, legs) it does not need
            return placo.HumanoidRobot(str(path), placo.Flags.ignore_collisions)


@contextlib.contextmanager
def _quiet_stderr() -> Iterator[None]:
    """Silence the C++ library's stderr (file descriptor 2) for the duration."""
    sys.stderr.flush()
    saved = os.dup(2)
    try:
        with open(os.devnull, "w") as devnull:
            os.dup2(devnull.fileno(), 2)
        yield
    finally:
        os.dup2(saved, 2)
        os.close(saved)
