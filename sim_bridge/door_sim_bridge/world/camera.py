"""Head RGB-D camera rendered with PyBullet's CPU TinyRenderer.

The camera sits at the profile's ``head_camera_frame``. That frame may be an optical frame
(z forward, x right, y down; TALOS's ``rgbd_rgb_optical_frame``) or a body frame (Atlas's
``head``: x forward, z up; DRC-HUBO's ``Body_NKP``, turned by pi: x backward; G1's
``d435_link``: x forward, pitched 0.83 rad down). The optical frame is fixed to it once
(:func:`optical_offset`): z along the profile's ``head_camera_axes.forward``, y along its
``down``, x = y × z. A profile without ``head_camera_axes`` gets a guess made in the zero
posture: z the frame axis (±x, ±y, ±z) closest to the base's forward axis, y the one closest
to straight down (the identity for a true optical frame). The guess is wrong for a frame
pitched more than 45°: for G1's it picks z, and the camera would look 42° up instead of 48°
down. OpenGL's camera looks along
its -z with y up, i.e. the optical frame turned by pi about x; the view matrix is built from
the optical pose accordingly.

Depth: PyBullet returns the normalised z-buffer value b in [0, 1]; the metric depth along the
optical axis (the eye-space z, which *is* the optical z, not the range along the ray) is
d = far * near / (far - (far - near) * b). Pixels where nothing was hit (b = 1) or beyond
``far`` are NaN, as stereo cameras report them. Colour and depth are registered (one
rendering), so one :class:`CameraIntrinsics` serves both.

Intrinsics of a symmetric perspective projection with vertical field of view fov:
fy = (H / 2) / tan(fov / 2), fx = fy (square pixels). TinyRenderer samples screen pixel
(i, j) at its integer corner, i = (ndc_x + 1) W / 2, j = (ndc_y + 1) H / 2, and PyBullet
stores row j as image row v = H - 1 - j; the optical axis (ndc 0, 0) therefore falls on
cx = W / 2, cy = H / 2 - 1 (verified by back-projecting rendered planes to < 0.1 mm).

Light: a directional light from ``CameraConfig.light_direction`` (odom), TinyRenderer's
ambient 0.6 and diffuse 0.35 coefficients; the default is the renderer's own z-up light.

Noise (optional): depth += N(0, (k z²)²) — stereo depth error grows with the square of the
range — and colour += N(0, sigma²) per channel, both from the world's seeded generator.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pybullet

from door_contract.converters.camera_info import CameraIntrinsics
from door_robot.profile import CameraAxes
from door_sim_bridge.world.client import PhysicsClient
from door_sim_bridge.world.config import CameraConfig
from door_sim_bridge.world.robot import SimRobot

__all__ = ["CameraFrame", "HeadCamera", "intrinsics_of", "metric_depth", "optical_offset"]

OPTICAL_TO_OPENGL = np.diag([1.0, -1.0, -1.0, 1.0])
"""The OpenGL camera frame in the optical frame (rotation by pi about x)."""


def _closest_axis(rotation: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """The signed frame axis (in frame coordinates) closest to a world ``direction``."""
    alignment = rotation.T @ direction
    axis = np.zeros(3)
    index = int(np.argmax(np.abs(alignment)))
    axis[index] = np.sign(alignment[index])
    return axis


def optical_offset(robot: SimRobot, camera_link: str, axes: CameraAxes | None = None) -> np.ndarray:
    """The optical frame in ``camera_link``'s frame: from ``axes`` (the profile's
    ``head_camera_axes``), else guessed (call in the zero posture, see the module doc)."""
    if axes is not None:
        forward, down = np.asarray(axes.forward, dtype=float), np.asarray(axes.down, dtype=float)
    else:
        base, camera = robot.base_pose(), robot.link_pose(camera_link)
        forward = _closest_axis(camera[:3, :3], base[:3, 0])
        down = _closest_axis(camera[:3, :3], -base[:3, 2])
    offset = np.eye(4)
    offset[:3, :3] = np.column_stack([np.cross(down, forward), down, forward])
    return offset


@dataclass(frozen=True, eq=False)
class CameraFrame:
    """One registered RGB-D frame.

    ``rgb`` is H×W×3 uint8, ``depth`` H×W float32 metres along the optical axis (NaN: no
    return), ``camera_pose`` the optical frame in odom, ``time`` the simulation time (s).
    """

    rgb: np.ndarray
    depth: np.ndarray
    intrinsics: CameraIntrinsics
    camera_pose: np.ndarray
    time: float


def intrinsics_of(config: CameraConfig) -> CameraIntrinsics:
    """Pinhole intrinsics of the rendered images (see the module docstring)."""
    focal = (config.height / 2.0) / math.tan(math.radians(config.vertical_fov_deg) / 2.0)
    return CameraIntrinsics(config.width, config.height, focal, focal, config.width / 2.0,
                            config.height / 2.0 - 1.0)


def metric_depth(zbuffer: np.ndarray, near: float, far: float) -> np.ndarray:
    """Depth along the optical axis (m) from OpenGL z-buffer values; NaN where nothing was hit."""
    buffer = np.asarray(zbuffer, dtype=np.float64)
    depth = far * near / (far - (far - near) * buffer)
    depth[(buffer >= 1.0 - 1e-7) | (depth >= far * (1.0 - 1e-4))] = np.nan
    return depth.astype(np.float32)


def _read_only(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


class HeadCamera:
    """Renders the robot's head camera in one PyBullet client."""

    def __init__(self, client: PhysicsClient, robot: SimRobot, config: CameraConfig,
                 noise: np.random.Generator, link_to_optical: np.ndarray) -> None:
        self._client = client
        self._robot = robot
        self._link_to_optical = link_to_optical
        self.config = config
        self._noise = noise
        self.intrinsics = intrinsics_of(config)
        self._projection = client.computeProjectionMatrixFOV(
            config.vertical_fov_deg, config.width / config.height, config.near, config.far)
        light = np.asarray(config.light_direction, dtype=float)
        self._light = (light / np.linalg.norm(light)).tolist()
        robot.link_index(robot.profile.head_camera_frame)  # fail early on a wrong frame name

    def pose(self) -> np.ndarray:
        """4×4 optical frame of the camera in odom."""
        pose: np.ndarray = self._robot.link_pose(self._robot.profile.head_camera_frame) @ self._link_to_optical
        return pose

    def render(self, time: float) -> CameraFrame:
        """Render colour and depth from the current camera pose (adds noise if configured)."""
        pose = self.pose()
        opengl = pose @ OPTICAL_TO_OPENGL
        view = np.linalg.inv(opengl).T.ravel().tolist()  # column-major, as OpenGL expects
        width, height = self.config.width, self.config.height
        _, _, rgba, zbuffer, _ = self._client.getCameraImage(
            width, height, view, self._projection, renderer=pybullet.ER_TINY_RENDERER,
            flags=pybullet.ER_NO_SEGMENTATION_MASK, shadow=0, lightDirection=self._light)
        rgb = np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)[:, :, :3]
        depth = metric_depth(np.reshape(zbuffer, (height, width)), self.config.near, self.config.far)
        return CameraFrame(_read_only(self._colour_noise(rgb)), _read_only(self._depth_noise(depth)),
                           self.intrinsics, _read_only(pose), time)

    def _depth_noise(self, depth: np.ndarray) -> np.ndarray:
        """depth + N(0, (k z²)²): the stereo error grows with the square of the range."""
        k = self.config.depth_noise_coefficient
        if k <= 0.0:
            return depth
        noisy = depth + self._noise.standard_normal(depth.shape) * k * depth * depth
        noisy[noisy <= self.config.near] = np.nan
        noisy_depth: np.ndarray = noisy.astype(np.float32)
        return noisy_depth

    def _colour_noise(self, rgb: np.ndarray) -> np.ndarray:
        sigma = self.config.colour_noise_sigma
        if sigma <= 0.0:
            return np.ascontiguousarray(rgb)
        noisy = rgb.astype(np.float32) + self._noise.normal(0.0, sigma, rgb.shape).astype(np.float32)
        return np.clip(np.rint(noisy), 0, 255).astype(np.uint8)
