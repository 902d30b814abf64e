"""The door as part of the kinematic chain ([Zucker 2013] Sec. III: hinge and handle are DOFs).

While the hand holds the handle, robot and door form a closed chain: at every grasped
waypoint the hand's pose must equal :meth:`DoorModel.grasp_pose` of the door's hinge
angle θ and handle angle φ. Conventions (shared with the detector's estimate and the
simulation): poses in the robot base frame; the grasp frame has x = door normal towards
the robot and z up at θ = φ = 0; θ > 0 opens the door (away from the robot for a push
door, towards it for a pull door); φ > 0 presses the lever down. The lever points from its
axis towards the hinge side, and the grasp point lies ``lever_radius`` from the axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import pinocchio as pin

from door_contract.payloads import DoorEstimate

__all__ = ["UP", "DoorModel", "cross_matrix", "door_model_from_estimate", "rotation_about", "rotation_about_up",
           "rotation_vector"]

UP = np.array([0.0, 0.0, 1.0])


def cross_matrix(vector: np.ndarray) -> np.ndarray:
    """[k]ₓ, the matrix of k × (·)."""
    return np.array([[0.0, -vector[2], vector[1]], [vector[2], 0.0, -vector[0]], [-vector[1], vector[0], 0.0]])


def rotation_about(unit_axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues: R = I + sin a [k]ₓ + (1 − cos a) [k]ₓ² for a unit axis k."""
    cross = cross_matrix(unit_axis)
    rotation: np.ndarray = np.eye(3) + math.sin(angle) * cross + (1.0 - math.cos(angle)) * (cross @ cross)
    return rotation


def rotation_about_up(angle: float) -> np.ndarray:
    """R_z(a), the hinge's rotation (the hinge axis is vertical)."""
    cos, sin = math.cos(angle), math.sin(angle)
    return np.array([[cos, -sin, 0.0], [sin, cos, 0.0], [0.0, 0.0, 1.0]])


