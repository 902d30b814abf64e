"""The door, its frame, the wall and the floor as one PyBullet multibody built from a URDF text.

Geometry convention (world frame = ``odom``, REP-103 axes, z up):

* the wall's robot-side face is the plane x = 0; the wall occupies 0 ≤ x ≤ WALL_THICKNESS;
  the doorway is centred at y = 0; the floor is z = 0;
* the robot starts on the x < 0 side facing +x; seen from it, a LEFT-hinged door has its hinge
  edge at y = +width/2 and a RIGHT-hinged one at y = -width/2;
* the closed leaf occupies 0 ≤ x ≤ thickness, so its robot-side face lies in the door plane
  x = 0; a PUSH door swings towards +x about an axis on its far face (x = thickness), a PULL
  door towards -x about an axis on its near face (x = 0);
* the hinge angle is positive when the door opens; the lever handle sits on the robot side at
  ``handle_backset`` from the latch edge, its lever pointing from the handle axis towards the
  hinge side (as real levers do); the handle angle is positive when the lever is pressed down;
* the handle grasp point lies on the lever's centre line at ``grasp_fraction`` of its length;
  its frame's x axis is the door normal towards the robot side and z points up (it turns with
  the lever and the leaf).

Multibody: base link ``scene`` (floor – visual only –, wall, jambs and header, fixed), link
``leaf`` on the revolute joint ``door_hinge``, link ``handle`` on the revolute joint
``door_handle``. Links of one PyBullet body do not collide with each other, so the leaf swings
through the frame's rebate freely; the door stop and the latch are joint limits instead.
"""

from __future__ import annotations

import math
import tempfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from enum import Enum
from pathlib import Path

import numpy as np
import pybullet

from door_contract.vocabulary import DoorOpening
from door_sim_bridge.world.client import PhysicsClient
from door_sim_bridge.world.config import DoorConfig, WindConfig
from door_sim_bridge.world.transforms import pose_matrix

__all__ = ["HANDLE_JOINT", "HINGE_JOINT", "LEVER_SECTION", "DoorGroundTruth", "DoorLayout", "DoorPart", "DoorState",
           "LatchEvent", "SimDoor", "door_urdf", "handle_torque", "hinge_torque", "wind_torque"]

WALL_THICKNESS = 0.12  # m
WALL_HALF_WIDTH = 3.0  # m
WALL_HEIGHT = 2.6  # m, at least; taller doors get a taller wall
FRAME_WIDTH = 0.06  # m, jamb and header face width
FRAME_PROTRUSION = 0.01  # m the frame stands out of the wall on both sides
EDGE_GAP = 0.004  # m between leaf and frame
FLOOR_HALF_SIZE = 8.0  # m
LEVER_SECTION = 0.02  # m, square section of the lever bar
LATCH_HYSTERESIS = 0.05  # rad the handle must come back below the release angle to re-latch

HINGE_JOINT = "door_hinge"
HANDLE_JOINT = "door_handle"


class DoorPart(str, Enum):
    """A moving part of the door that forces can be applied to."""

    LEAF = "leaf"
    HANDLE = "handle"


@dataclass(frozen=True)
class DoorState:
    """Joint state of the door: angles in rad (hinge > 0 = open, handle > 0 = pressed down)."""

    hinge_angle: float
    handle_angle: float
    latched: bool
    hinge_velocity: float = 0.0  # rad/s
    handle_velocity: float = 0.0  # rad/s


@dataclass(frozen=True, eq=False)
class DoorGroundTruth:
    """Where the door is now (odom frame): for evaluation and tests only, never for the robot."""

    hinge_point: np.ndarray  # (3,) on the hinge axis at floor height
    hinge_axis: np.ndarray  # (3,) unit, positive rotation opens the door
    corners: np.ndarray  # (4, 3) robot-side face: bottom-hinge, bottom-latch, top-latch, top-hinge
    normal: np.ndarray  # (3,) unit normal of the robot-side face, pointing towards the robot side
    handle_grasp_pose: np.ndarray  # (4, 4) grasp frame: x = normal towards robot, z up
    opening: DoorOpening
    width: float
    height: float


