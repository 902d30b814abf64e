"""Executing a joint trajectory with the robot's position motors.

Validation first (any failure → REJECTED with the reason, and nothing moves): a non-empty,
consistently shaped trajectory of known, distinct, movable joints; finite times, positions
(and velocities, if given); times ≥ 0 and strictly increasing; every position inside the URDF
limits; a first point at t = 0 no farther than ``start_tolerance`` from where the joints are;
no segment faster than ``velocity_limit_scale`` × the URDF velocity limit.

Interpolation: if the first point is later than t = 0 the current positions are prepended at
t = 0 (as ros2_control's joint_trajectory_controller does). Between points the command follows
a monotone cubic (PCHIP: it never overshoots the waypoints, so it stays inside the limits), or
a cubic Hermite spline when the points carry velocities. At every physics step the motors get
the position for the end of that step. After the last point the command is held for
``settle_time``; the outcome is SUCCESS if every joint is then within ``goal_tolerance`` of its
final position, else FAILURE naming the worst joint (e.g. an arm blocked by the door), and the
joints then hold where they are, as after a slip: a blocked arm does not go on straining
towards a goal it cannot reach while the next plan is made. The wrist of a hand that holds the
handle or touches the leaf or handle (its last joint above the hand) has ``held_wrist_tolerance``
instead: a turn or swing is planned on the *estimated* lever axis and hinge, the lever holds the
hand on its true arc, and the weak last wrist joint (TALOS: 6.6 N·m) is what gives way, 0.06-0.09 rad
for an estimate off by the detector's ~0.6 cm / 0.5° (the turn failed so in 4 of 20 sideways rig
doors); a pull door's leaf resting on the blocking hand held the same joint 0.05-0.14 rad off the
tuck's goal (5 of 6 rig doors stopped there). An arm joint of a hand the open door leans on (it
touches the leaf or handle without holding it, and the closer and wind press the leaf on it) that
ends beyond its tolerance while its motor pushes back towards the goal at full force has *yielded
to the door*: the hand went where it was sent and the door holds it off, so the execution
succeeds and its reason names the joint. The leaf on a tucked hand's fingertips (~50 N, the
closer and 2-3 N·m of wind) bent TALOS's wrist (``arm_left_6``/``_7``, 6.6 N·m) 0.36-0.64 rad and
held its elbow 0.051 rad off, and every repeat of the tuck failed alike. An arm held off by a
*closed* leaf is still a FAILURE: it is the arm that pushes (an arm blocked by the door). A grasp
slip during the motion stops it at once with FAILURE.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from scipy.interpolate import CubicHermiteSpline, PchipInterpolator

from door_contract.converters.trajectory import JointPath
from door_contract.payloads import OutcomeStatus
from door_sim_bridge.execution.base import Execution, ExecutionPhase
from door_sim_bridge.world.config import ExecutionConfig
from door_sim_bridge.world.robot import JointLimit
from door_sim_bridge.world.world import DoorWorld

__all__ = ["TrajectoryExecution", "validate_trajectory", "with_start_point"]

LIMIT_TOLERANCE = 1e-6  # rad
YIELD_EFFORT = 0.98  # × the motor's force: an arm joint pushing back this hard has yielded to the door


def _shape_problem(times: np.ndarray, names: tuple[str, ...], positions: np.ndarray,
                   velocities: np.ndarray | None) -> str | None:
    if times.ndim != 1 or times.size == 0:
        return f"trajectory times must be a non-empty vector, got shape {times.shape}"
    if positions.shape != (times.size, len(names)):
        return f"positions have shape {positions.shape}, expected {(times.size, len(names))}"
    if velocities is not None and velocities.shape != positions.shape:
        return f"velocities have shape {velocities.shape}, expected {positions.shape}"
    if not names:
        return "trajectory names no joints"
    if len(set(names)) != len(names):
        return "trajectory joint names are not unique"
    return None


def _value_problem(times: np.ndarray, names: tuple[str, ...], positions: np.ndarray,
                   velocities: np.ndarray | None) -> str | None:
    if not np.all(np.isfinite(times)):
        return "trajectory times contain NaN or infinity"
    bad = np.argwhere(~np.isfinite(positions))
    if bad.size:
        point, joint = bad[0]
        return f"position of {names[joint]} at point {point} is {positions[point, joint]} (not finite)"
    if velocities is not None and not np.all(np.isfinite(velocities)):
        return "trajectory velocities contain NaN or infinity"
    if times[0] < 0.0:
        return f"first time {times[0]:g} s is negative"
    steps = np.diff(times)
    if np.any(steps <= 0.0):
        point = int(np.argmax(steps <= 0.0)) + 1
        return (f"times must be strictly increasing: point {point} at {times[point]:g} s "
                f"follows {times[point - 1]:g} s")
    return None


def _limit_problem(names: tuple[str, ...], positions: np.ndarray,
                   limits: Mapping[str, JointLimit]) -> str | None:
    for column, name in enumerate(names):
        limit = limits[name]
        outside = np.flatnonzero(~((positions[:, column] >= limit.lower - LIMIT_TOLERANCE)
                                   & (positions[:, column] <= limit.upper + LIMIT_TOLERANCE)))
        if outside.size:
            point = int(outside[0])
            return (f"{name} at point {point} is {positions[point, column]:.4f} rad, outside its "
                    f"limits [{limit.lower:.4f}, {limit.upper:.4f}]")
    return None


def _speed_problem(times: np.ndarray, names: tuple[str, ...], positions: np.ndarray,
                   limits: Mapping[str, JointLimit], scale: float) -> str | None:
    speeds = np.abs(np.diff(positions, axis=0)) / np.diff(times)[:, None]
    for column, name in enumerate(names):
        allowed = scale * limits[name].velocity
        if allowed > 0.0 and speeds.size and np.max(speeds[:, column]) > allowed:
            segment = int(np.argmax(speeds[:, column]))
            return (f"{name} would move at {speeds[segment, column]:.2f} rad/s between "
                    f"{times[segment]:g} s and {times[segment + 1]:g} s (limit {allowed:.2f} rad/s)")
    return None


def validate_trajectory(times: np.ndarray, names: tuple[str, ...], positions: np.ndarray,
                        velocities: np.ndarray | None, limits: Mapping[str, JointLimit],
                        current: Mapping[str, float], config: ExecutionConfig,
                        commandable: frozenset[str] | None = None) -> str | None:
    """The reason to reject the trajectory, or None when it may be executed (``commandable``:
    the joints a trajectory may move, default all)."""
    problem = _shape_problem(times, names, positions, velocities)
    if problem is None:
        unknown = [name for name in names if name not in limits]
        if unknown:
            return f"unknown joint {unknown[0]!r} (not a movable joint of the robot)"
        balanced = [name for name in names if commandable is not None and name not in commandable]
        if balanced:
            return f"{balanced[0]} is a leg joint: the walking controller drives the legs"
        problem = (_value_problem(times, names, positions, velocities)
                   or _limit_problem(names, positions, limits))
    if problem is not None:
        return problem
    start = np.array([current[name] for name in names])
    full_times, full_positions = with_start_point(times, positions, start)
    if times[0] <= 0.0:
        worst = int(np.argmax(np.abs(positions[0] - start)))
        deviation = abs(positions[0, worst] - start[worst])
        if deviation > config.start_tolerance:
            return (f"first point (t = 0) puts {names[worst]} {deviation:.3f} rad from its current "
                    f"position (allowed {config.start_tolerance:.3f} rad)")
    return _speed_problem(full_times, names, full_positions, limits, config.velocity_limit_scale)


def with_start_point(times: np.ndarray, positions: np.ndarray,
                     start: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Prepend ``start`` at t = 0 when the trajectory begins later."""
    if times[0] <= 0.0:
        return times, positions
    return np.concatenate([[0.0], times]), np.vstack([start, positions])


