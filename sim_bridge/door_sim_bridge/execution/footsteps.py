"""Walking a footstep plan: physically with the walking controller, or glided (kinematic).

Validation first (any failure → REJECTED, nothing moves): a crouch the walker can take
(:func:`~door_robot.crouch.crouch_problem`), a non-empty plan whose feet alternate
left, right, … starting with the left foot (the contract's convention: even index = left),
finite poses, and every step within the profile's walking limits, measured — as the footstep
planner does — in the frame of the support foot (the other foot's latest placement, or its
current pose for the first step): forward/backward reach |dx| ≤ max_stride, lateral distance
towards the swing foot's own side in [foot_width, foot_separation + max_side_step] (the legs
never cross), |dyaw| ≤ max_turn.

Physical robot (the default): the world's walking controller walks the plan
(:meth:`~door_sim_bridge.world.world.DoorWorld.walk`); the execution watches it — a fall ends
it with FELL, a hand that slips or a link in the wall or frame with FAILURE (the walk stops at
the next stable stance) — and, once the base has come to rest (:data:`STILL_RADIUS` for
:data:`STILL_TIME`, at most :data:`STILL_TIMEOUT` after the walk: a walk ending in a 90° turn
left the pelvis rocking ±8 cm for 4 s, and an arm motion planned from it missed the handle by
10 cm), judges where the soles ended against the plan's last two placements (``landing_tolerance``).

Kinematic robot (fast unit tests): each footstep takes ``step_duration`` of simulated time. During it the base glides from
the stance before the step to the stance after it — the midpoint of the two soles with their
mean heading, at the nominal base height and offset — along a cosine-eased blend
s(τ) = (1 - cos πτ) / 2 (zero velocity at both ends, as a quasi-static walker pauses in double
support). The legs stay in their posture: the soles move with the base, so the world's sole
links report the stance *centre* and heading exactly, and the individual soles at the nominal
separation. If a robot link penetrates the wall or door frame deeper than ``collision_depth``
the walk stops with FAILURE (the real robot would have hit it).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping, Sequence

import numpy as np

from door_contract.converters.footsteps import FootPlacement, foot_of_index
from door_contract.geometry import planar_pose, yaw_of
from door_contract.payloads import OutcomeStatus
from door_contract.vocabulary import Foot
from door_robot.crouch import crouch_problem
from door_robot.profile import WalkingLimits
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.execution.base import Execution
from door_sim_bridge.walking.gait import smooth_blend
from door_sim_bridge.world.world import DoorWorld

__all__ = ["STILL_RADIUS", "STILL_TIME", "STILL_TIMEOUT", "FootstepExecution", "blend_poses", "relative_step",
           "smooth_blend", "validate_footsteps", "wrap_angle"]

LIMIT_TOLERANCE = 0.005  # m or rad: planners round to their grids; a few mm more is still a safe step
LANDING_TOLERANCE = 0.05  # m: a physical walk ending farther than this from its plan is a FAILURE
STILL_RADIUS = 0.01  # m: the base counts as at rest while it stays this close to where it was ...
STILL_TIME = 0.5  # s ... for this long
STILL_TIMEOUT = 4.0  # s after the walking controller stood: the walk ends then, at rest or not


def wrap_angle(angle: float) -> float:
    """Angle in (-pi, pi]."""
    return math.atan2(math.sin(angle), math.cos(angle))


def relative_step(support: FootPlacement, swing: FootPlacement) -> tuple[float, float, float]:
    """(forward, outward, turn) of ``swing`` in ``support``'s frame.

    ``outward`` is the lateral offset towards the swing foot's own side (+y for a left foot).
    """
    c, s = math.cos(support.yaw), math.sin(support.yaw)
    dx, dy = swing.x - support.x, swing.y - support.y
    forward, lateral = c * dx + s * dy, -s * dx + c * dy
    outward = lateral if swing.foot is Foot.LEFT else -lateral
    return forward, outward, wrap_angle(swing.yaw - support.yaw)


def _step_problem(index: int, support: FootPlacement, swing: FootPlacement,
                  limits: WalkingLimits) -> str | None:
    forward, outward, turn = relative_step(support, swing)
    where = f"step {index} ({swing.foot.value} foot)"
    widest = limits.foot_separation + limits.max_side_step
    if abs(forward) > limits.max_stride + LIMIT_TOLERANCE:
        return f"{where}: stride {forward:+.3f} m exceeds max_stride {limits.max_stride:.3f} m"
    if outward < limits.foot_width - LIMIT_TOLERANCE:
        return (f"{where}: soles only {outward:.3f} m apart sideways (at least the foot width "
                f"{limits.foot_width:.3f} m, or the legs cross)")
    if outward > widest + LIMIT_TOLERANCE:
        return f"{where}: soles {outward:.3f} m apart sideways, more than {widest:.3f} m"
    if abs(turn) > limits.max_turn + LIMIT_TOLERANCE:
        return f"{where}: turn {turn:+.3f} rad exceeds max_turn {limits.max_turn:.3f} rad"
    return None


def _finite(*values: object) -> bool:
    return all(isinstance(v, numbers.Real) and not isinstance(v, bool) and math.isfinite(v)
               for v in values)


def validate_footsteps(steps: Sequence[FootPlacement], current: Mapping[Foot, FootPlacement],
                       limits: WalkingLimits) -> str | None:
    """The reason to reject the plan, or None when it may be walked."""
    if not steps:
        return "footstep plan is empty"
    feet = dict(current)
    for index, step in enumerate(steps):
        if not isinstance(step, FootPlacement):
            return f"step {index} is not a FootPlacement"
        if step.foot is not foot_of_index(index):
            return (f"step {index} is the {getattr(step.foot, 'value', step.foot)} foot; feet must "
                    f"alternate starting with the left foot")
        if not _finite(step.x, step.y, step.yaw):
            return f"step {index} contains NaN, infinity or a non-number"
        other = Foot.RIGHT if step.foot is Foot.LEFT else Foot.LEFT
        problem = _step_problem(index, feet[other], step, limits)
        if problem is not None:
            return problem
        feet[step.foot] = step
    return None


def blend_poses(start: np.ndarray, end: np.ndarray, weight: float) -> np.ndarray:
    """Planar blend of two base poses: position linearly, heading along the shorter arc."""
    position = (1.0 - weight) * start[:3, 3] + weight * end[:3, 3]
    heading = yaw_of(start) + weight * wrap_angle(yaw_of(end) - yaw_of(start))
    return planar_pose(position[0], position[1], heading, position[2])


class FootstepExecution(Execution):
    """One footstep plan on the world's robot (see the module docstring)."""

    def __init__(self, world: DoorWorld, steps: Sequence[FootPlacement], crouch: float = 0.0) -> None:
        super().__init__(world)
        self.steps, self.crouch = tuple(steps), crouch
        self._feet = world.foot_placements()
        reason = validate_footsteps(self.steps, self._feet, world.profile.walking) or crouch_problem(crouch)
        if reason:
            self._reject(reason)
        self._step_duration = world.config.execution.step_duration
        self._index = 0
        self._from_pose = np.eye(4)
        self._to_pose = np.eye(4)
        self._problem_reason = ""  # why the walk was stopped from inside (collision, slip)
        self._slipped = False
        self._stood_at: float | None = None  # sim time the walking controller stood (physical)
        self._rest: tuple[float, np.ndarray] | None = None  # since when, and where, the base is at rest

    @property
    def steps_done(self) -> int:
        """Footsteps completed so far."""
        balance = self.world.balance  # not None exactly when the world is physical
        return balance.controller.steps_landed if balance is not None else self._index

    def _on_start(self) -> None:
        if not self.world.physical:
            self._begin_step()
            return
        try:
            self.world.walk(self.steps, self.crouch)
        except SimulationError as error:
            self._finish(OutcomeStatus.FAILURE, f"the walking controller refused the plan: {error}")

    def _command_now(self) -> None:
        if self.done:
            return
        problem = self._problem()
        if problem is not None and not self.world.physical:
            self._finish(OutcomeStatus.FAILURE, problem[0], slipped=problem[1])
            return
        if self.world.physical:
            self._command_physical(problem)
        else:
            self._command_kinematic()

    def _problem(self) -> tuple[str, bool] | None:
        """Why the walk must stop (reason, slipped), or None."""
        penetration, link = self.world.scene_contact()
        if penetration > self.world.config.execution.collision_depth:
            return (f"robot hit the wall or door frame during step {self.steps_done} ({link}, "
                    f"{penetration:.3f} m deep)", False)
        slip = self._slip_since_start()
        if slip is not None:
            return f"grasp slipped at t = {slip.time:.2f} s while walking", True
        return None

    def _command_physical(self, problem: tuple[str, bool] | None) -> None:
        """Watch the walking controller; on a problem, stop at the next stable stance."""
        if problem is not None and not self._problem_reason:
            self._problem_reason, self._slipped = problem
            self.world.stop_walking()
        if self.world.walking:
            return
        if self._problem_reason:
            self._finish(OutcomeStatus.FAILURE, self._problem_reason, slipped=self._slipped)
        elif self.stop_reason is not None:
            self._finish(OutcomeStatus.STOPPED, f"stopped after step {self.steps_done} of {len(self.steps)}: "
                                                f"{self.stop_reason}")
        elif self._at_rest():
            self._judge_landing()

    def _at_rest(self) -> bool:
        """Whether the base has stayed within :data:`STILL_RADIUS` for :data:`STILL_TIME` (or
        :data:`STILL_TIMEOUT` has passed since the walking controller stood)."""
        now, where = self.world.time, self.world.base_pose()[:2, 3]
        if self._stood_at is None:
            self._stood_at = now
        if self._rest is None or np.linalg.norm(where - self._rest[1]) > STILL_RADIUS:
            self._rest = (now, where.copy())
        return now - self._rest[0] >= STILL_TIME or now - self._stood_at >= STILL_TIMEOUT

    def _judge_landing(self) -> None:
        feet = self.world.foot_placements()
        last = {step.foot: step for step in self.steps[-2:]}
        errors = {foot: math.hypot(feet[foot].x - step.x, feet[foot].y - step.y) for foot, step in last.items()}
        worst = max(errors, key=errors.__getitem__)
        if errors[worst] > LANDING_TOLERANCE:
            self._finish(OutcomeStatus.FAILURE, f"the {worst.value} sole ended {errors[worst]:.3f} m from its "
                                                f"planned placement (tolerance {LANDING_TOLERANCE:.3f} m)")
        else:
            self._finish(OutcomeStatus.SUCCESS)

    def _begin_step(self) -> None:
        step = self.steps[self._index]
        self._from_pose = self.world.base_pose()
        self._feet[step.foot] = step
        self._to_pose = self.world.base_pose_for_feet(self._feet[Foot.LEFT], self._feet[Foot.RIGHT])

    def _command_kinematic(self) -> None:
        tau = (self.elapsed - self._index * self._step_duration) / self._step_duration
        if tau >= 1.0:
            self.world.set_base_pose(self._to_pose)
            self._index += 1
            if self._index == len(self.steps):
                self._finish(OutcomeStatus.SUCCESS)
                return
            if self.stop_reason is not None:  # both feet down: the next stable stance
                self._finish(OutcomeStatus.STOPPED, f"stopped after step {self._index} of {len(self.steps)}: "
                                                    f"{self.stop_reason}")
                return
            self._begin_step()
            tau = (self.elapsed - self._index * self._step_duration) / self._step_duration
        step_time = self.world.config.time_step / self._step_duration
        self.world.set_base_pose(blend_poses(self._from_pose, self._to_pose, smooth_blend(tau + step_time)))

    def _on_stop(self) -> None:
        """Walking stops at the next stable stance. Physical: the walking controller lands the
        foot in the air and steps the other beside it; kinematic: the step in progress is
        finished (that walk has both feet down only between steps). See ``_command_now``."""
        self.world.stop_walking()

    def _hold(self) -> None:
        """Physical: end the walk at the next stable stance; kinematic: the base stays put."""
        self.world.stop_walking()
