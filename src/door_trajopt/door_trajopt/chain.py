"""One arm chain (torso + arm joints of a side) of the robot, with the rest of the body fixed.

The optimiser's robot DOFs are the chain's joints; every other joint stays at the
configuration the chain was built from (the measured posture). Wraps
:class:`door_robot.kinematics.RobotKinematics` so callers speak in chain vectors.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from door_contract.vocabulary import Side
from door_robot.kinematics import RobotKinematics

__all__ = ["ArmChain"]


@dataclass
class ArmChain:
    kinematics: RobotKinematics
    side: Side
    body_q: np.ndarray  # full configuration of the joints outside the chain
    joints: tuple[str, ...] = ()  # a subset of the side's chain; empty: the profile's whole chain
    indices: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        self.indices = self.kinematics.joint_indices(self.joint_names)

    @property
    def joint_names(self) -> tuple[str, ...]:
        return self.joints or self.kinematics.profile.arm(self.side).joints

    @property
    def size(self) -> int:
        return int(self.indices.size)

    @cached_property
    def tcp_frame(self) -> str:
        """The side's TCP frame (looked up once: the constraints ask for it at every waypoint)."""
        return self.kinematics.profile.tcp_frame(self.side)

    @property
    def elbow_frame(self) -> str:
        """Body frame of the elbow joint: the 4th-from-last joint of a 7-DOF arm chain."""
        return self.body_frame(self.size - 4)

    @property
    def forearm_frames(self) -> tuple[str, ...]:
        """Body frames of the elbow and forearm joints (4th- and 3rd-from-last); the wrist
        beyond them is placed by the hand's pose."""
        return tuple(self.body_frame(i) for i in range(self.size - 4, self.size - 2))

    def body_frame(self, chain_index: int) -> str:
        model = self.kinematics.model
        joint_id = model.getJointId(self.joint_names[chain_index])
        frame: str = next(f.name for f in model.frames if f.parentJoint == joint_id and f.type.name == "BODY")
        return frame

    @cached_property
    def lower(self) -> np.ndarray:
        """The chain joints' lower limits (looked up once, read-only)."""
        limits: np.ndarray = self.kinematics.lower_limits[self.indices]
        limits.setflags(write=False)
        return limits

    @cached_property
    def upper(self) -> np.ndarray:
        """The chain joints' upper limits (looked up once, read-only)."""
        limits: np.ndarray = self.kinematics.upper_limits[self.indices]
        limits.setflags(write=False)
        return limits

    @property
    def velocity_limits(self) -> np.ndarray:
        limits: np.ndarray = self.kinematics.velocity_limits[self.indices]
        return limits

    def full(self, chain_q: np.ndarray) -> np.ndarray:
        q = self.body_q.copy()
        q[self.indices] = chain_q
        return q

    def chain_of(self, full_q: np.ndarray) -> np.ndarray:
        chain_q: np.ndarray = np.asarray(full_q)[self.indices].copy()
        return chain_q

    def tcp_pose(self, chain_q: np.ndarray) -> np.ndarray:
        return self.kinematics.frame_pose(self.full(chain_q), self.tcp_frame)

    def tcp_jacobian(self, chain_q: np.ndarray) -> np.ndarray:
        """6×k: rows (linear, angular) world-aligned, columns the chain joints."""
        return self.kinematics.frame_jacobian(self.full(chain_q), self.tcp_frame)[:, self.indices]

    def tcp_pose_and_jacobian(self, chain_q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`tcp_pose` and :meth:`tcp_jacobian` together (one kinematics pass)."""
        pose, jacobian = self.kinematics.frame_pose_and_jacobian(self.full(chain_q), self.tcp_frame)
        return pose, jacobian[:, self.indices]

    def point(self, chain_q: np.ndarray, frame: str) -> np.ndarray:
        """Origin of ``frame`` (base frame): forward kinematics only, no Jacobian pass."""
        point: np.ndarray = self.kinematics.frame_pose(self.full(chain_q), frame)[:3, 3]
        return point

    def com(self, chain_q: np.ndarray) -> np.ndarray:
        """Whole-body centre of mass (base frame), without its Jacobian."""
        return self.kinematics.center_of_mass(self.full(chain_q))

    def point_and_jacobian(self, chain_q: np.ndarray, frame: str) -> tuple[np.ndarray, np.ndarray]:
        pose, jacobian = self.kinematics.frame_pose_and_jacobian(self.full(chain_q), frame)
        return pose[:3, 3], jacobian[:3, self.indices]

    def com_and_jacobian(self, chain_q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        q = self.full(chain_q)
        return self.kinematics.center_of_mass(q), self.kinematics.com_jacobian(q)[:, self.indices]
