"""A minimal PyBullet door scene for the detector's tests (stand-in for the sim core).

World frame: z up; the wall's front face is the plane x = 0 facing −x (towards the
camera); the doorway is centred on y = 0. The door leaf is recessed ``recess`` behind
the wall face. The handle (a lever on a neck) is on the world −y side, i.e. on the
**right** of the image for a camera looking along +x: hinge LEFT.

The camera is a pinhole like the MultiSense SL head (1024×544, 80° horizontal field of
view); depth is z-depth in metres linearised from the z-buffer,
d = far·near / (far − (far − near)·zbuf), with optional stereo-like noise σ = k·d².
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pybullet

from door_contract.converters.camera_info import CameraIntrinsics

DOOR_WIDTH = 0.914
DOOR_HEIGHT = 2.083
HANDLE_HEIGHT = 0.95
HANDLE_FROM_EDGE = 0.075
LEVER_LENGTH = 0.12
LEVER_SECTION = 0.022
LEVER_STANDOFF = 0.06
GRASP_FRACTION = 0.6
"""The grasp point lies on the lever's centre line, 0.6 of its length from its axis (the
sim core's convention, ``DoorConfig.grasp_fraction``)."""


@dataclass(frozen=True)
class SceneSpec:
    distance: float = 2.0
    """Camera distance from the door plane (m), measured from the door centre."""
    yaw: float = 0.0
    """Angle of the viewing direction from the door normal (rad)."""
    camera_height: float = 1.5
    door_rgb: tuple[float, float, float] = (0.55, 0.36, 0.20)
    handle_rgb: tuple[float, float, float] = (0.80, 0.80, 0.82)
    wall_rgb: tuple[float, float, float] = (0.86, 0.83, 0.76)
    noise_k: float = 0.0
    """Depth noise σ = noise_k·d² (m)."""
    recess: float = 0.015
    width: int = 1024
    height: int = 544
    seed: int = 0


@dataclass(frozen=True)
class RenderedScene:
    rgb: np.ndarray
    depth: np.ndarray
    intrinsics: CameraIntrinsics
    handle_position: np.ndarray
    """Ground-truth grasp point, optical frame."""
    normal: np.ndarray
    """Ground-truth door normal towards the camera, optical frame."""
    handle_polygon: np.ndarray
    """Pixel polygon (N×2) around the projected lever (a synthetic scribble)."""


def _box(client: int, half: tuple[float, float, float], centre: tuple[float, float, float],
         rgb: tuple[float, float, float]) -> None:
    visual = pybullet.createVisualShape(pybullet.GEOM_BOX, halfExtents=half,
                                        rgbaColor=(*rgb, 1.0), physicsClientId=client)
    pybullet.createMultiBody(0, -1, visual, basePosition=centre, physicsClientId=client)


def _build(client: int, spec: SceneSpec) -> tuple[np.ndarray, np.ndarray]:
    """Wall, floor, door, a lever on a square neck (no rose, unlike the sim core's).
    Returns the grasp point and the lever's corner points (world)."""
    gap = 0.006
    half_open = DOOR_WIDTH / 2 + gap
    _box(client, (0.1, 3.0, 1.35), (0.1, -3.0 - half_open, 1.35), spec.wall_rgb)
    _box(client, (0.1, 3.0, 1.35), (0.1, 3.0 + half_open, 1.35), spec.wall_rgb)
    lintel = 2.7 - DOOR_HEIGHT - gap
    _box(client, (0.1, half_open, lintel / 2), (0.1, 0.0, DOOR_HEIGHT + gap + lintel / 2),
         spec.wall_rgb)
    _box(client, (6.0, 6.0, 0.01), (0.0, 0.0, -0.01), (0.45, 0.45, 0.47))
    thick = 0.04
    _box(client, (thick / 2, DOOR_WIDTH / 2, DOOR_HEIGHT / 2),
         (spec.recess + thick / 2, 0.0, DOOR_HEIGHT / 2), spec.door_rgb)
    face = spec.recess
    pivot = np.array([face - LEVER_STANDOFF, -DOOR_WIDTH / 2 + HANDLE_FROM_EDGE, HANDLE_HEIGHT])
    _box(client, (LEVER_STANDOFF / 2, 0.016, 0.016), (face - LEVER_STANDOFF / 2, pivot[1], HANDLE_HEIGHT),
         spec.handle_rgb)
    half = LEVER_SECTION / 2
    lever_centre = pivot + np.array([0.0, LEVER_LENGTH / 2, 0.0])
    _box(client, (half, LEVER_LENGTH / 2 + half, half), tuple(lever_centre), spec.handle_rgb)
    reach = LEVER_LENGTH / 2 + half
    offsets = np.array([[dx, dy, dz] for dx in (-half, half) for dy in (-reach, reach)
                        for dz in (-half, half)])
    grasp = pivot + np.array([0.0, GRASP_FRACTION * LEVER_LENGTH, 0.0])
    return grasp, lever_centre + offsets