@dataclass(frozen=True, eq=False)
class DoorLayout:
    """Fixed placements of the door's joints and shapes, derived from a :class:`DoorConfig`.

    Leaf link frame: on the hinge axis at floor height, world-aligned when closed. Handle link
    frame: on the handle axis at the lever's centre line, world-aligned when closed and at rest.
    """

    hinge_origin: np.ndarray  # (3,) in the scene (world) frame
    hinge_axis: np.ndarray  # (3,) in the leaf frame (= world when closed)
    leaf_centre: np.ndarray  # (3,) in the leaf frame
    handle_origin: np.ndarray  # (3,) in the leaf frame
    handle_axis: np.ndarray  # (3,) in the handle frame
    lever_direction: np.ndarray  # (3,) unit, in the handle frame
    grasp_in_handle: np.ndarray  # (4, 4) grasp frame in the handle frame
    face_corners: np.ndarray  # (4, 3) robot-side face corners in the leaf frame

    @classmethod
    def from_config(cls, door: DoorConfig) -> DoorLayout:
        side = door.hinge_side.sign
        swing = 1.0 if door.opening is DoorOpening.PUSH else -1.0
        axis_x = door.thickness if door.opening is DoorOpening.PUSH else 0.0
        hinge_origin = np.array([axis_x, side * door.width / 2.0, 0.0])
        lever_direction = np.array([0.0, side, 0.0])
        # the lever tip must move down (-z) for a positive turn: axis = lever x (-z)
        handle_axis = np.cross(lever_direction, [0.0, 0.0, -1.0])
        grasp = np.diag([-1.0, -1.0, 1.0, 1.0])  # x towards the robot (-x), z up
        grasp[:3, 3] = lever_direction * door.grasp_fraction * door.lever_length
        face_x = -axis_x
        bottom, top = door.floor_gap, door.floor_gap + door.height
        latch_y = -side * door.width
        return cls(
            hinge_origin=hinge_origin,
            hinge_axis=np.array([0.0, 0.0, side * swing]),
            leaf_centre=np.array([door.thickness / 2.0 - axis_x, -hinge_origin[1],
                                  door.floor_gap + door.height / 2.0]),
            handle_origin=np.array([face_x - door.lever_standoff,
                                    side * (door.handle_backset - door.width), door.handle_height]),
            handle_axis=handle_axis,
            lever_direction=lever_direction,
            grasp_in_handle=grasp,
            face_corners=np.array([[face_x, 0.0, bottom], [face_x, latch_y, bottom],
                                   [face_x, latch_y, top], [face_x, 0.0, top]]),
        )


# ---------------------------------------------------------------------------- URDF text
def _vector(values: np.ndarray | tuple[float, ...]) -> str:
    return " ".join(f"{float(v):.6f}" for v in values)


def _box_element(parent: ET.Element, tag: str, centre: tuple[float, ...], size: tuple[float, ...],
                 colour: tuple[float, float, float] | None = None, name: str = "") -> None:
    shape = ET.SubElement(parent, tag)
    ET.SubElement(shape, "origin", xyz=_vector(centre), rpy="0 0 0")
    ET.SubElement(ET.SubElement(shape, "geometry"), "box", size=_vector(size))
    if colour is not None:
        material = ET.SubElement(shape, "material", name=name)
        ET.SubElement(material, "color", rgba=_vector((*colour, 1.0)))


def _cylinder_along_x(parent: ET.Element, tag: str, centre: tuple[float, ...], radius: float,
                      length: float, colour: tuple[float, float, float] | None, name: str) -> None:
    shape = ET.SubElement(parent, tag)
    ET.SubElement(shape, "origin", xyz=_vector(centre), rpy=f"0 {math.pi / 2:.6f} 0")
    ET.SubElement(ET.SubElement(shape, "geometry"), "cylinder", radius=f"{radius:.6f}",
                  length=f"{length:.6f}")
    if colour is not None:
        material = ET.SubElement(shape, "material", name=name)
        ET.SubElement(material, "color", rgba=_vector((*colour, 1.0)))


