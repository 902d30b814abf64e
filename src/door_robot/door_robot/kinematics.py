"""Forward kinematics, frame Jacobians and centre of mass through Pinocchio.

The model is the profile's URDF with a **fixed base** at ``profile.base_frame`` (quasi-static
manipulation: the feet do not move while the arm does, [Banerjee 2015] Sec. IV). Poses are 4×4
transforms in the base frame; pass ``base_pose`` (base in world/odom) to get world
quantities. Jacobians are ``LOCAL_WORLD_ALIGNED``: rows (v_x, v_y, v_z, ω_x, ω_y, ω_z) of the
frame origin expressed in the base axes, so that for a small joint step δq the frame moves
by J δq (used by Q3 and the Cartesian constraints of [Banerjee 2015] eq. 5).

An optimiser asks for several frames' poses, Jacobians and the centre of mass at one
waypoint in a row: the kinematics of the last configuration are kept (one forward pass,
one joint-Jacobian pass, one centre-of-mass pass per configuration), and frame ids are
looked up once per name, not on every call.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from door_contract.vocabulary import Side
from door_robot.errors import RobotModelError
from door_robot.profile import RobotProfile

__all__ = ["RobotKinematics", "to_world"]


@dataclass
class _EvaluatedConfiguration:
    """Which Pinocchio passes ``data`` holds for configuration ``q`` (None: none yet)."""

    key: bytes = b""  # q's bytes (comparing bytes is several times faster than np.array_equal)
    joint_jacobians: bool = False
    com: np.ndarray | None = None
    com_jacobian: np.ndarray | None = None
    frame_ids: dict[str, int] = field(default_factory=dict)


class RobotKinematics:
    """Kinematics of one robot profile; owns its Pinocchio model and data (not thread-safe)."""

    def __init__(self, profile: RobotProfile) -> None:
        self.profile = profile
        self.model = pin.buildModelFromUrdf(str(profile.urdf_path))
        if self.model.nq != self.model.nv:
            raise RobotModelError(f"{profile.name}: continuous joints are not supported "
                                  f"(nq={self.model.nq}, nv={self.model.nv})")
        for name, extra in profile.extra_frames.items():
            self._add_frame(name, extra.parent, extra.xyz, "extra frame")
        for side, arm in profile.arms.items():
            self._add_frame(profile.tcp_frame(side), arm.tcp_parent_frame, arm.grasp_offset, "TCP")
        self.data = self.model.createData()
        self._evaluated = _EvaluatedConfiguration()
        self.joint_names: tuple[str, ...] = tuple(self.model.names[1:])
        self._index = {name: self.model.joints[i].idx_q for i, name in enumerate(self.model.names) if i}
        self.lower_limits = np.array(self.model.lowerPositionLimit)
        self.upper_limits = np.array(self.model.upperPositionLimit)
        self.velocity_limits = np.array(self.model.velocityLimit)
        self.nominal_q = self.configuration(profile.nominal_posture)
        self.walking_q = self.configuration(profile.walking_posture, base=self.nominal_q)
        self._check_profile_names()

    def _add_frame(self, name: str, parent: str, offset: Sequence[float], what: str) -> None:
        if not self.model.existFrame(parent):
            raise RobotModelError(f"{self.profile.name}: unknown {what} parent frame {parent!r}")
        parent_frame = self.model.frames[self.model.getFrameId(parent)]
        placement = parent_frame.placement * pin.SE3(np.eye(3), np.asarray(offset, dtype=float))
        self.model.addFrame(pin.Frame(name, parent_frame.parentJoint, self.model.getFrameId(parent),
                                      placement, pin.FrameType.OP_FRAME))

    def _check_profile_names(self) -> None:
        for arm in self.profile.arms.values():
            self.joint_indices(arm.joints)
        self.configuration(self.profile.look_posture, base=self.walking_q)  # names a joint the URDF has
        for frame in (self.profile.head_camera_frame, *self.profile.feet.values()):
            self.frame_id(frame)

    # ---------------------------------------------------------------- names and indices
    def joint_indices(self, joints: Sequence[str]) -> np.ndarray:
        """Indices in q of ``joints``; :class:`RobotModelError` names an unknown joint."""
        try:
            return np.array([self._index[name] for name in joints], dtype=int)
        except KeyError as error:
            raise RobotModelError(f"{self.profile.name} has no joint {error.args[0]!r}") from None

    def frame_id(self, frame: str) -> int:
        known = self._evaluated.frame_ids.get(frame)
        if known is not None:
            return known
        if not self.model.existFrame(frame):
            raise RobotModelError(f"{self.profile.name} has no frame {frame!r}")
        self._evaluated.frame_ids[frame] = self.model.getFrameId(frame)
        return self._evaluated.frame_ids[frame]

    def arm_indices(self, side: Side) -> np.ndarray:
        return self.joint_indices(self.profile.arm(side).joints)

    def configuration(self, positions: Mapping[str, float], base: np.ndarray | None = None) -> np.ndarray:
        """q with ``positions`` set by name over ``base`` (default: neutral), NaN rejected."""
        q = pin.neutral(self.model) if base is None else np.array(base, dtype=float)
        indices = self.joint_indices(list(positions))
        values = np.fromiter(positions.values(), float, len(positions))
        if not np.all(np.isfinite(values)):
            raise RobotModelError("joint positions contain NaN or infinity")
        q[indices] = values
        return q

    def within_limits(self, q: np.ndarray, tolerance: float = 1e-9) -> bool:
        return bool(np.all(q >= self.lower_limits - tolerance) and np.all(q <= self.upper_limits + tolerance))

    # ---------------------------------------------------------------- single configuration
    def _adopt(self, q: np.ndarray) -> bool:
        """Make the cache ``q``'s; True when ``q`` is new: the passes of the last q are forgotten
        and none is done yet (the caller does the one it needs)."""
        evaluated = self._evaluated
        key = np.asarray(q, dtype=float).tobytes()
        if key == evaluated.key:
            return False
        evaluated.key = key
        evaluated.joint_jacobians, evaluated.com, evaluated.com_jacobian = False, None, None
        return True

    def _at(self, q: np.ndarray) -> _EvaluatedConfiguration:
        """The cache for ``q``: forward kinematics done, the passes of another q forgotten."""
        if self._adopt(q):
            pin.forwardKinematics(self.model, self.data, q)
        return self._evaluated

    def frame_pose(self, q: np.ndarray, frame: str) -> np.ndarray:
        """4×4 pose of ``frame`` in the base frame."""
        frame_id = self.frame_id(frame)
        self._at(q)
        pose: np.ndarray = pin.updateFramePlacement(self.model, self.data, frame_id).homogeneous.copy()
        return pose

    def _with_joint_jacobians(self, q: np.ndarray) -> None:
        """The joint Jacobians of ``q`` computed. Their pass places the joints as it goes, so a
        new ``q`` needs no forward pass before it (``data.oMi`` then serves :meth:`frame_pose`)."""
        self._adopt(q)
        evaluated = self._evaluated
        if not evaluated.joint_jacobians:
            pin.computeJointJacobians(self.model, self.data, q)
            evaluated.joint_jacobians = True

    def frame_jacobian(self, q: np.ndarray, frame: str) -> np.ndarray:
        """6×nq Jacobian (linear rows first) of ``frame``, LOCAL_WORLD_ALIGNED."""
        frame_id = self.frame_id(frame)
        self._with_joint_jacobians(q)
        pin.updateFramePlacement(self.model, self.data, frame_id)
        jacobian: np.ndarray = pin.getFrameJacobian(self.model, self.data, frame_id,
                                                    pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        return jacobian

    def frame_pose_and_jacobian(self, q: np.ndarray, frame: str) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`frame_pose` and :meth:`frame_jacobian` of ``frame`` from one joint-Jacobian pass."""
        frame_id = self.frame_id(frame)
        self._with_joint_jacobians(q)
        pose: np.ndarray = pin.updateFramePlacement(self.model, self.data, frame_id).homogeneous.copy()
        jacobian: np.ndarray = pin.getFrameJacobian(self.model, self.data, frame_id,
                                                    pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        return pose, jacobian

    def center_of_mass(self, q: np.ndarray) -> np.ndarray:
        """Whole-body centre of mass (m, base frame): c = Σ mᵢ cᵢ / Σ mᵢ."""
        evaluated = self._at(q)
        if evaluated.com is None:
            evaluated.com = pin.centerOfMass(self.model, self.data, q).copy()
        return evaluated.com.copy()

    def com_jacobian(self, q: np.ndarray) -> np.ndarray:
        """3×nq Jacobian of the centre of mass, ∂c/∂q."""
        evaluated = self._at(q)
        if evaluated.com_jacobian is None:
            evaluated.com_jacobian = pin.jacobianCenterOfMass(self.model, self.data, q).copy()
            evaluated.com = self.data.com[0].copy()
        return evaluated.com_jacobian.copy()

    # ---------------------------------------------------------------- batched over waypoints
    def frame_poses(self, trajectory: np.ndarray, frame: str) -> np.ndarray:
        """(T, 4, 4) poses of ``frame`` along a (T, nq) trajectory."""
        return np.stack([self.frame_pose(q, frame) for q in np.atleast_2d(trajectory)])

    def frame_jacobians(self, trajectory: np.ndarray, frame: str) -> np.ndarray:
        """(T, 6, nq) Jacobians of ``frame`` along a trajectory."""
        return np.stack([self.frame_jacobian(q, frame) for q in np.atleast_2d(trajectory)])

    def centers_of_mass(self, trajectory: np.ndarray) -> np.ndarray:
        """(T, 3) centres of mass along a trajectory."""
        return np.stack([self.center_of_mass(q) for q in np.atleast_2d(trajectory)])

    def com_jacobians(self, trajectory: np.ndarray) -> np.ndarray:
        """(T, 3, nq) centre-of-mass Jacobians along a trajectory."""
        return np.stack([self.com_jacobian(q) for q in np.atleast_2d(trajectory)])


def to_world(base_pose: np.ndarray, pose_in_base: np.ndarray) -> np.ndarray:
    """World pose of a base-frame pose (or (T,4,4) stack) given the base pose in the world."""
    pose: np.ndarray = np.asarray(base_pose) @ pose_in_base
    return pose
