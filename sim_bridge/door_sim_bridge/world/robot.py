"""The humanoid in PyBullet: position-controlled joints on a floating or a fixed base.

* **Physical** (the default, :class:`~door_sim_bridge.world.config.RobotMode`): the robot is a
  free body standing on the floor, loaded from the profile's URDF with box soles
  (:mod:`door_sim_bridge.world.robot_urdf`); the walking controller drives every joint and
  the robot can fall.
* **Kinematic** (fast unit tests only): the base is fixed to the world and teleported with
  ``resetBasePositionAndOrientation``; it passes through walls and cannot fall.

Every movable joint is driven by PyBullet's position motor (a velocity constraint solved
with the contacts, limited to ``joint_force_scale`` × the URDF effort), so an arm blocked by
the door stalls instead of passing through it. Gravity acts on the links.

PyBullet reports a base's pose at its centre of mass; the URDF (and Pinocchio) frame of the
base differs by the base's inertial offset, which this class removes, so :meth:`base_pose` is
the URDF base frame, as in :mod:`door_robot.kinematics`.
"""

from __future__ import annotations

import math
import tempfile
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import pybullet

from door_contract.vocabulary import Side
from door_robot.profile import RobotProfile
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.world.client import PhysicsClient
from door_sim_bridge.world.config import RobotVisuals
from door_sim_bridge.world.robot_urdf import box_sole_urdf, profile_urdf
from door_sim_bridge.world.transforms import invert, pose_matrix, position_quaternion, translation

__all__ = ["JointLimit", "JointStates", "SimRobot"]

MOVABLE_JOINT_TYPES = (pybullet.JOINT_REVOLUTE, pybullet.JOINT_PRISMATIC)
MIN_MOTOR_FORCE = 5.0  # N·m, so weak URDF efforts (wrist: 3 N·m) still hold the hand's weight


@dataclass(frozen=True)
class JointLimit:
    """URDF limits of one joint: position (rad), velocity (rad/s), effort (N·m)."""

    lower: float
    upper: float
    velocity: float
    effort: float

    def contains(self, value: float, tolerance: float = 1e-6) -> bool:
        return self.lower - tolerance <= value <= self.upper + tolerance


def _with_efforts(limits: dict[str, JointLimit], profile: RobotProfile) -> dict[str, JointLimit]:
    """The URDF's limits with the profile's ``joint_efforts`` in place of its efforts; a joint
    the model lacks is refused."""
    unknown = sorted(set(profile.joint_efforts) - set(limits))
    if unknown:
        raise SimulationError(f"profile {profile.name!r}: joint_efforts names joint(s) the URDF lacks: {unknown}")
    return {name: replace(limit, effort=profile.joint_efforts.get(name, limit.effort)) for name, limit in limits.items()}


@dataclass(frozen=True, eq=False)
class JointStates:
    """Positions (rad), velocities (rad/s) and motor efforts (N·m) of the named joints."""

    names: tuple[str, ...]
    positions: np.ndarray
    velocities: np.ndarray
    efforts: np.ndarray


