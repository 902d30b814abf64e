"""Rendered evaluation scenes from the project's simulation core (``door_sim_bridge``).

One :class:`Scenario` (distance, viewing angle, colours, depth noise, hinge side) becomes a
:class:`SceneFrame`: the head camera's RGB-D frame of a :class:`DoorWorld` and the ground
truth in the camera's optical frame, plus a synthetic operator scribble.

Viewing geometry: the robot stands ``distance`` from the door centre (base to the door
plane's centre line), on the line that makes ``yaw`` with the door normal, and faces the
door centre: ``StanceConfig(distance·cos yaw, −distance·sin yaw, yaw)``.  Both the
robot's yaw and the angle under which the door is seen are therefore ``yaw`` (the
paper's "orientation", Table II).  The head is pitched to look at a point
``aim_above_handle`` above the handle height, as an operator would point it.

Only the evaluation, the benchmark and the tests import this module (it needs the sim).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from door_contract.converters.camera_info import CameraIntrinsics
from door_contract.vocabulary import Side

if TYPE_CHECKING:  # the sim is imported where a world is built, not with this module
    from door_sim_bridge.world import DoorWorld, WorldConfig

__all__ = ["DOOR_COLOURS", "HANDLE_COLOURS", "Scenario", "SceneFrame", "lever_corners", "render_scenario",
           "synthetic_scribble"]

CAMERA_WIDTH = 1024
CAMERA_HEIGHT = 544
CAMERA_VERTICAL_FOV_DEG = 48.0
"""MultiSense-SL-like head camera, 1024×544 and ~80°×48° (fx ≈ 611 px)."""
HEAD_CAMERA_HEIGHT = 1.57
"""TALOS's head camera above the floor in the nominal posture (m), for aiming the head."""

DOOR_COLOURS: tuple[tuple[str, tuple[float, float, float]], ...] = (
    ("brown", (0.55, 0.33, 0.17)), ("light wood", (0.76, 0.60, 0.42)),
    ("green", (0.20, 0.40, 0.25)), ("red", (0.60, 0.15, 0.12)))
HANDLE_COLOURS: tuple[tuple[str, tuple[float, float, float]], ...] = (
    ("brass", (0.85, 0.70, 0.15)), ("steel", (0.75, 0.75, 0.78)), ("black", (0.08, 0.08, 0.08)))


@dataclass(frozen=True)
class Scenario:
    """One evaluation scene (see the module docstring for the geometry)."""

    distance: float = 2.0
    """Robot base to the door centre (m)."""
    yaw: float = 0.0
    """Viewing angle from the door normal = robot yaw (rad), > 0 turns the robot left."""
    door_colour: tuple[float, float, float] = DOOR_COLOURS[0][1]
    handle_colour: tuple[float, float, float] = HANDLE_COLOURS[0][1]
    depth_noise: float = 0.0
    """Stereo-like depth noise coefficient k, σ = k·z² (1/m)."""
    hinge_side: Side = Side.LEFT
    """Hinge side as seen from the robot (= image side for |yaw| < ~1 rad)."""
    aim_above_handle: float = 0.15
    """The head looks at this height above the handle (m)."""
    seed: int = 0


@dataclass(frozen=True, eq=False)
class SceneFrame:
    """A rendered frame and its ground truth (camera optical frame, metres)."""

    scenario: Scenario
    rgb: np.ndarray
    depth: np.ndarray
    intrinsics: CameraIntrinsics
    handle_position: np.ndarray
    normal: np.ndarray
    scribble: np.ndarray | None
    """Synthetic operator scribble (N, 2) px, None when the lever is not in the image."""
    up: np.ndarray
    """The world's up (odom +z) in the optical frame, as tf would give the node."""


def render_scenario(scenario: Scenario, scribble_noise_px: float = 2.0) -> SceneFrame:
    """Build the world, render the head camera once, and express the ground truth in the
    optical frame (p_opt = Rᵀ(p − t) with (R, t) the camera pose in odom)."""
    from door_sim_bridge.world import DoorWorld

    with DoorWorld(_world_config(scenario)) as world:
        frame = world.render()
        camera = frame.camera_pose
        grasp = world.handle_grasp_pose()
        truth = world.door_ground_truth()
        lever = lever_corners(world)
    rotation, origin = camera[:3, :3], camera[:3, 3]
    handle = (grasp[:3, 3] - origin) @ rotation
    normal = truth.normal @ rotation
    pixels = frame.intrinsics.project((lever - origin) @ rotation)
    rng = np.random.default_rng(scenario.seed + 7919)
    scribble = synthetic_scribble(pixels, frame.intrinsics, rng, scribble_noise_px)
    up = np.array([0.0, 0.0, 1.0]) @ rotation
    return SceneFrame(scenario, frame.rgb, frame.depth, frame.intrinsics, handle, normal, scribble, up)


def _world_config(scenario: Scenario) -> WorldConfig:
    from door_sim_bridge.world import CameraConfig, DoorConfig, RobotVisuals, StanceConfig, WorldConfig

    door = DoorConfig(hinge_side=scenario.hinge_side, door_colour=scenario.door_colour,
                      handle_colour=scenario.handle_colour)
    pitch = math.atan2(HEAD_CAMERA_HEIGHT - door.handle_height - scenario.aim_above_handle,
                       scenario.distance)
    camera = CameraConfig(width=CAMERA_WIDTH, height=CAMERA_HEIGHT,
                          vertical_fov_deg=CAMERA_VERTICAL_FOV_DEG,
                          depth_noise_coefficient=scenario.depth_noise, head_pitch=pitch,
                          robot_visuals=RobotVisuals.NONE)
    stance = StanceConfig(distance=scenario.distance * math.cos(scenario.yaw),
                          lateral_offset=-scenario.distance * math.sin(scenario.yaw), yaw=scenario.yaw)
    return WorldConfig(door=door, stance=stance, camera=camera, seed=scenario.seed)


def lever_corners(world: DoorWorld) -> np.ndarray:
    """The 8 corners (odom) of the lever bar, from the door's geometry (evaluation only)."""
    from door_sim_bridge.world import DoorPart
    from door_sim_bridge.world.door import LEVER_SECTION

    config, geometry = world.door.config, world.door.geometry
    pose = world.door.link_pose(DoorPart.HANDLE)
    direction = geometry.lever_direction
    centre = direction * config.lever_length / 2
    half = np.abs(direction) * (config.lever_length + LEVER_SECTION) / 2 + \
        (1 - np.abs(direction)) * LEVER_SECTION / 2
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    local = centre + signs * half
    return local @ pose[:3, :3].T + pose[:3, 3]


def synthetic_scribble(pixels: np.ndarray, intrinsics: CameraIntrinsics, rng: np.random.Generator,
                       noise_px: float) -> np.ndarray | None:
    """An operator's polygon around projected handle points: their convex hull, each
    vertex moved by uniform noise of ±``noise_px``, clipped to the image; None when the
    handle is entirely outside the image (the operator cannot mark it)."""
    import cv2

    hull = cv2.convexHull(pixels.astype(np.float32)).reshape(-1, 2).astype(float)
    hull += rng.uniform(-noise_px, noise_px, size=hull.shape)
    inside = (hull[:, 0] >= 0) & (hull[:, 0] <= intrinsics.width - 1) & \
             (hull[:, 1] >= 0) & (hull[:, 1] <= intrinsics.height - 1)
    if not inside.any():
        return None
    hull[:, 0] = np.clip(hull[:, 0], 0, intrinsics.width - 1)
    hull[:, 1] = np.clip(hull[:, 1], 0, intrinsics.height - 1)
    return hull