class TrajectoryExecution(Execution):
    """One joint trajectory on the world's robot (see the module docstring)."""

    def __init__(self, world: DoorWorld, times: Sequence[float] | np.ndarray, joint_names: Sequence[str],
                 positions: Sequence[Sequence[float]] | np.ndarray,
                 velocities: Sequence[Sequence[float]] | np.ndarray | None = None) -> None:
        """Validate against the robot's current state; an invalid trajectory is REJECTED at once."""
        super().__init__(world)
        self._config = world.config.execution
        self._curve: PchipInterpolator | CubicHermiteSpline | None = None
        self._end_time = 0.0
        self.joint_names = tuple(str(name) for name in joint_names)
        try:
            self._times = np.atleast_1d(np.asarray(times, dtype=float))
            self._positions = np.asarray(positions, dtype=float)
            self._velocities = None if velocities is None else np.asarray(velocities, dtype=float)
        except (TypeError, ValueError) as error:
            self._reject(f"trajectory is not numeric arrays of points × joints ({error})")
            return
        reason = validate_trajectory(self._times, self.joint_names, self._positions, self._velocities,
                                     world.joint_limits(), world.joint_positions(), self._config,
                                     world.commandable_joints())
        if reason is not None:
            self._reject(reason)

    @classmethod
    def from_joint_path(cls, world: DoorWorld, path: JointPath) -> TrajectoryExecution:
        """From the contract's :class:`JointPath` (validated again here: it may be hand-made)."""
        return cls(world, path.times, path.joint_names, path.positions, path.velocities)

    @property
    def final_positions(self) -> dict[str, float]:
        return dict(zip(self.joint_names, self._positions[-1].tolist()))

    def _on_start(self) -> None:
        """Interpolate from where the joints are now (see the module docstring)."""
        start = np.array([self.world.joint_positions()[name] for name in self.joint_names])
        times, positions = with_start_point(self._times, self._positions, start)
        self._end_time = float(times[-1])
        if times.size < 2:
            return  # a single point at t = 0: hold it
        if self._velocities is None:
            self._curve = PchipInterpolator(times, positions, axis=0)
            return
        velocities = self._velocities
        if times.size != self._times.size:
            velocities = np.vstack([np.zeros(len(self.joint_names)), velocities])  # start at rest
        self._curve = CubicHermiteSpline(times, positions, velocities, axis=0)

    def _command_now(self) -> None:
        slip = self._slip_since_start()
        if slip is not None:
            self._hold()
            hand = f"{slip.side.value} " if slip.side is not None else ""
            self._finish(OutcomeStatus.FAILURE, f"{hand}grasp slipped at t = {slip.time:.2f} s", slipped=True)
            return
        lookahead = self.elapsed + self.world.config.time_step
        if lookahead < self._end_time:
            self.world.set_joint_targets(self._targets_at(lookahead))
            return
        self.world.set_joint_targets(self.final_positions)
        self.phase = ExecutionPhase.SETTLING
        if self.elapsed >= self._end_time + self._config.settle_time - 1e-9:
            self._judge()

    def _targets_at(self, time: float) -> dict[str, float]:
        values = self._positions[-1] if self._curve is None else self._curve(time)
        return dict(zip(self.joint_names, np.asarray(values, dtype=float).tolist()))

    def _judge(self) -> None:
        states = self.world.joint_states()
        reached = dict(zip(states.names, states.positions.tolist()))
        error = {name: reached[name] - goal for name, goal in self.final_positions.items()}
        tolerances = self._tolerances()
        excess = {name: abs(off) - tolerances[name] for name, off in error.items()}
        yielded = self._yielded(error, excess, dict(zip(states.names, states.efforts.tolist())))
        worst = max((name for name in excess if name not in yielded), key=excess.__getitem__, default=None)
        if worst is None or excess[worst] <= 0.0:
            self._finish(OutcomeStatus.SUCCESS, "; ".join(
                f"{name} yielded to the door {abs(error[name]):.3f} rad from its goal at full effort"
                for name in yielded))
        else:
            self._hold()  # a blocked arm must not go on straining towards its goal
            self._finish(OutcomeStatus.FAILURE, f"{worst} ended {abs(error[worst]):.3f} rad from its goal "
                                                f"(tolerance {tolerances[worst]:.3f} rad)")

    def _tolerances(self) -> dict[str, float]:
        """Each joint's goal tolerance: ``held_wrist_tolerance`` for the last wrist joint of a hand
        that holds the handle or touches the door, ``goal_tolerance`` for the rest."""
        world = self.world
        held = {world.robot.wrist_joint(side) for side in world.profile.arms
                if world.holding(side) or world.hand_touches_door(side)}
        return {name: self._config.held_wrist_tolerance if name in held else self._config.goal_tolerance
                for name in self.final_positions}

    def _yielded(self, error: Mapping[str, float], excess: Mapping[str, float],
                 efforts: Mapping[str, float]) -> list[str]:
        """The arm joints of the hands the door leans on (:meth:`DoorWorld.door_leans_on`) beyond
        their tolerance (``excess`` > 0) whose motors push back towards the goal (against
        ``error``, rad) at :data:`YIELD_EFFORT` × their force or more (``efforts``, N·m)."""
        robot = self.world.robot
        arms = {name for side in self.world.profile.arms if self.world.door_leans_on(side)
                for name in robot.arm_joints(side)} & set(excess)
        return sorted(name for name in arms if excess[name] > 0.0 and -error[name] * efforts[name] > 0.0
                      and abs(efforts[name]) >= YIELD_EFFORT * robot.motor_force(name))

    def _hold(self) -> None:
        if self.phase is not ExecutionPhase.PENDING:
            positions = self.world.joint_positions()
            self.world.set_joint_targets({name: positions[name] for name in self.joint_names})