def _camera(spec: SceneSpec) -> tuple[np.ndarray, np.ndarray]:
    """Camera position and optical rotation (columns: optical x, y, z in world)."""
    look_at = np.array([0.0, 0.0, 1.05])
    position = np.array([-spec.distance * math.cos(spec.yaw), spec.distance * math.sin(spec.yaw),
                         spec.camera_height])
    forward = look_at - position
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    down = np.cross(forward, right)
    return position, np.stack([right, down, forward], axis=1)


def _intrinsics(spec: SceneSpec) -> CameraIntrinsics:
    fx = spec.width / 2 / math.tan(math.radians(40.0))
    return CameraIntrinsics(spec.width, spec.height, fx, fx, (spec.width - 1) / 2, (spec.height - 1) / 2)


def render(spec: SceneSpec) -> RenderedScene:
    """Render rgb (uint8 H×W×3), depth (float32 m, NaN invalid) and the ground truth.

    PyBullet's TinyRenderer puts the optical axis at (W/2, H/2 − 1) (see the sim core's
    camera module); the intrinsics here use ((W − 1)/2, (H − 1)/2), half a pixel off, on
    purpose: the detector must tolerate small calibration errors.
    """
    client = pybullet.connect(pybullet.DIRECT)
    try:
        grasp, lever_corners = _build(client, spec)
        position, rotation = _camera(spec)
        intrinsics = _intrinsics(spec)
        near, far = 0.1, 20.0
        view = pybullet.computeViewMatrix(position.tolist(), (position + rotation[:, 2]).tolist(),
                                          (-rotation[:, 1]).tolist())
        fov = math.degrees(2 * math.atan(spec.height / 2 / intrinsics.fy))
        projection = pybullet.computeProjectionMatrixFOV(fov, spec.width / spec.height, near, far)
        _, _, rgba, zbuf, _ = pybullet.getCameraImage(
            spec.width, spec.height, view, projection, lightDirection=[-1.0, 0.5, 2.0],
            shadow=0, renderer=pybullet.ER_TINY_RENDERER, physicsClientId=client)
    finally:
        pybullet.disconnect(client)
    rgb = np.asarray(rgba, dtype=np.uint8).reshape(spec.height, spec.width, 4)[:, :, :3].copy()
    zbuf = np.asarray(zbuf, dtype=np.float64).reshape(spec.height, spec.width)
    depth = far * near / (far - (far - near) * zbuf)
    depth[depth > 0.99 * far] = np.nan
    if spec.noise_k > 0:
        rng = np.random.default_rng(spec.seed)
        depth = depth + rng.normal(size=depth.shape) * spec.noise_k * depth ** 2
    to_optical = lambda p: (np.asarray(p) - position) @ rotation  # noqa: E731
    handle = to_optical(grasp)
    normal = np.array([-1.0, 0.0, 0.0]) @ rotation
    corners_px = intrinsics.project(to_optical(lever_corners))
    return RenderedScene(rgb, depth.astype(np.float32), intrinsics, handle, normal,
                         _hull(corners_px))


def _hull(points: np.ndarray) -> np.ndarray:
    import cv2
    return cv2.convexHull(points.astype(np.float32)).reshape(-1, 2).astype(float)