class SimRobot:
    """One robot profile loaded into a PyBullet client (floating or fixed base)."""

    def __init__(self, client: PhysicsClient, profile: RobotProfile, force_scale: float,
                 floating: bool = True) -> None:
        self._client = client
        self.profile = profile
        self.floating = floating
        if floating:
            self.urdf_text = box_sole_urdf(profile)
        else:  # the profile's file as it is, unless the profile adds frames to it
            self.urdf_text = profile_urdf(profile) if profile.extra_frames else profile.urdf_path.read_text()
        self.body = self._load(floating)
        infos = [client.getJointInfo(self.body, j) for j in range(client.getNumJoints(self.body))]
        self._parents = {j: info[16] for j, info in enumerate(infos)}
        self._links = {info[12].decode(): j for j, info in enumerate(infos)}
        self._links[client.getBodyInfo(self.body)[0].decode()] = -1
        movable = [(info[1].decode(), j) for j, info in enumerate(infos) if info[2] in MOVABLE_JOINT_TYPES]
        self.joint_names: tuple[str, ...] = tuple(name for name, _ in movable)
        self._indices = np.array([j for _, j in movable], dtype=int)
        self._index_of = {name: k for k, name in enumerate(self.joint_names)}
        self.limits = _with_efforts({info[1].decode(): JointLimit(info[8], info[9], info[11], info[10])
                                     for info in infos if info[2] in MOVABLE_JOINT_TYPES}, profile)
        self._forces = np.array([max(force_scale * self.limits[n].effort, MIN_MOTOR_FORCE)
                                 for n in self.joint_names])
        dynamics = client.getDynamicsInfo(self.body, -1)
        self._base_inertial = pose_matrix(dynamics[3], dynamics[4])
        # kg, the base's then every link's by index: read once (the CoM is measured every step)
        self.link_masses = np.array([client.getDynamicsInfo(self.body, index)[0]
                                     for index in range(-1, client.getNumJoints(self.body))])
        self._targets = np.zeros(len(self.joint_names))
        self._wrists: dict[Side, tuple[int, float]] = {}
        if floating:  # PyBullet's default velocity motors would hold every joint still
            client.setJointMotorControlArray(self.body, self._indices.tolist(), pybullet.VELOCITY_CONTROL,
                                             forces=[0.0] * len(self._indices))
            self.enable_wrist_sensors()

    def _load(self, floating: bool) -> int:
        flags = pybullet.URDF_USE_INERTIA_FROM_FILE
        if not floating and not self.profile.extra_frames:  # the URDF as it is
            body: int = self._client.loadURDF(str(self.profile.urdf_path), useFixedBase=True, flags=flags)
            return body
        with tempfile.TemporaryDirectory(prefix="door_robot_") as folder:
            path = Path(folder) / f"{self.profile.name}_{'box_soles' if floating else 'frames'}.urdf"
            path.write_text(self.urdf_text)
            body = self._client.loadURDF(str(path), useFixedBase=not floating, flags=flags)
            return body

    # ------------------------------------------------------------------ names
    def link_index(self, link: str) -> int:
        """PyBullet link index of a URDF link (-1 for the base)."""
        try:
            return self._links[link]
        except KeyError:
            raise SimulationError(f"{self.profile.name} has no link {link!r}") from None

    def joint_link_index(self, joint: str) -> int:
        """PyBullet index of a movable joint (= index of its child link)."""
        self._require_known([joint])
        return int(self._indices[self._index_of[joint]])

    def _require_known(self, names: Iterable[str]) -> None:
        unknown = [name for name in names if name not in self._index_of]
        if unknown:
            raise SimulationError(f"{self.profile.name} has no movable joint {unknown[0]!r}")

    def descendants(self, link_index: int) -> set[int]:
        """``link_index`` and every link below it in the kinematic tree."""
        found = {link_index}
        changed = True
        while changed:
            before = len(found)
            found |= {child for child, parent in self._parents.items() if parent in found}
            changed = len(found) != before
        return found

    def chain_to_root(self, link_index: int) -> list[int]:
        """Joint indices from ``link_index`` up to the base."""
        chain = []
        while link_index >= 0:
            chain.append(link_index)
            link_index = self._parents[link_index]
        return chain

    # ------------------------------------------------------------------ joints
    def reset_joints(self, positions: Mapping[str, float]) -> None:
        """Teleport joints (no dynamics) and hold them there with the motors."""
        self._require_known(positions)
        for name, value in positions.items():
            self._client.resetJointState(self.body, self.joint_link_index(name), float(value), 0.0)
        self.set_joint_targets(positions)

    def set_joint_targets(self, targets: Mapping[str, float]) -> None:
        """Position-motor targets by joint name, clipped to the URDF limits; others keep theirs."""
        self._require_known(targets)
        values = np.array([float(v) for v in targets.values()])
        if not np.all(np.isfinite(values)):
            raise SimulationError("joint targets contain NaN or infinity")
        for name, value in zip(targets, values):
            limit = self.limits[name]
            self._targets[self._index_of[name]] = min(max(value, limit.lower), limit.upper)
        self._client.setJointMotorControlArray(self.body, self._indices.tolist(),
                                               pybullet.POSITION_CONTROL,
                                               targetPositions=self._targets.tolist(),
                                               forces=self._forces.tolist())

    def joint_targets(self) -> dict[str, float]:
        return dict(zip(self.joint_names, self._targets.tolist()))

    def motor_force(self, name: str) -> float:
        """The most torque (N·m, or N) the joint's position motor applies."""
        self._require_known((name,))
        return float(self._forces[self._index_of[name]])

    def wrist_joint(self, side: Side) -> str:
        """The movable joint nearest above the ``side`` hand's TCP parent frame."""
        names = {self.joint_link_index(n): n for n in self.joint_names}
        for index in self.chain_to_root(self.link_index(self.profile.arm(side).tcp_parent_frame)):
            if index in names:
                return names[index]
        raise SimulationError(f"{self.profile.name}: no joint above {self.profile.arm(side).tcp_parent_frame}")

    def arm_joints(self, side: Side) -> tuple[str, ...]:
        """The joints of the ``side`` arm chain that move only that hand (a torso in every arm
        chain, as TALOS's, is not the arm's)."""
        others = {name for other, arm in self.profile.arms.items() if other != side for name in arm.joints}
        return tuple(name for name in self.profile.arm(side).joints if name not in others)

    def enable_wrist_sensors(self) -> None:
        """Six-axis force/torque sensing at both wrists (PyBullet's joint reaction forces)."""
        for side in self.profile.arms:
            index = self.joint_link_index(self.wrist_joint(side))
            self._client.enableJointForceTorqueSensor(self.body, index, True)
            below = self.descendants(index)
            mass = sum(self._client.getDynamicsInfo(self.body, link)[0] for link in below)
            self._wrists[side] = (index, mass)

    def wrist_force(self, side: Side, gravity: float) -> np.ndarray:
        """External force (N, world axes) on the ``side`` hand from its wrist sensor.

        The sensor reports the force the arm exerts on the hand (the wrist's child link), in
        that link's centre-of-mass frame. Quasi-statically it balances the hand's weight and
        whatever holds the hand: F_ext = −R·f_sensor + m_hand·g·ẑ (the gravity compensation
        real wrist sensors get from the hand's known mass).
        """
        index, mass = self._wrists[side]
        reaction = np.array(self._client.getJointState(self.body, index)[2][:3])
        force: np.ndarray = -(self.link_com_pose(index)[:3, :3] @ reaction) + np.array([0.0, 0.0, mass * gravity])
        return force

    def go_limp(self, damping_fraction: float = 0.05) -> None:
        """Motors off but for a little damping (a fallen robot's joints give way)."""
        self._client.setJointMotorControlArray(self.body, self._indices.tolist(), pybullet.VELOCITY_CONTROL,
                                               targetVelocities=[0.0] * len(self._indices),
                                               forces=(damping_fraction * self._forces).tolist())

    def joint_states(self) -> JointStates:
        states = self._client.getJointStates(self.body, self._indices.tolist())
        return JointStates(self.joint_names, np.array([s[0] for s in states]),
                           np.array([s[1] for s in states]), np.array([s[3] for s in states]))

    def joint_positions(self) -> dict[str, float]:
        return dict(zip(self.joint_names, self.joint_states().positions.tolist()))

    # ------------------------------------------------------------------ base and links
    def base_pose(self) -> np.ndarray:
        """4×4 URDF base frame in the world."""
        position, orientation = self._client.getBasePositionAndOrientation(self.body)
        pose: np.ndarray = pose_matrix(position, orientation) @ invert(self._base_inertial)
        return pose

    def set_base_pose(self, pose: np.ndarray) -> None:
        """Teleport the base (URDF frame) to ``pose``; joint angles are unchanged (placing the
        robot before a run; the world refuses it for the physical robot afterwards)."""
        position, orientation = position_quaternion(np.asarray(pose) @ self._base_inertial)
        self._client.resetBasePositionAndOrientation(self.body, position, orientation)

    def link_pose(self, link: str) -> np.ndarray:
        """4×4 URDF frame of ``link`` in the world."""
        index = self.link_index(link)
        if index < 0:
            return self.base_pose()
        state = self._client.getLinkState(self.body, index, computeForwardKinematics=True)
        return pose_matrix(state[4], state[5])

    def link_com_pose(self, index: int) -> np.ndarray:
        """4×4 centre-of-mass frame of a link (the frame PyBullet constraints are relative to)."""
        if index < 0:
            position, orientation = self._client.getBasePositionAndOrientation(self.body)
            return pose_matrix(position, orientation)
        state = self._client.getLinkState(self.body, index, computeForwardKinematics=True)
        return pose_matrix(state[0], state[1])

    def joint_axis_world(self, index: int) -> np.ndarray:
        """Unit axis of joint ``index`` in the world.

        PyBullet reports the axis in the child link's centre-of-mass frame, not its URDF frame.
        """
        axis = np.array(self._client.getJointInfo(self.body, index)[13], dtype=float)
        axis_in_world: np.ndarray = self.link_com_pose(index)[:3, :3] @ axis
        return axis_in_world

    def tcp_pose(self, side: Side) -> np.ndarray:
        """4×4 TCP in the world: the profile's TCP parent frame shifted by its grasp offset."""
        arm = self.profile.arm(side)
        pose: np.ndarray = self.link_pose(arm.tcp_parent_frame) @ translation(arm.grasp_offset)
        return pose

    def hand_links(self, side: Side) -> set[int]:
        """The TCP parent link and everything below it (gripper, fingers)."""
        return self.descendants(self.link_index(self.profile.arm(side).tcp_parent_frame))

    # ------------------------------------------------------------------ visuals
    def arm_links(self) -> set[int]:
        """Links moved by the arm joints the two arms do not share (upper arms to fingertips)."""
        chains = [set(arm.joints) for arm in self.profile.arms.values()]
        shared = set.intersection(*chains) if chains else set()
        links: set[int] = set()
        for joint in set.union(*chains) - shared:
            links |= self.descendants(self.joint_link_index(joint))
        return links

    def hide_links(self, visuals: RobotVisuals) -> None:
        """Make links invisible to the renderer (alpha 0 is skipped by TinyRenderer: faster)."""
        if visuals is RobotVisuals.ALL:
            return
        keep = self.arm_links() if visuals is RobotVisuals.ARMS else set()
        for index in [-1, *self._parents]:
            if index not in keep:
                self._client.changeVisualShape(self.body, index, rgbaColor=[0.5, 0.5, 0.5, 0.0])

    def pitch_joint(self, camera_link: str, optical_x: np.ndarray) -> tuple[str, float] | None:
        """The neck joint nearest the camera whose axis is the camera's optical x axis, and its sign.

        Rotating about the optical +x by a positive angle tilts the view up, so a joint whose
        axis is along +x_optical must turn by ``-pitch`` to look down by ``pitch``: the sign
        returned is the joint angle per radian of downward tilt. Joints of the arm chains
        (torso joints) are not the neck's, as in ``door_detection.neck``: a robot without a
        neck (G1, its camera fixed to the torso) has no pitch joint and looks where its
        camera is mounted.
        """
        arm_joints = {joint for arm in self.profile.arms.values() for joint in arm.joints}
        names = {self.joint_link_index(n): n for n in self.joint_names if n not in arm_joints}
        for index in self.chain_to_root(self.link_index(camera_link)):
            if index in names:
                alignment = float(self.joint_axis_world(index) @ optical_x)
                if abs(alignment) > math.cos(math.radians(15.0)):
                    return names[index], -math.copysign(1.0, alignment)
        return None
