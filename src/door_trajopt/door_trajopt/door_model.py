"""The door as part of the kinematic chain (seed 000 Sec. III: hinge and handle are DOFs).

While the hand holds the handle, robot and door form a closed chain: at every grasped
waypoint the hand's pose must equal :meth:`DoorModel.grasp_pose` of the door's hinge
angle θ and handle angle φ. Conventions (shared with the detector's estimate and the
simulation): poses in the robot base frame; the grasp frame has x = door normal towards
the robot and z up at θ = φ = 0; θ > 0 opens the door (away from the robot for a push
door, towards it for a pull door); φ > 0 presses the lever down. The lever points from its
axis towards the hinge side, and the grasp point lies ``lever_radius`` from the axis.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from door_contract.payloads import DoorEstimate

UP = np.array([0.0, 0.0, 1.0])


def rotation_about(unit_axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues: R = I + sin a [k]ₓ + (1 − cos a) [k]ₓ² for a unit axis k."""
    k = unit_axis
    cross = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(angle) * cross + (1.0 - np.cos(angle)) * (cross @ cross)


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
        return offset / np.linalg.norm(offset)

    @cached_property
    def hinge_sign(self) -> float:
        """s such that R_z(s·θ) swings the free edge away (push) or towards (pull) the robot."""
        swing = np.cross(UP, self.along)
        towards_robot = float(np.sign(swing @ self.normal))
        return -towards_robot if self.push else towards_robot

    def leaf_rotation(self, hinge_angle: float) -> np.ndarray:
        return rotation_about(UP, self.hinge_sign * hinge_angle)

    def grasp_pose(self, hinge_angle: float, handle_angle: float) -> np.ndarray:
        """4×4 grasp frame at (θ, φ): the lever turns about the normal, the leaf about the hinge."""
        # the lever axis is lever_radius beyond the grasp point, away from the hinge
        axis_point = self.grasp_point + self.lever_radius * self.along
        # pressing the lever down (φ > 0) swings the grasp point down about the normal axis
        turn = rotation_about(self.normal, self.lever_sign * handle_angle)
        grasp_at_phi = axis_point + turn @ (self.grasp_point - axis_point)
        leaf = self.leaf_rotation(hinge_angle)
        pose = np.eye(4)
        pose[:3, :3] = leaf @ turn @ self.rest_frame
        pose[:3, 3] = self.hinge_point + leaf @ (grasp_at_phi - self.hinge_point)
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

    def pose_derivatives(self, hinge_angle: float, handle_angle: float, step: float = 1e-6) -> np.ndarray:
        """(6, 2): ∂(position, rotation vector)/∂(θ, φ) by central differences."""
        columns = []
        for d_theta, d_phi in ((step, 0.0), (0.0, step)):
            plus = self.grasp_pose(hinge_angle + d_theta, handle_angle + d_phi)
            minus = self.grasp_pose(hinge_angle - d_theta, handle_angle - d_phi)
            linear = (plus[:3, 3] - minus[:3, 3]) / (2 * step)
            angular = rotation_vector(plus[:3, :3] @ minus[:3, :3].T) / (2 * step)
            columns.append(np.concatenate([linear, angular]))
        return np.column_stack(columns)


def rotation_vector(rotation: np.ndarray) -> np.ndarray:
    """log(R) as an axis-angle vector (|ω| = angle ≤ π)."""
    cos_angle = np.clip((np.trace(rotation) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arccos(cos_angle)
    skew = np.array([rotation[2, 1] - rotation[1, 2], rotation[0, 2] - rotation[2, 0],
                     rotation[1, 0] - rotation[0, 1]])
    if angle < 1e-9:
        return skew / 2.0
    if np.pi - angle < 1e-6:
        axis = np.sqrt(np.maximum((np.diag(rotation) + 1.0) / 2.0, 0.0))
        axis *= np.where(skew >= 0, 1.0, -1.0) if np.any(skew) else 1.0
        return angle * axis / np.linalg.norm(axis)
    return angle / (2.0 * np.sin(angle)) * skew


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