@dataclass(frozen=True)
class DoorModel:
    """Hinge axis, leaf direction and lever of one door, in the robot base frame (m, rad)."""

    grasp_point: np.ndarray  # (3,) grasp point at θ = φ = 0
    normal: np.ndarray  # (3,) unit, horizontal, towards the robot
    hinge_point: np.ndarray  # (3,) on the hinge axis at the grasp height
    push: bool  # the door opens away from the robot
    lever_radius: float = 0.066  # m, lever axis → grasp point

    @cached_property
    def along(self) -> np.ndarray:
        """Unit vector in the door plane from the hinge towards the grasp point (θ = 0)."""
        offset = self.grasp_point - self.hinge_point
        offset -= (offset @ UP) * UP + (offset @ self.normal) * self.normal
        direction: np.ndarray = offset / np.linalg.norm(offset)
        return direction

    @cached_property
    def hinge_sign(self) -> float:
        """s such that R_z(s·θ) swings the free edge away (push) or towards (pull) the robot."""
        swing = np.cross(UP, self.along)
        towards_robot = float(np.sign(swing @ self.normal))
        return -towards_robot if self.push else towards_robot

    def leaf_rotation(self, hinge_angle: float) -> np.ndarray:
        return rotation_about_up(self.hinge_sign * hinge_angle)

    @cached_property
    def _lever(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Lever axis point a (lever_radius beyond the grasp point, away from the hinge),
        the grasp point's arm g − a from it, and [l·n]ₓ of the lever's signed turn axis."""
        axis_point = self.grasp_point + self.lever_radius * self.along
        return axis_point, self.grasp_point - axis_point, cross_matrix(self.lever_sign * self.normal)

    def _turned_lever(self, handle_angle: float) -> tuple[np.ndarray, np.ndarray]:
        """R_n(l·φ) and the grasp point's arm R_n(l·φ)(g − a) at handle angle φ."""
        _, arm, cross = self._lever
        turn = np.eye(3) + math.sin(handle_angle) * cross + (1.0 - math.cos(handle_angle)) * (cross @ cross)
        return turn, turn @ arm

    def grasp_pose(self, hinge_angle: float, handle_angle: float) -> np.ndarray:
        """4×4 grasp frame at (θ, φ): the lever turns about the normal, the leaf about the hinge.

        R = R_z(sθ) R_n(lφ) R₀ and p = h + R_z(sθ)(a + R_n(lφ)(g − a) − h), with h the hinge
        point, a the lever axis point, g the grasp point at rest, R₀ :attr:`rest_frame`.
        """
        turn, arm = self._turned_lever(handle_angle)
        leaf = self.leaf_rotation(hinge_angle)
        pose = np.eye(4)
        pose[:3, :3] = leaf @ turn @ self.rest_frame
        pose[:3, 3] = self.hinge_point + leaf @ (self._lever[0] + arm - self.hinge_point)
        return pose

    @cached_property
    def lever_sign(self) -> float:
        """Orientation of the lever turn so that the grasp point moves down for φ > 0."""
        # grasp point sits at −along from the axis; rotating it about the normal by +a moves it
        # by a·(normal × −along); we want that to point down.
        return float(np.sign(np.cross(self.normal, -self.along) @ (-UP)))

    @cached_property
    def rest_frame(self) -> np.ndarray:
        """Grasp frame axes at θ = φ = 0: x = normal, z = up, y = z × x."""
        return np.column_stack([self.normal, np.cross(UP, self.normal), UP])

    def pose_derivatives(self, hinge_angle: float, handle_angle: float) -> np.ndarray:
        """(6, 2): ∂(position, rotation vector)/∂(θ, φ), world-aligned (as frame Jacobians).

        The hinge turns the grasp frame about the vertical axis through h at rate s:
        ∂p/∂θ = s z × (p − h), ∂ω/∂θ = s z. The lever turns it about the leaf's normal
        R_z(sθ) n at rate l: ∂p/∂φ = l (R_z n) × (R_z R_n (g − a)), ∂ω/∂φ = l R_z n.
        """
        axis_point, _, lever_cross = self._lever
        leaf = self.leaf_rotation(hinge_angle)
        _, turned_arm = self._turned_lever(handle_angle)
        from_hinge = leaf @ (axis_point + turned_arm - self.hinge_point)
        sign = self.hinge_sign
        derivatives = np.zeros((6, 2))
        derivatives[:3, 0] = (-sign * from_hinge[1], sign * from_hinge[0], 0.0)  # s z × (p − h)
        derivatives[5, 0] = sign
        derivatives[:3, 1] = leaf @ (lever_cross @ turned_arm)  # (R l n) × (R w) = R (l n × w)
        derivatives[3:, 1] = self.lever_sign * (leaf @ self.normal)
        return derivatives


def rotation_vector(rotation: np.ndarray) -> np.ndarray:
    """log(R) as an axis-angle vector (|ω| = angle ≤ π), by Pinocchio's log₃."""
    vector: np.ndarray = pin.log3(np.asarray(rotation, dtype=float))
    return vector


def door_model_from_estimate(estimate: DoorEstimate, world_to_base: np.ndarray, push: bool,
                             lever_radius: float = 0.066, leaf_thickness: float = 0.04) -> DoorModel:
    """The door model in the base frame from a detector estimate given in the world (odom).

    The detector sees the robot-side face; hinges sit on the face the door swings towards,
    so for a push door the hinge axis is ``leaf_thickness`` behind the visible hinge edge.
    """
    rotation, translation = world_to_base[:3, :3], world_to_base[:3, 3]
    grasp = rotation @ np.asarray(estimate.handle_position) + translation
    normal = rotation @ np.asarray(estimate.normal)
    normal = normal - (normal @ UP) * UP
    normal /= np.linalg.norm(normal)
    corners = np.asarray(estimate.corners) @ rotation.T + translation
    hinge_bottom, hinge_top = corners[0], corners[3]
    hinge_point = hinge_bottom + (hinge_top - hinge_bottom) * (
        (grasp[2] - hinge_bottom[2]) / max(hinge_top[2] - hinge_bottom[2], 1e-6))
    if push:
        hinge_point = hinge_point - leaf_thickness * normal
    return DoorModel(grasp, normal, hinge_point, push, lever_radius)