def _inertial(link: ET.Element, mass: float, centre: np.ndarray, size: tuple[float, float, float]) -> None:
    """Solid-box inertia about its centre: I_xx = m (b² + c²) / 12, and so on."""
    a, b, c = size
    inertial = ET.SubElement(link, "inertial")
    ET.SubElement(inertial, "origin", xyz=_vector(centre), rpy="0 0 0")
    ET.SubElement(inertial, "mass", value=f"{mass:.6f}")
    ET.SubElement(inertial, "inertia", ixx=f"{mass * (b * b + c * c) / 12:.6f}",
                  iyy=f"{mass * (a * a + c * c) / 12:.6f}", izz=f"{mass * (a * a + b * b) / 12:.6f}",
                  ixy="0", ixz="0", iyz="0")


def _static_boxes(door: DoorConfig) -> list[tuple[str, tuple[float, ...], tuple[float, ...]]]:
    """(kind, centre, size) of the wall segments, jambs and header (scene frame)."""
    opening_half = door.width / 2.0 + EDGE_GAP
    opening_top = door.floor_gap + door.height + EDGE_GAP
    outer_half = opening_half + FRAME_WIDTH
    frame_depth = WALL_THICKNESS + 2.0 * FRAME_PROTRUSION
    side_width = WALL_HALF_WIDTH - outer_half
    wall_height = max(WALL_HEIGHT, opening_top + FRAME_WIDTH + 0.3)
    mid_x = WALL_THICKNESS / 2.0
    boxes: list[tuple[str, tuple[float, ...], tuple[float, ...]]]
    boxes = [("wall", (mid_x, sign * (outer_half + side_width / 2.0), wall_height / 2.0),
              (WALL_THICKNESS, side_width, wall_height)) for sign in (1.0, -1.0)]
    above = wall_height - opening_top - FRAME_WIDTH
    boxes.append(("wall", (mid_x, 0.0, wall_height - above / 2.0), (WALL_THICKNESS, 2 * outer_half, above)))
    boxes += [("frame", (mid_x, sign * (opening_half + FRAME_WIDTH / 2.0), opening_top / 2.0),
               (frame_depth, FRAME_WIDTH, opening_top)) for sign in (1.0, -1.0)]
    boxes.append(("frame", (mid_x, 0.0, opening_top + FRAME_WIDTH / 2.0),
                  (frame_depth, 2.0 * outer_half, FRAME_WIDTH)))
    return boxes


def _scene_link(robot: ET.Element, door: DoorConfig) -> None:
    link = ET.SubElement(robot, "link", name="scene")
    _inertial(link, 0.0, np.zeros(3), (1.0, 1.0, 1.0))  # fixed base: mass 0
    colours = {"wall": door.wall_colour, "frame": door.frame_colour}
    _box_element(link, "visual", (0.0, 0.0, -0.005), (2 * FLOOR_HALF_SIZE, 2 * FLOOR_HALF_SIZE, 0.01),
                 door.floor_colour, "floor")
    for kind, centre, size in _static_boxes(door):
        _box_element(link, "visual", centre, size, colours[kind], kind)
        _box_element(link, "collision", centre, size)


def _leaf_link(robot: ET.Element, door: DoorConfig, geometry: DoorLayout) -> None:
    link = ET.SubElement(robot, "link", name="leaf")
    size = (door.thickness, door.width, door.height)
    _inertial(link, door.mass, geometry.leaf_centre, size)
    _box_element(link, "visual", tuple(geometry.leaf_centre), size, door.door_colour, "door")
    _box_element(link, "collision", tuple(geometry.leaf_centre), size)


