"""The robot's whole-body walking controller: balance always, steps when asked.

Every control tick (every physics step) it turns references into joint position targets:

* **upper body** (torso, arms, neck, grippers): the commanded joint positions, unchanged —
  they are masked out of the inverse kinematics and set on the model directly;
* **legs**: placo's whole-body inverse kinematics (a QP over the floating base and the leg
  joints) with both soles as frame tasks, the trunk orientation, and either
  - *standing*: the trunk's position held where standing began (the pelvis stays put
    relative to the feet, so an arm trajectory planned with a fixed base is executed as
    planned; the trajectory optimiser has kept its CoM inside the support polygon), or
  - *walking*: the CoM of the LIPM walking pattern (:mod:`door_sim_bridge.walking.gait`)
    and the swing foot along its curve;
  plus, in both, the stabiliser's CoM offset (:mod:`door_sim_bridge.walking.stabilizer`),
  and while walking the DCM feedback's (:mod:`door_sim_bridge.walking.dcm`: the measured
  capture point's error from the pattern's, fed back on the CoM target).

Feet on the ground are held where they are measured and the model is anchored on the measured
support sole every tick of a single support, so a stance foot that slips does not carry its
error into the next landing: each step lands where it was planned in ``odom``. A stop request
during a walk re-plans the pattern to end at the next stable stance: the foot in the air
lands on its target, the other steps beside it, and the CoM comes to rest over both.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import Enum

import numpy as np
import placo

from door_contract.converters.footsteps import FootPlacement
from door_contract.vocabulary import Foot
from door_robot.crouch import crouch_problem
from door_robot.profile import RobotProfile
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.walking.dcm import CentreOfMassMotion, DcmFeedback, PatternDeparture
from door_sim_bridge.walking.gait import GaitOptions, footstep_sequence, placo_parameters, smooth_blend
from door_sim_bridge.walking.model import PLACO_TRUNK_FRAME, joint_split, load_placo_robot
from door_sim_bridge.walking.stabilizer import ContactWrench, Stabilizer, StabilizerOptions
from door_sim_bridge.walking.support import into_polygon, support_polygon

__all__ = ["START_INSET", "BalanceMode", "HeightChange", "Measurement", "WalkingController",
           "level_frame", "mean_yaw", "offset_in_stance", "stance_frame", "supports_from", "yaw_rotation"]

START_INSET = 0.005
"""m a walk's starting CoM is kept inside the pattern's ZMP region (``zmp_margin`` in from the
soles' edges), so that placo's QP starts strictly feasible."""


HEIGHT_PROBE = 0.02  # m the trunk is lowered on the model to measure how the CoM follows it
HEIGHT_PROBE_TICKS = 200  # IK ticks for it (velocity-limited: 0.8 s of motion at the control rate)


@dataclass(frozen=True)
class HeightChange:
    """The CoM's height through a walk's first double support: ``start`` → ``end`` m over
    ``duration`` s, a cosine blend (zero vertical speed at both ends), then ``end``."""

    start: float
    end: float
    duration: float

    def at(self, t: float) -> float:
        tau = t / self.duration if self.duration > 0.0 else 1.0
        return self.start + (self.end - self.start) * smooth_blend(tau)


class BalanceMode(str, Enum):
    STANDING = "standing"
    WALKING = "walking"


@dataclass(frozen=True, eq=False)
class Measurement:
    """What the controller reads from the hardware each tick (world frame = odom)."""

    soles: Mapping[Foot, np.ndarray]  # 4×4 sole poses
    cop: np.ndarray | None  # (2,) centre of pressure of the floor contacts, None in the air
    wrench: ContactWrench  # net external force on the robot (door contacts and grasps)
    trunk_rotation: np.ndarray | None = None  # 3×3 base orientation (an IMU), None: not measured
    centre_of_mass: CentreOfMassMotion | None = None  # the robot's (state estimation), None: not measured


def level_frame(frame: np.ndarray) -> np.ndarray:
    """``frame`` with its z axis made vertical (yaw kept) and on the floor."""
    yaw = math.atan2(frame[1, 0], frame[0, 0])
    level = np.eye(4)
    level[:2, :2] = [[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]]
    level[:2, 3] = frame[:2, 3]
    return level


def yaw_rotation(yaw: float) -> np.ndarray:
    rotation = np.eye(3)
    rotation[:2, :2] = [[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]]
    return rotation


def supports_from(items: list[placo.Support]) -> placo.Supports:
    supports = placo.Supports()
    for item in items:
        supports.append(item)
    return supports


def mean_yaw(first: np.ndarray, second: np.ndarray) -> float:
    return math.atan2(first[1, 0] + second[1, 0], first[0, 0] + second[0, 0])


def stance_frame(feet: Mapping[Foot, np.ndarray]) -> np.ndarray:
    """The soles' midpoint on the floor, their mean heading (4×4)."""
    left, right = feet[Foot.LEFT], feet[Foot.RIGHT]
    frame = np.eye(4)
    frame[:3, :3] = yaw_rotation(mean_yaw(left, right))
    frame[:2, 3] = 0.5 * (left[:2, 3] + right[:2, 3])
    return frame


def offset_in_stance(point: np.ndarray, feet: Mapping[Foot, np.ndarray]) -> str:
    """Where ``point`` stands from the soles' midpoint, in the stance frame (m: ahead, left)."""
    stance = stance_frame(feet)
    ahead, left = stance[:2, :2].T @ (np.asarray(point)[:2] - stance[:2, 3])
    return f"({ahead:+.3f}, {left:+.3f}) m from the feet's midpoint"


class WalkingController:
    """Balance and walking of one robot (see the module docstring)."""

    def __init__(self, urdf_text: str, profile: RobotProfile, gait: GaitOptions,
                 stabilizer: StabilizerOptions, dt: float) -> None:
        self.profile, self.gait, self.dt = profile, gait, dt
        self.joints = joint_split(urdf_text, profile.feet)
        self.robot = load_placo_robot(urdf_text, profile)
        self.stabilizer = Stabilizer(stabilizer, self.robot.total_mass() * 9.81)
        self._dcm = DcmFeedback(stabilizer.dcm_gain, stabilizer.max_dcm_shift)
        self.mode = BalanceMode.STANDING
        self._upper = {name: 0.0 for name in self.joints.upper_body}
        self._trajectory: placo.WPGTrajectory | None = None
        self._walk_time = 0.0
        self._support_side: str | None = None
        self._anchor_foot = Foot.LEFT
        self._feet: dict[Foot, np.ndarray] = {}
        self._trunk_target = np.zeros(3)
        self._com_from = np.zeros(3)
        self._com_target = np.zeros(3)
        self._settle_time = 0.0
        self._trunk_rotation = np.eye(3)
        self._standing_height = 0.0  # m: the pelvis's height above the soles standing as placed (start())
        self._height_change = HeightChange(0.0, 0.0, 1.0)
        self._com_per_pelvis = 1.0  # ∂(CoM height)/∂(pelvis height), the soles fixed (start())
        self.steps_planned = 0
        self.steps_landed = 0
        self._stopping = False
        self._solver, self._tasks = self._make_solver()

    # ------------------------------------------------------------------ set-up
    def _make_solver(self) -> tuple[placo.KinematicsSolver, placo.WalkTasks]:
        solver = placo.KinematicsSolver(self.robot)
        solver.enable_velocity_limits(True)
        solver.dt = self.dt
        for name in self.joints.upper_body:
            solver.mask_dof(name)
        tasks = placo.WalkTasks()
        tasks.trunk_mode = True
        tasks.initialize_tasks(solver, self.robot)
        return solver, tasks

    def start(self, joint_positions: Mapping[str, float], base_pose: np.ndarray) -> None:
        """Synchronise the model with the measured robot and stand where it is."""
        for name, value in joint_positions.items():
            if name in self._upper or name in self.joints.legs:
                self.robot.set_joint(name, float(value))
        self._upper.update({k: float(v) for k, v in joint_positions.items() if k in self._upper})
        self.robot.set_T_world_frame(PLACO_TRUNK_FRAME, np.asarray(base_pose, dtype=float))
        self.robot.update_kinematics()
        self._standing_height = self._pelvis_height()
        self._stand_here(settle=False)  # placed standing: nothing to settle
        self._com_per_pelvis = self._measure_com_per_pelvis()

    def _stance_frame(self) -> np.ndarray:
        return stance_frame(self._feet)

    def _stand_here(self, settle: bool = True) -> None:
        """Hold the soles where the model has them. After a walk (``settle``) the CoM is first
        brought over their midpoint (a smooth blend of ``settle_s``, CoM task, as the walk
        pattern tracked it); then, and at start-up, the trunk is held where it is — the pelvis
        stays put relative to the feet, so arm trajectories planned from it execute as planned."""
        self.mode, self._trajectory, self._support_side = BalanceMode.STANDING, None, None
        self._feet = {Foot.LEFT: level_frame(self.robot.get_T_world_left()),
                      Foot.RIGHT: level_frame(self.robot.get_T_world_right())}
        stance = self._stance_frame()
        self._trunk_rotation = stance[:3, :3]
        self._com_from = np.array(self.robot.com_world())
        self._com_target = np.array([stance[0, 3], stance[1, 3], self._com_from[2]])
        self._settle_time = 0.0 if settle else self.gait.settle_s
        self._tasks.trunk_mode = settle
        self._hold_trunk()

    def _pelvis_height(self) -> float:
        """m of the model's trunk frame above its soles' mean height."""
        soles = 0.5 * (self.robot.get_T_world_left()[2, 3] + self.robot.get_T_world_right()[2, 3])
        return float(self.robot.get_T_world_frame(PLACO_TRUNK_FRAME)[2, 3] - soles)

    def _measure_com_per_pelvis(self) -> float:
        """∂(CoM height)/∂(pelvis height) with the soles where they stand: the legs fold under a
        lowering pelvis, so the CoM moves less than the pelvis (TALOS: 0.8). Measured on the model
        by lowering the trunk :data:`HEIGHT_PROBE` m with the IK; the model is then restored."""
        saved, trunk_mode = np.array(self.robot.state.q), self._tasks.trunk_mode
        self._tasks.trunk_mode = True
        com, pelvis = float(self.robot.com_world()[2]), self._pelvis_height()
        target = self._trunk_target - np.array([0.0, 0.0, HEIGHT_PROBE])
        for _ in range(HEIGHT_PROBE_TICKS):
            self._tasks.update_tasks(self._feet[Foot.LEFT], self._feet[Foot.RIGHT], target, self._trunk_rotation)
            self._solver.solve(True)
            self.robot.update_kinematics()
        lowered = pelvis - self._pelvis_height()
        ratio = (com - float(self.robot.com_world()[2])) / lowered if lowered > 0.5 * HEIGHT_PROBE else 1.0
        self.robot.state.q, self._tasks.trunk_mode = saved, trunk_mode
        self.robot.update_kinematics()
        return float(np.clip(ratio, 0.5, 1.0))

    def _hold_trunk(self) -> None:
        self._trunk_target = np.array(self.robot.get_T_world_frame(PLACO_TRUNK_FRAME)[:3, 3])

    # ------------------------------------------------------------------ commands
    def set_upper_body(self, targets: Mapping[str, float]) -> None:
        """Commanded positions of upper-body joints; legs are refused (balance drives them)."""
        legs = [name for name in targets if name in self.joints.legs]
        if legs:
            raise SimulationError(f"{legs[0]} is a leg joint: the walking controller drives the legs")
        unknown = [name for name in targets if name not in self._upper]
        if unknown:
            raise SimulationError(f"{self.profile.name} has no upper-body joint {unknown[0]!r}")
        self._upper.update({name: float(value) for name, value in targets.items()})

    def upper_body_targets(self) -> dict[str, float]:
        return dict(self._upper)

    def walk(self, steps: Sequence[FootPlacement], soles: Mapping[Foot, np.ndarray], crouch: float = 0.0) -> float:
        """Plan the walk over ``steps`` from the measured ``soles``, the pelvis ``crouch`` m below
        its height standing as placed; its duration (s), 0 when there is nothing to walk.
        SimulationError when already walking or the pattern fails.

        The pattern is the LIPM's at the CoM height h that puts the pelvis there in the present
        posture (ω = √(g/h)); the CoM goes to h from where it is over the walk's first double
        support (a cosine blend, both feet down), and the robot stays at that height standing
        after the walk, until a walk at another height."""
        if self.mode is BalanceMode.WALKING:
            raise SimulationError("already walking")
        if problem := crouch_problem(crouch):
            raise SimulationError(problem)
        self._anchor(Foot.LEFT, soles[Foot.LEFT])
        feet_now = {Foot.LEFT: level_frame(self.robot.get_T_world_left()),
                    Foot.RIGHT: level_frame(self.robot.get_T_world_right())}
        walking = self.profile.walking
        footsteps = footstep_sequence(steps, feet_now, self.gait.in_place_tolerance,
                                      walking.foot_length, walking.foot_width)
        if not footsteps:
            return 0.0
        com = np.array(self.robot.com_world())
        height = float(com[2]) - self._com_per_pelvis * (self._pelvis_height() - (self._standing_height - crouch))
        parameters = placo_parameters(self.gait, walking.foot_length, walking.foot_width,
                                      walking.foot_separation, height)
        # placo's generator keeps a C++ reference to its parameters: they must outlive it
        self._parameters = parameters
        self._generator = placo.WalkPatternGenerator(self.robot, parameters)
        supports = placo.FootstepsPlanner.make_supports(footsteps, 0.0, True, parameters.has_double_support(), True)
        start = self._pattern_start(com, feet_now)
        try:
            trajectory = self._generator.plan(supports, start, 0.0)
        except RuntimeError as error:  # placo's QP found no pattern: a refused plan, not a bug
            moved = "" if np.allclose(start[:2], com[:2]) else f", brought in from {offset_in_stance(com, feet_now)}"
            raise SimulationError(f"the walking pattern generator found no CoM trajectory for {len(steps)} steps "
                                  f"from the CoM at {offset_in_stance(start, feet_now)}{moved} ({error})") from error
        if not trajectory.t_end > 0.0:
            raise SimulationError("the walking pattern generator found no CoM trajectory")
        self._trajectory, self._walk_time, self._stopping = trajectory, 0.0, False
        self._height_change = HeightChange(float(com[2]), height, float(trajectory.get_part_t_end(0.0)))
        self._dcm.start()
        self.steps_planned, self.steps_landed = len(footsteps) - 2, 0
        self.mode, self._support_side, self._anchor_foot = BalanceMode.WALKING, None, Foot.LEFT
        self._tasks.trunk_mode = False
        return float(trajectory.t_end)

    def _pattern_start(self, com: np.ndarray, feet: Mapping[Foot, np.ndarray]) -> np.ndarray:
        """The CoM the pattern starts from: ``com`` brought inside the double-support polygon
        where the pattern's ZMP may be (:mod:`~door_sim_bridge.walking.support`)."""
        walking = self.profile.walking
        polygon = support_polygon(feet.values(), walking.foot_length, walking.foot_width,
                                  self.gait.zmp_margin + START_INSET)
        start = np.array(com, dtype=float)
        start[:2] = into_polygon(start[:2], polygon)
        return start

    def stop(self) -> None:
        """End the walk at the next stable stance (no-op when standing)."""
        if self.mode is BalanceMode.WALKING:
            self._stopping = True

    @property
    def settling(self) -> bool:
        """Standing, but the trunk still on its way over the feet after a walk."""
        return self.mode is BalanceMode.STANDING and self._settle_time < self.gait.settle_s

    @property
    def pattern_departure(self) -> PatternDeparture | None:
        """When the last walk was knocked off its pattern (None: it never was, or no walk yet)."""
        return self._dcm.departure

    @property
    def remaining_s(self) -> float:
        """Seconds of walking left (0 standing)."""
        if self._trajectory is None:
            return 0.0
        return max(0.0, float(self._trajectory.t_end) - self._walk_time)

    # ------------------------------------------------------------------ the tick
    def tick(self, measurement: Measurement) -> dict[str, float]:
        """Joint position targets for this tick (legs and upper body)."""
        for name, value in self._upper.items():
            self.robot.set_joint(name, value)
        if self.mode is BalanceMode.WALKING:
            self._walk_references(measurement)
        else:
            self._stand_references(measurement)
        self.robot.update_kinematics()
        self._solver.solve(True)
        if self.mode is BalanceMode.WALKING:
            self.robot.ensure_on_floor()
        targets = {name: self.robot.get_joint(name) for name in self.joints.legs}
        targets.update(self._upper)
        return targets

    def _stand_references(self, measurement: Measurement) -> None:
        offset = self.stabilizer.update(self.dt, self._com_reference(), measurement.wrench, measurement.cop,
                                        walking=False)
        shift = np.array([offset[0], offset[1], 0.0])
        if self.settling:
            blend = smooth_blend(self._settle_time / self.gait.settle_s)
            self._settle_time += self.dt
            self._tasks.trunk_mode = False
            com = (1.0 - blend) * self._com_from + blend * self._com_target
            self._tasks.update_tasks(self._feet[Foot.LEFT], self._feet[Foot.RIGHT], com + shift, self._trunk_rotation)
            if not self.settling:  # settled: from now on the pelvis holds still
                self._hold_trunk()
            return
        self._tasks.trunk_mode = True
        target = self._trunk_target + shift
        self._tasks.update_tasks(self._feet[Foot.LEFT], self._feet[Foot.RIGHT], target, self._trunk_rotation)

    def _com_reference(self) -> np.ndarray:
        """Standing: where the CoP should be — under the CoM of the commanded posture."""
        return np.array(self.robot.com_world()[:2])

    def _walk_trajectory(self) -> placo.WPGTrajectory:
        """The walk's pattern; SimulationError if there is none (a bug: every walk has one)."""
        if self._trajectory is None:
            raise SimulationError("walking without a walking pattern")
        return self._trajectory

    def _walk_references(self, measurement: Measurement) -> None:
        trajectory, t = self._walk_trajectory(), self._walk_time
        if self._stopping:
            self._replan_stop(t)
            if self.mode is BalanceMode.STANDING:
                self._stand_references(measurement)
                return
            trajectory = self._walk_trajectory()
        if t >= trajectory.t_end:
            self._stand_here()
            self._stand_references(measurement)
            return
        self._tasks.update_tasks_from_trajectory(trajectory, t)
        self._hold_stance_feet(trajectory, t, measurement)
        com_task = self._tasks.com_task
        com_task.target_world = np.array([*np.array(com_task.target_world)[:2], self._height_change.at(t)])
        omega = math.sqrt(9.81 / self._generator_com_height())
        zmp = np.array(trajectory.get_p_world_ZMP(t, omega)[:2])
        offset = self.stabilizer.update(self.dt, zmp, measurement.wrench, measurement.cop, walking=True)
        if measurement.centre_of_mass is not None:
            planned = CentreOfMassMotion(np.array(trajectory.get_p_world_CoM(t)), np.array(trajectory.get_v_world_CoM(t)))
            offset = offset + self._dcm.shift(measurement.centre_of_mass, planned, omega, self._walk_time)
        com_task.target_world = np.array(com_task.target_world) + np.array([offset[0], offset[1], 0.0])
        self._track_support(trajectory, t, measurement)
        self._walk_time += self.dt

    def _hold_stance_feet(self, trajectory: placo.WPGTrajectory, t: float, measurement: Measurement) -> None:
        """Feet on the ground are held where they are measured, not where they were planned:
        the IK then moves the swing foot to its target in odom from the real stance foot (a
        stance foot that slipped would otherwise carry its error into the next landing)."""
        on_ground = (Foot.LEFT, Foot.RIGHT) if trajectory.support_is_both(t) else (Foot(str(trajectory.support_side(t))),)
        for foot in on_ground:
            task = self._tasks.left_foot_task if foot is Foot.LEFT else self._tasks.right_foot_task
            task.T_world_frame = level_frame(measurement.soles[foot])

    def _replan_stop(self, t: float) -> None:
        """Re-plan the pattern from ``t`` to stop at the next stable stance: the foot in the air
        (if any) lands on its target, the other steps beside it, both stand (supports built by
        placo's ``make_supports`` over [trailing, leading, beside]; the first one carries the
        elapsed ratio, as placo's own ``replan_supports`` does)."""
        self._stopping = False
        trajectory = self._walk_trajectory()
        current = trajectory.get_support(t)
        if current.end:  # already ending at a stance
            return
        if current.start:  # no foot has moved yet: stand right here
            self._stand_here()
            return
        if current.is_both():
            leading_side = trajectory.get_next_support(t, 1).side()
        else:
            leading_side = placo.HumanoidRobot.other_side(current.side())
        trailing_side = placo.HumanoidRobot.other_side(leading_side)
        leading_frame = (current.footstep_frame(leading_side) if current.is_both()
                         else trajectory.get_next_support(t, 1).footstep_frame(leading_side))
        trailing = self._footstep(trailing_side, current.footstep_frame(trailing_side))
        leading = self._footstep(leading_side, leading_frame)
        beside = self._footstep(trailing_side, self._beside(leading_frame, trailing_side))
        supports = placo.FootstepsPlanner.make_supports([trailing, leading, beside], current.t_start, False, True, True)
        if current.is_both():
            supports = supports_from(list(supports)[1:])
        first = supports[0]
        first.elapsed_ratio = current.elapsed_ratio + (t - current.t_start) / (
            self._support_duration(current) * current.time_ratio)
        first.time_ratio = current.time_ratio
        replanned = self._generator.replan(supports, trajectory, t)
        if replanned.replan_success:
            self._trajectory = replanned
        else:  # try again at the next tick (the pattern may not be solvable at this instant)
            self._stopping = True
            self.steps_planned = self.steps_landed + (1 if current.is_both() else 2)

    def _footstep(self, side: placo.HumanoidRobot_Side, frame: np.ndarray) -> placo.Footstep:
        step = placo.Footstep(self.profile.walking.foot_width, self.profile.walking.foot_length)
        step.side, step.frame = side, np.array(frame, dtype=float)
        return step

    def _beside(self, frame: np.ndarray, side: placo.HumanoidRobot_Side) -> np.ndarray:
        """The sole frame beside ``frame`` at the standing foot separation, towards ``side``."""
        lateral = self.profile.walking.foot_separation * (1.0 if side == placo.HumanoidRobot_Side.left else -1.0)
        beside = np.array(frame, dtype=float)
        beside[:3, 3] = beside[:3, 3] + beside[:3, :3] @ np.array([0.0, lateral, 0.0])
        return beside

    def _support_duration(self, support: placo.Support) -> float:
        gait = self.gait
        double = gait.double_support_ratio * gait.single_support_s
        if not support.is_both():
            return gait.single_support_s
        return double * gait.start_end_ratio if (support.start or support.end) else double

    def _generator_com_height(self) -> float:
        return float(self._walk_trajectory().get_p_world_CoM(0.0)[2])

    def _track_support(self, trajectory: placo.WPGTrajectory, t: float, measurement: Measurement) -> None:
        """A single support that ends is a landing; one that begins re-anchors the model on
        the measured sole it stands on."""
        side = None if trajectory.support_is_both(t) else str(trajectory.support_side(t))
        if side != self._support_side and self._support_side is not None:
            self.steps_landed += 1
        if side is not None:
            self._anchor_foot = Foot(side)
        # anchored every tick on the foot that carries it (the last stance foot in double
        # support): unanchored, the model drifted 25 cm from the robot in a final stance
        self._anchor(self._anchor_foot, measurement.soles[self._anchor_foot])
        if measurement.trunk_rotation is not None and self.gait.imu_feedback:
            self.robot.update_from_imu(np.asarray(measurement.trunk_rotation, dtype=float))
        self._support_side = side

    def _anchor(self, foot: Foot, measured_sole: np.ndarray) -> None:
        """Place the model so that ``foot`` is where it was measured (flattened on the floor)."""
        self.robot.update_support_side(foot.value)
        self.robot.set_T_world_support(placo.flatten_on_floor(np.asarray(measured_sole, dtype=float)))
        self.robot.ensure_on_floor()

