"""The simulated world: TALOS (or another profile), the door in its wall, the head camera.

``DoorWorld`` owns one PyBullet client in DIRECT mode. Conventions (see
:mod:`door_sim_bridge.world.door` for the door's): world frame = ``odom``; the robot starts
on the x < 0 side at x = -stance.distance, y = stance.lateral_offset, yawed by stance.yaw from
facing +x, its soles on the floor (base at ``profile.base_height``), joints in the profile's
nominal posture with the head pitched down by ``camera.head_pitch``.

One :meth:`DoorWorld.step` is one physics step of 1/physics_rate s: the door's latch is
updated and its spring, damper and wind torques applied (PyBullet clears torques and external
forces after every step, so they are re-applied each time), test forces are applied, the
solver runs, then every grasp's constraint force is checked for a slip.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import Enum
from types import TracebackType

import numpy as np
import pybullet

from door_contract.converters.footsteps import Foot, FootPlacement
from door_robot.locations import cmeel_share_dir
from door_robot.profile import Side, load_profile
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.world.camera import CameraFrame, HeadCamera, optical_offset
from door_sim_bridge.world.client import PhysicsClient
from door_sim_bridge.world.config import StanceConfig, WorldConfig
from door_sim_bridge.world.door import DoorGroundTruth, DoorPart, DoorState, LatchEvent, SimDoor
from door_sim_bridge.world.grasp import GraspController, GraspResult
from door_sim_bridge.world.robot import JointLimit, JointStates, SimRobot
from door_contract.geometry import planar_pose, yaw_of
from door_sim_bridge.world.transforms import invert, is_rigid


class EventKind(str, Enum):
    GRASP_CLOSED = "grasp_closed"
    GRASP_REFUSED = "grasp_refused"
    GRASP_OPENED = "grasp_opened"
    GRASP_SLIPPED = "grasp_slipped"
    LATCH_RELEASED = "latch_released"
    LATCH_ENGAGED = "latch_engaged"


@dataclass(frozen=True)
class SimEvent:
    """Something that happened in the simulation, for diagnostics and the evaluator."""

    time: float
    kind: EventKind
    detail: str = ""
    side: Side | None = None


@dataclass(frozen=True, eq=False)
class _ExternalForce:
    """A force (N, world axes) at a point fixed on a door part, for a number of steps."""

    part: DoorPart
    force: np.ndarray
    local_point: np.ndarray  # in the part's link frame, so it moves with the part


class DoorWorld:
    """Robot + door + camera in a private PyBullet client; use as a context manager or close()."""

    def __init__(self, config: WorldConfig | None = None) -> None:
        self.config = config or WorldConfig()
        self.profile = load_profile(self.config.robot_profile)
        self._client = PhysicsClient()
        try:
            self._build()
        except BaseException:
            self._client.disconnect()
            raise
        self._steps = 0
        self._events: list[SimEvent] = []
        self._forces: list[tuple[_ExternalForce, int]] = []
        self._stance_offset = invert(self._feet_midpoint()) @ self.robot.base_pose()

    def _build(self) -> None:
        """Physics settings, door, robot (placed), camera and grasps; randomness from the seed."""
        wind_seed, noise_seed = np.random.SeedSequence(self.config.seed).spawn(2)
        self._configure_physics()
        phase = float(np.random.default_rng(wind_seed).uniform(0.0, 2.0 * math.pi))
        self.door = SimDoor(self._client, self.config.door, phase)
        self.robot = SimRobot(self._client, self.profile, self.config.joint_force_scale)
        camera_frame = self.profile.head_camera_frame
        self._optical = optical_offset(self.robot, camera_frame)  # in the zero posture
        optical_x = (self.robot.link_pose(camera_frame) @ self._optical)[:3, 0]
        self._pitch_joint = self.robot.pitch_joint(camera_frame, optical_x)
        self._place_robot(self.config.stance)
        self.camera = HeadCamera(self._client, self.robot, self.config.camera,
                                 np.random.default_rng(noise_seed), self._optical)
        self.robot.hide_links(self.config.camera.robot_visuals)
        self._grasps = GraspController(self._client, self.robot, self.door, self.config.grasp_distance,
                                       self.config.grasp_break_force, self.config.grasp_break_steps)

    def _configure_physics(self) -> None:
        self._client.setPhysicsEngineParameter(fixedTimeStep=self.config.time_step, useSplitImpulse=0)
        self._client.setGravity(0.0, 0.0, -self.config.gravity)
        self._client.setAdditionalSearchPath(str(cmeel_share_dir()))

    def _place_robot(self, stance: StanceConfig) -> None:
        self.robot.set_base_pose(planar_pose(-stance.distance, stance.lateral_offset, stance.yaw,
                                        self.profile.base_height))
        self.robot.reset_joints(self._initial_posture())

    def _initial_posture(self) -> dict[str, float]:
        """Zero (clipped into the limits), then the profile's nominal posture with its walking
        posture on top (the robot arrives walking), the overrides, and the head pitch on the
        joint that tilts the camera (unless overridden)."""
        posture = {name: min(max(0.0, limit.lower), limit.upper) for name, limit in self.robot.limits.items()}
        posture.update(self.profile.nominal_posture)
        posture.update(self.profile.walking_posture)
        overrides = dict(self.config.posture_overrides)
        if self._pitch_joint is not None and self._pitch_joint[0] not in overrides:
            name, sign = self._pitch_joint
            posture[name] = sign * self.config.camera.head_pitch
        posture.update(overrides)
        return posture

    def reset_robot(self, stance: StanceConfig | None = None) -> None:
        """Open both hands and put the robot back at ``stance`` (default: the configured one)
        in its initial posture; the door and the clock are left as they are."""
        for side in self.profile.arms:
            if self.holding(side):
                self.grasp(side, close=False)
        self._place_robot(stance or self.config.stance)

    # ------------------------------------------------------------------ lifetime
    def close(self) -> None:
        """Disconnect the PyBullet client (idempotent); the world is unusable afterwards."""
        self._client.disconnect()

    def __enter__(self) -> DoorWorld:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.close()

    # ------------------------------------------------------------------ time
    @property
    def time(self) -> float:
        """Simulated seconds since the start (step count / physics rate, no drift)."""
        return self._steps * self.config.time_step

    @property
    def step_count(self) -> int:
        return self._steps

    def step(self, count: int = 1) -> None:
        """Advance ``count`` physics steps."""
        for _ in range(count):
            self._step_once()

    def _step_once(self) -> None:
        latch = self.door.update(self.time)
        if latch is not None:
            kind = EventKind.LATCH_RELEASED if latch is LatchEvent.RELEASED else EventKind.LATCH_ENGAGED
            self._record(kind)
        self._apply_external_forces()
        self._client.stepSimulation()
        self._steps += 1
        for side in self._grasps.check_slips():
            self._record(EventKind.GRASP_SLIPPED, f"grasp force above {self.config.grasp_break_force:g} N",
                         side)

    def _record(self, kind: EventKind, detail: str = "", side: Side | None = None) -> None:
        self._events.append(SimEvent(self.time, kind, detail, side))

    # ------------------------------------------------------------------ robot
    @property
    def joint_names(self) -> tuple[str, ...]:
        """Every movable robot joint, in /joint_states order."""
        return self.robot.joint_names

    def joint_limits(self) -> dict[str, JointLimit]:
        return dict(self.robot.limits)

    def joint_positions(self) -> dict[str, float]:
        return self.robot.joint_positions()

    def joint_states(self) -> JointStates:
        return self.robot.joint_states()

    def set_joint_targets(self, targets: Mapping[str, float]) -> None:
        """Position targets by name (clipped to the limits); SimulationError on unknown or NaN."""
        self.robot.set_joint_targets(targets)

    def joint_targets(self) -> dict[str, float]:
        return self.robot.joint_targets()

    def base_pose(self) -> np.ndarray:
        """4×4 base frame (profile.base_frame) in odom."""
        return self.robot.base_pose()

    def set_base_pose(self, pose: np.ndarray) -> None:
        """Teleport the base (kinematic walking); SimulationError unless a finite rigid transform."""
        if not is_rigid(pose):
            raise SimulationError("base pose must be a finite rigid 4×4 transform")
        self.robot.set_base_pose(pose)

    def tcp_pose(self, side: Side) -> np.ndarray:
        """4×4 tool-centre point of the ``side`` hand in odom."""
        return self.robot.tcp_pose(side)

    def link_pose(self, link: str) -> np.ndarray:
        return self.robot.link_pose(link)

    def foot_placements(self) -> dict[Foot, FootPlacement]:
        """Where the soles are now (x, y, yaw in odom), from the profile's sole links."""
        placements = {}
        for side, link in self.profile.feet.items():
            pose = self.robot.link_pose(link)
            foot = Foot(side.value)
            placements[foot] = FootPlacement(foot, float(pose[0, 3]), float(pose[1, 3]), yaw_of(pose))
        return placements

    def _feet_midpoint(self) -> np.ndarray:
        feet = self.foot_placements()
        return stance_midpoint(feet[Foot.LEFT], feet[Foot.RIGHT])

    def base_pose_for_feet(self, left: FootPlacement, right: FootPlacement) -> np.ndarray:
        """Base pose that puts the soles at ``left``/``right`` (midpoint, mean yaw, nominal height)."""
        return stance_midpoint(left, right) @ self._stance_offset

    def body_extents(self, reach: float = 1.5) -> dict[str, float]:
        """How far (m) the robot's collision shapes reach from its base, in the base frame:
        ``ahead`` (+x), ``behind`` (−x), ``left`` (+y), ``right`` (−y) — the footprint a
        footstep planner must keep clear of the door frame. Measured with a probe plane
        ``reach`` m out on each side (PyBullet's closest points; exact for the shapes)."""
        base = self.base_pose()
        shape = self._client.createCollisionShape(pybullet.GEOM_BOX, halfExtents=[0.005, 3.0, 3.0])
        extents = {}
        for name, axis in (("ahead", 0), ("behind", 0), ("left", 1), ("right", 1)):
            sign = -1.0 if name in ("behind", "right") else 1.0
            direction = base[:3, axis] * sign
            yaw = math.atan2(direction[1], direction[0])
            probe = self._client.createMultiBody(0, shape, basePosition=(base[:3, 3] + reach * direction).tolist(),
                                                 baseOrientation=pybullet.getQuaternionFromEuler((0.0, 0.0, yaw)))
            nearest = min(point[8] for point in self._client.getClosestPoints(self.robot.body, probe, 2.0 * reach))
            self._client.removeBody(probe)
            extents[name] = reach - 0.005 - nearest
        return extents

    def scene_penetration(self) -> float:
        """Deepest penetration (m, ≥ 0) of a robot link into the wall or door frame."""
        return self.scene_contact()[0]

    def scene_contact(self) -> tuple[float, str]:
        """Deepest penetration (m, ≥ 0) into the wall or frame and the robot link that made it."""
        contacts = self._client.getContactPoints(bodyA=self.robot.body, bodyB=self.door.body, linkIndexB=-1)
        if not contacts:
            return 0.0, ""
        deepest = min(contacts, key=lambda contact: contact[8])
        link = deepest[3]
        name = self._client.getJointInfo(self.robot.body, link)[12].decode() if link >= 0 else "base"
        return max(-deepest[8], 0.0), name

    # ------------------------------------------------------------------ door
    def door_state(self) -> DoorState:
        return self.door.state()

    def handle_grasp_pose(self) -> np.ndarray:
        """4×4 ground-truth grasp point on the lever (x = door normal towards the robot, z up)."""
        return self.door.handle_grasp_pose()

    def door_ground_truth(self) -> DoorGroundTruth:
        return self.door.ground_truth()

    def apply_door_force(self, force: Sequence[float], point: Sequence[float],
                         part: DoorPart = DoorPart.LEAF, steps: int = 1) -> None:
        """Push ``part`` with ``force`` (N, odom axes) at ``point`` (odom) for the next ``steps`` steps.

        The point is attached to the part (it moves with the leaf as it swings); the force keeps
        its world direction. For tests and disturbances.
        """
        vector = np.asarray(force, dtype=float)
        where = np.asarray(point, dtype=float)
        if vector.shape != (3,) or where.shape != (3,) or not np.all(np.isfinite([*vector, *where])):
            raise SimulationError("door force and point must be finite 3-vectors")
        if not isinstance(steps, int) or steps < 1:
            raise SimulationError(f"door force steps must be a positive integer, got {steps!r}")
        local = invert(self.door.link_pose(part)) @ np.append(where, 1.0)
        self._forces.append((_ExternalForce(part, vector, local[:3]), steps))

    def clear_door_forces(self) -> None:
        self._forces.clear()

    def _apply_external_forces(self) -> None:
        remaining = []
        for push, steps in self._forces:
            point = self.door.link_pose(push.part) @ np.append(push.local_point, 1.0)
            self._client.applyExternalForce(self.door.body, self.door.link_index(push.part),
                                            push.force.tolist(), point[:3].tolist(), pybullet.WORLD_FRAME)
            if steps > 1:
                remaining.append((push, steps - 1))
        self._forces = remaining

    # ------------------------------------------------------------------ grasp
    def grasp(self, side: Side, close: bool) -> GraspResult:
        """Close (attach within grasp_distance) or open the ``side`` hand; records an event."""
        result = self._grasps.close(side) if close else self._grasps.open(side)
        kind = (EventKind.GRASP_OPENED if not close
                else EventKind.GRASP_CLOSED if result.success else EventKind.GRASP_REFUSED)
        self._record(kind, result.message, side)
        return result

    def holding(self, side: Side) -> bool:
        return self._grasps.holding(side)

    def slipped(self, side: Side) -> bool:
        """True when the last grasp of ``side`` ended in a slip (cleared by the next close)."""
        return self._grasps.slipped(side)

    def hand_handle_distance(self, side: Side) -> float:
        """Distance (m) between the ``side`` TCP and the handle grasp point."""
        return self._grasps.distance(side)

    def grasp_force(self, side: Side) -> float:
        """Current reaction force (N) of the ``side`` grasp, 0 when open."""
        return self._grasps.constraint_force(side)

    def peak_grasp_force(self, side: Side) -> float:
        """Largest reaction force (N) of the ``side`` grasp since it was last closed."""
        return self._grasps.peak_force(side)

    # ------------------------------------------------------------------ events and camera
    def events(self) -> tuple[SimEvent, ...]:
        """Every event since the start, oldest first."""
        return tuple(self._events)

    def events_since(self, index: int) -> tuple[SimEvent, ...]:
        """Events after the first ``index`` (a node keeps ``len(world.events())`` as its cursor)."""
        return tuple(self._events[index:])

    def render(self) -> CameraFrame:
        """One registered RGB-D frame of the head camera at the current time."""
        return self.camera.render(self.time)


def stance_midpoint(left: FootPlacement, right: FootPlacement) -> np.ndarray:
    """Planar pose halfway between two soles, with their mean heading (circular mean)."""
    heading = math.atan2(math.sin(left.yaw) + math.sin(right.yaw), math.cos(left.yaw) + math.cos(right.yaw))
    return planar_pose((left.x + right.x) / 2.0, (left.y + right.y) / 2.0, heading)