def _handle_link(robot: ET.Element, door: DoorConfig, geometry: DoorLayout) -> None:
    link = ET.SubElement(robot, "link", name="handle")
    lever_centre = geometry.lever_direction * door.lever_length / 2.0
    lever_size = (LEVER_SECTION, door.lever_length + LEVER_SECTION, LEVER_SECTION)
    _inertial(link, door.handle_mass, lever_centre, lever_size)
    _box_element(link, "visual", tuple(lever_centre), lever_size, door.handle_colour, "handle")
    _box_element(link, "collision", tuple(lever_centre), lever_size)
    spindle = (door.lever_standoff / 2.0, 0.0, 0.0)
    _cylinder_along_x(link, "visual", spindle, 0.011, door.lever_standoff, door.handle_colour, "handle")
    _cylinder_along_x(link, "collision", spindle, 0.011, door.lever_standoff, None, "")
    _cylinder_along_x(link, "visual", (door.lever_standoff - 0.005, 0.0, 0.0), 0.03, 0.01,
                      door.handle_colour, "handle")


def _revolute(robot: ET.Element, name: str, parent: str, child: str, origin: np.ndarray,
              axis: np.ndarray, upper: float) -> None:
    joint = ET.SubElement(robot, "joint", name=name, type="revolute")
    ET.SubElement(joint, "parent", link=parent)
    ET.SubElement(joint, "child", link=child)
    ET.SubElement(joint, "origin", xyz=_vector(origin), rpy="0 0 0")
    ET.SubElement(joint, "axis", xyz=_vector(axis))
    ET.SubElement(joint, "limit", lower="0", upper=f"{upper:.6f}", effort="1000", velocity="20")


def door_urdf(door: DoorConfig) -> str:
    """URDF text of the scene, leaf and handle for ``door``."""
    geometry = DoorLayout.from_config(door)
    robot = ET.Element("robot", name="door_scene")
    _scene_link(robot, door)
    _leaf_link(robot, door, geometry)
    _handle_link(robot, door, geometry)
    _revolute(robot, HINGE_JOINT, "scene", "leaf", geometry.hinge_origin, geometry.hinge_axis,
              door.hinge_max_angle)
    _revolute(robot, HANDLE_JOINT, "leaf", "handle", geometry.handle_origin, geometry.handle_axis,
              door.handle_max_angle)
    ET.indent(robot)  # PyBullet's URDF reader fails on very long lines
    return ET.tostring(robot, encoding="unicode")


# ---------------------------------------------------------------------------- physics
def wind_torque(wind: WindConfig, phase: float, time: float) -> float:
    """Wind torque on the hinge at ``time`` (N·m, positive opens)."""
    if not wind.enabled:
        return 0.0
    return wind.bias + wind.amplitude * math.sin(2.0 * math.pi * wind.frequency * time + phase)


def hinge_torque(door: DoorConfig, angle: float, velocity: float) -> float:
    """Door-closer spring and damper: -(preload + k theta) - c dtheta (N·m)."""
    return -(door.closer_preload + door.closer_stiffness * angle) - door.hinge_damping * velocity


def handle_torque(door: DoorConfig, angle: float, velocity: float) -> float:
    """Handle return spring and damper: -(preload + k phi) - c dphi (N·m)."""
    return -(door.handle_preload + door.handle_stiffness * angle) - door.handle_damping * velocity


class LatchEvent(str, Enum):
    RELEASED = "latch_released"
    ENGAGED = "latch_engaged"


