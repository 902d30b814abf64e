"""The simulated world: TALOS (or another profile), the door in its wall, the head camera.

``DoorWorld`` owns one PyBullet client in DIRECT mode. Conventions (see
:mod:`door_sim_bridge.world.door` for the door's): world frame = ``odom``; the robot starts
on the x < 0 side at x = -stance.distance, y = stance.lateral_offset, yawed by stance.yaw from
facing +x, its soles on the floor, joints in the profile's nominal posture with the head
pitched down by ``camera.head_pitch`` (by its neck; a robot without one looks where its camera
is mounted).

The robot is **physical** by default (:class:`~door_sim_bridge.world.config.RobotMode`): a
floating base standing on a collision floor, whose walking controller
(:mod:`door_sim_bridge.world.balance`) keeps it balanced every step, walks footstep plans
(:meth:`walk`) and can fall; nothing teleports it once placed. The **kinematic** robot (fixed
base, glided along footsteps by the execution) remains for fast unit tests.

One :meth:`DoorWorld.step` is one physics step of 1/physics_rate s: the door's latch is
updated and its spring, damper and wind torques applied (PyBullet clears torques and external
forces after every step, so they are re-applied each time), test forces are applied, the
balance controller sets the joint targets, the solver runs, then every grasp's constraint
force is checked for a slip and the robot for a fall.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import Enum
from types import TracebackType

import numpy as np
import pybullet

from door_contract.converters.footsteps import FootPlacement
from door_contract.geometry import planar_pose, yaw_of
from door_contract.vocabulary import Foot, Side
from door_robot.locations import cmeel_share_dir
from door_robot.profile import load_profile
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.world.balance import BalanceLoop
from door_sim_bridge.world.camera import CameraFrame, HeadCamera, optical_offset
from door_sim_bridge.world.client import PhysicsClient
from door_sim_bridge.world.config import ContactSolver, RobotMode, StanceConfig, WorldConfig
from door_sim_bridge.world.door import DoorGroundTruth, DoorPart, DoorState, LatchEvent, SimDoor
from door_sim_bridge.world.grasp import GraspController, GraspResult
from door_sim_bridge.world.hardware import SoleContact, centre_of_mass_motion, make_floor, sole_contact
from door_sim_bridge.world.robot import JointLimit, JointStates, SimRobot
from door_sim_bridge.world.robot_urdf import sole_placement_link
from door_sim_bridge.world.transforms import invert, is_rigid

__all__ = ["LEAF_CLOSED", "DoorWorld", "EventKind", "SimEvent", "stance_midpoint"]

SOLE_CLEARANCE = 0.0005  # m between the lowest sole and the floor when the robot is placed
LEAF_CLOSED = 0.03  # rad; a leaf nearer its frame than this holds a hand only through its lever
SOLVER_TYPES = {ContactSolver.DANTZIG: pybullet.CONSTRAINT_SOLVER_LCP_DANTZIG,
                ContactSolver.SEQUENTIAL_IMPULSE: pybullet.CONSTRAINT_SOLVER_LCP_SI}


class EventKind(str, Enum):
    GRASP_CLOSED = "grasp_closed"
    GRASP_REFUSED = "grasp_refused"
    GRASP_OPENED = "grasp_opened"
    GRASP_SLIPPED = "grasp_slipped"
    LATCH_RELEASED = "latch_released"
    LATCH_ENGAGED = "latch_engaged"
    FELL = "fell"


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
        self._robot_forces: list[tuple[str, np.ndarray, int]] = []
        self._stance_offset = invert(self._feet_midpoint()) @ self.robot.base_pose()

    def _build(self) -> None:
        """Physics settings, door, robot (placed), camera and grasps; randomness from the seed."""
        wind_seed, noise_seed = np.random.SeedSequence(self.config.seed).spawn(2)
        self._configure_physics()
        phase = float(np.random.default_rng(wind_seed).uniform(0.0, 2.0 * math.pi))
        self.door = SimDoor(self._client, self.config.door, phase)
        physical = self.config.robot_mode is RobotMode.PHYSICAL
        self._floor = make_floor(self._client, self.config.floor_friction) if physical else None
        self.robot = SimRobot(self._client, self.profile, self.config.joint_force_scale, floating=physical)
        if physical:
            self._set_sole_friction(self.config.floor_friction)
        camera_frame = self.profile.head_camera_frame
        self._optical = optical_offset(self.robot, camera_frame, self.profile.head_camera_axes)  # zero posture
        optical_x = (self.robot.link_pose(camera_frame) @ self._optical)[:3, 0]
        self._pitch_joint = self.robot.pitch_joint(camera_frame, optical_x)
        self._place_robot(self.config.stance)
        self.camera = HeadCamera(self._client, self.robot, self.config.camera,
                                 np.random.default_rng(noise_seed), self._optical)
        self.robot.hide_links(self.config.camera.robot_visuals)
        self._grasps = GraspController(self._client, self.robot, self.door, self.config.grasp_distance,
                                       self.config.grasp_break_force, self.config.grasp_break_steps,
                                       self.config.grasp_model)
        # the floor exists exactly for the physical robot
        self.balance = (BalanceLoop(self._client, self.robot, self._floor, self.door.body, self.config,
                                    self._grasps.holding, self.leaf_closed) if self._floor is not None else None)

    def leaf_closed(self) -> bool:
        """The leaf within ``LEAF_CLOSED`` of its frame (it can bear on a hand only through its lever)."""
        return self.door.state().hinge_angle < LEAF_CLOSED

    def _set_sole_friction(self, friction: float) -> None:
        for link in self.profile.feet.values():
            carrier = sole_placement_link(self.robot, link)
            self._client.changeDynamics(self.robot.body, carrier, lateralFriction=friction)

    def _configure_physics(self) -> None:
        self._client.setPhysicsEngineParameter(fixedTimeStep=self.config.time_step, useSplitImpulse=0,
                                               numSolverIterations=self.config.solver_iterations,
                                               constraintSolverType=SOLVER_TYPES[self.config.contact_solver])
        self._client.setGravity(0.0, 0.0, -self.config.gravity)
        self._client.setAdditionalSearchPath(str(cmeel_share_dir()))

    def _place_robot(self, stance: StanceConfig) -> None:
        """Base at the stance (at the profile's base height), joints in the initial posture;
        the physical robot is then lowered or raised until its lowest sole is on the floor."""
        pose = planar_pose(-stance.distance, stance.lateral_offset, stance.yaw, self.profile.base_height)
        self.robot.set_base_pose(pose)
        self.robot.reset_joints(self._initial_posture())
        if not self.robot.floating:
            return
        lowest = min(self.robot.link_pose(link)[2, 3] for link in self.profile.feet.values())
        pose[2, 3] -= lowest - SOLE_CLEARANCE
        self.robot.set_base_pose(pose)

    def _initial_posture(self) -> dict[str, float]:
        """Zero (clipped into the limits), then the profile's nominal posture with its walking
        posture on top (the robot arrives walking) and its look posture (how it stands to look
        for the door), the overrides, and the head pitch on the neck joint that tilts the
        camera (unless overridden)."""
        posture = {name: min(max(0.0, limit.lower), limit.upper) for name, limit in self.robot.limits.items()}
        posture.update(self.profile.nominal_posture)
        posture.update(self.profile.walking_posture)
        posture.update(self.profile.look_posture)
        overrides = dict(self.config.posture_overrides)
        if self._pitch_joint is not None and self._pitch_joint[0] not in overrides:
            name, sign = self._pitch_joint
            posture[name] = sign * self.config.camera.head_pitch
        posture.update(overrides)
        return posture

    def reset_robot(self, stance: StanceConfig | None = None) -> None:
        """Open both hands and put the robot back at ``stance`` (default: the configured one)
        in its initial posture; the door and the clock are left as they are. Kinematic robot
        only: the physical one is never teleported."""
        self._require_kinematic("reset_robot")
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
        self._apply_robot_forces()
        if self.balance is not None:
            self.balance.control()
        self._client.stepSimulation()
        self._steps += 1
        for side in self._grasps.check_slips():
            self._record(EventKind.GRASP_SLIPPED, f"grasp force above {self.config.grasp_break_force:g} N",
                         side)
        fall = self.balance.check_fall() if self.balance is not None else None
        if fall is not None:
            self._record(EventKind.FELL, fall)

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
        """Position targets by name (clipped to the limits); SimulationError on unknown or NaN,
        and, for the physical robot, on leg joints (its balance drives them)."""
        if self.balance is None:
            self.robot.set_joint_targets(targets)
            return
        values = np.array([float(v) for v in targets.values()])
        if not np.all(np.isfinite(values)):
            raise SimulationError("joint targets contain NaN or infinity")
        self.balance.set_upper_body({name: min(max(float(v), self.robot.limits[name].lower),
                                               self.robot.limits[name].upper) if name in self.robot.limits
                                     else float(v) for name, v in targets.items()})

    def joint_targets(self) -> dict[str, float]:
        return self.robot.joint_targets()

    def commandable_joints(self) -> frozenset[str]:
        """Joints a trajectory may move: all of them on the kinematic robot; the upper body
        (torso, arms, neck, grippers) on the physical one."""
        if self.balance is None:
            return frozenset(self.robot.joint_names)
        return frozenset(self.balance.controller.joints.upper_body)

    def base_pose(self) -> np.ndarray:
        """4×4 base frame (profile.base_frame) in odom."""
        return self.robot.base_pose()

    def set_base_pose(self, pose: np.ndarray) -> None:
        """Teleport the base (kinematic walking); SimulationError unless a finite rigid transform,
        and always for the physical robot."""
        self._require_kinematic("set_base_pose")
        if not is_rigid(pose):
            raise SimulationError("base pose must be a finite rigid 4×4 transform")
        self.robot.set_base_pose(pose)

    # ------------------------------------------------------------------ the physical robot
    @property
    def physical(self) -> bool:
        return self.balance is not None

    def _require_kinematic(self, what: str) -> None:
        if self.balance is not None:
            raise SimulationError(f"{what} would teleport the physical robot (kinematic robot only)")

    def walk(self, steps: Sequence[FootPlacement], crouch: float = 0.0) -> float:
        """Start walking ``steps`` with the walking controller, the pelvis ``crouch`` m below its
        standing height (:meth:`~door_sim_bridge.walking.controller.WalkingController.walk`);
        the walk's duration (s).

        SimulationError for the kinematic robot (its executions glide it), when fallen or
        already walking, or when no walking pattern exists for the steps.
        """
        if self.balance is None:
            raise SimulationError("the kinematic robot does not walk (FootstepExecution glides it)")
        if self.fallen:
            raise SimulationError(f"the robot has fallen ({self.balance.fall})")
        return self.balance.walk(steps, crouch)

    def stop_walking(self) -> None:
        """End a walk at the next stable stance (the foot in the air lands first)."""
        if self.balance is not None:
            self.balance.stop_walking()

    @property
    def walking(self) -> bool:
        return self.balance is not None and self.balance.walking

    @property
    def fallen(self) -> bool:
        return self.balance is not None and self.balance.fall is not None

    @property
    def fall_reason(self) -> str:
        return "" if self.balance is None or self.balance.fall is None else self.balance.fall

    def push_robot(self, link: str, force: Sequence[float], steps: int) -> None:
        """Shove the robot: ``force`` (N, odom axes) at ``link``'s centre of mass for ``steps``
        physics steps (a disturbance; the stabiliser does not measure it)."""
        vector = np.asarray(force, dtype=float)
        if vector.shape != (3,) or not np.all(np.isfinite(vector)):
            raise SimulationError("robot push force must be a finite 3-vector")
        if not isinstance(steps, int) or steps < 1:
            raise SimulationError(f"robot push steps must be a positive integer, got {steps!r}")
        self.robot.link_index(link)
        self._robot_forces.append((link, vector, steps))

    def _apply_robot_forces(self) -> None:
        remaining = []
        for link, force, steps in self._robot_forces:
            index = self.robot.link_index(link)
            point = self.robot.link_com_pose(index)[:3, 3]
            self._client.applyExternalForce(self.robot.body, index, force.tolist(), point.tolist(),
                                            pybullet.WORLD_FRAME)
            if steps > 1:
                remaining.append((link, force, steps - 1))
        self._robot_forces = remaining

    def centre_of_mass(self) -> np.ndarray:
        """Whole-body CoM (odom, m): PyBullet's link masses and poses."""
        return centre_of_mass_motion(self._client, self.robot.body, self.robot.link_masses).position

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
            placements[side] = FootPlacement(side, float(pose[0, 3]), float(pose[1, 3]), yaw_of(pose))
        return placements

    def sole_contacts(self) -> dict[Side, SoleContact]:
        """The floor under each sole now (physical robot only: a kinematic one has no floor)."""
        if self._floor is None:
            raise SimulationError("sole contacts need the physical robot (the kinematic one has no floor)")
        return {side: sole_contact(self._client, self.robot.body, self._floor, sole_placement_link(self.robot, link))
                for side, link in self.profile.feet.items()}

    def _feet_midpoint(self) -> np.ndarray:
        feet = self.foot_placements()
        return stance_midpoint(feet[Foot.LEFT], feet[Foot.RIGHT])

    def base_pose_for_feet(self, left: FootPlacement, right: FootPlacement) -> np.ndarray:
        """Base pose that puts the soles at ``left``/``right`` (midpoint, mean yaw, nominal height)."""
        pose: np.ndarray = stance_midpoint(left, right) @ self._stance_offset
        return pose

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
        name = self._link_name(self.robot.body, link)
        return max(-deepest[8], 0.0), name

    # ------------------------------------------------------------------ door
    def door_state(self) -> DoorState:
        return self.door.state()

    def door_contact_forces(self) -> dict[str, float]:
        """Normal force (N) of this step's contacts between the robot and the door's body (leaf,
        handle, frame and wall), summed per ``"<robot link> | <door link>"``."""
        forces: dict[str, float] = {}
        for contact in self._client.getContactPoints(bodyA=self.robot.body, bodyB=self.door.body):
            robot_link = self._link_name(self.robot.body, contact[3])
            door_link = self._link_name(self.door.body, contact[4])
            key = f"{robot_link} | {door_link}"
            forces[key] = forces.get(key, 0.0) + float(contact[9])
        return forces

    def _link_name(self, body: int, link: int) -> str:
        return self._client.getJointInfo(body, link)[12].decode() if link >= 0 else "base"

    def handle_grasp_pose(self) -> np.ndarray:
        """4×4 ground-truth grasp point on the lever (x = door normal towards the robot, z up)."""
        return self.door.handle_grasp_pose()

    def door_ground_truth(self) -> DoorGroundTruth:
        return self.door.ground_truth()

    def apply_door_force(self, force: Sequence[float] | np.ndarray, point: Sequence[float] | np.ndarray,
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

    def hand_touches_door(self, side: Side) -> bool:
        """Whether the ``side`` hand (the links below its wrist joint) touches the leaf or the
        handle this step: the door then bears on the hand as a grasp does."""
        hand = self.robot.descendants(self.robot.joint_link_index(self.robot.wrist_joint(side)))
        moving = {self.door.link_index(part) for part in DoorPart}
        contacts = self._client.getContactPoints(bodyA=self.robot.body, bodyB=self.door.body)
        return any(contact[3] in hand and contact[4] in moving for contact in contacts)

    def door_leans_on(self, side: Side) -> bool:
        """Whether the open door bears on the ``side`` hand by itself: the hand touches the leaf
        or handle, does not hold it, and the leaf is open (its closer and the wind press it on
        the hand; a closed leaf rests on its frame, and a hand touching it pushes it)."""
        return not self.holding(side) and not self.leaf_closed() and self.hand_touches_door(side)

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