class SimDoor:
    """The door multibody in one PyBullet client: springs, friction, latch and ground truth."""

    def __init__(self, client: PhysicsClient, config: DoorConfig, wind_phase: float) -> None:
        self._client = client
        self.config = config
        self.geometry = DoorLayout.from_config(config)
        self._wind_phase = wind_phase
        self.body = self._load(client, config)
        joints = {client.getJointInfo(self.body, j)[1].decode(): j
                  for j in range(client.getNumJoints(self.body))}
        self.hinge_index = joints[HINGE_JOINT]
        self.handle_index = joints[HANDLE_JOINT]
        self._latched = True
        self._set_friction()
        self._set_hinge_upper(config.latch_play)

    @staticmethod
    def _load(client: PhysicsClient, config: DoorConfig) -> int:
        with tempfile.TemporaryDirectory(prefix="door_sim_") as folder:
            path = Path(folder) / "door_scene.urdf"
            path.write_text(door_urdf(config))
            body: int = client.loadURDF(str(path), useFixedBase=True,
                                        flags=pybullet.URDF_USE_INERTIA_FROM_FILE)
            return body

    def _set_friction(self) -> None:
        """Coulomb friction as velocity motors with target 0 and the friction as force limit."""
        self._client.setJointMotorControlArray(
            self.body, [self.hinge_index, self.handle_index], pybullet.VELOCITY_CONTROL,
            targetVelocities=[0.0, 0.0],
            forces=[self.config.hinge_friction, self.config.handle_friction])

    def _set_hinge_upper(self, upper: float) -> None:
        self._client.changeDynamics(self.body, self.hinge_index, jointLowerLimit=0.0,
                                    jointUpperLimit=upper)

    # ------------------------------------------------------------------ per physics step
    def update(self, time: float) -> LatchEvent | None:
        """Update the latch and apply spring, damper and wind torques for the next step."""
        state = self.state()
        event = self._update_latch(state)
        torques = [hinge_torque(self.config, state.hinge_angle, state.hinge_velocity)
                   + wind_torque(self.config.wind, self._wind_phase, time),
                   handle_torque(self.config, state.handle_angle, state.handle_velocity)]
        self._client.setJointMotorControlArray(self.body, [self.hinge_index, self.handle_index],
                                               pybullet.TORQUE_CONTROL, forces=torques)
        return event

    def _update_latch(self, state: DoorState) -> LatchEvent | None:
        """Bolt retracted past the release angle; caught again near closed with the handle back up.

        The handle must return ``LATCH_HYSTERESIS`` below the release angle before the bolt
        extends again, so a hand holding the lever at the threshold does not chatter the latch.
        """
        release = self.config.latch_release_angle
        if self._latched and state.handle_angle > release:
            self._latched = False
            self._set_hinge_upper(self.config.hinge_max_angle)
            return LatchEvent.RELEASED
        handle_up = state.handle_angle < release - LATCH_HYSTERESIS
        if not self._latched and handle_up and state.hinge_angle < self.config.latch_engage_angle:
            self._latched = True
            self._set_hinge_upper(self.config.latch_play)
            return LatchEvent.ENGAGED
        return None

    # ------------------------------------------------------------------ queries
    def state(self) -> DoorState:
        hinge, handle = self._client.getJointStates(self.body, [self.hinge_index, self.handle_index])
        return DoorState(hinge_angle=hinge[0], handle_angle=handle[0], latched=self._latched,
                         hinge_velocity=hinge[1], handle_velocity=handle[1])

    def link_index(self, part: DoorPart) -> int:
        return self.hinge_index if part is DoorPart.LEAF else self.handle_index

    def link_pose(self, part: DoorPart) -> np.ndarray:
        """4×4 link frame (not the centre of mass) of the leaf or handle in the world."""
        state = self._client.getLinkState(self.body, self.link_index(part), computeForwardKinematics=True)
        return pose_matrix(state[4], state[5])

    def link_com_pose(self, part: DoorPart) -> np.ndarray:
        """4×4 centre-of-mass frame of the leaf or handle (the frame constraints refer to)."""
        state = self._client.getLinkState(self.body, self.link_index(part), computeForwardKinematics=True)
        return pose_matrix(state[0], state[1])

    def handle_grasp_pose(self) -> np.ndarray:
        """4×4 ground-truth grasp frame on the lever (x towards the robot side, z up)."""
        pose: np.ndarray = self.link_pose(DoorPart.HANDLE) @ self.geometry.grasp_in_handle
        return pose

    def ground_truth(self) -> DoorGroundTruth:
        leaf = self.link_pose(DoorPart.LEAF)
        rotation = leaf[:3, :3]
        corners = self.geometry.face_corners @ rotation.T + leaf[:3, 3]
        return DoorGroundTruth(
            hinge_point=leaf[:3, 3].copy(), hinge_axis=rotation @ self.geometry.hinge_axis,
            corners=corners, normal=rotation @ np.array([-1.0, 0.0, 0.0]),
            handle_grasp_pose=self.handle_grasp_pose(), opening=self.config.opening,
            width=self.config.width, height=self.config.height)
