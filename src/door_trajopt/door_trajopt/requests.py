"""From a motion request to a motion library job, and from its plan to the request's
PlanningOutcome, without ROS.

The node converts messages and calls these: the motion, backend and arm a request names,
the arm chain at the measured joint positions, the door model in the base frame, and the
figures a :class:`~door_contract.payloads.PlanningOutcome` carries (with the initial guess
and the optimised trajectory for the report's before/after plot, [Zucker 2013] Fig. 4).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from door_contract.door_estimates import requested_estimate_problem
from door_contract.payloads import (
    DoorEstimate,
    MotionFigures,
    MotionRequest,
    OutcomeStatus,
    PlanningOutcome,
    finite_or_none,
)
from door_contract.vocabulary import Backend, DoorOpening, Motion, Side
from door_robot.kinematics import RobotKinematics
from door_trajopt.chain import ArmChain
from door_trajopt.door_model import door_model_from_estimate
from door_trajopt.library import MotionPlan
from door_trajopt.motions import MotionOptions, MotionSetup, start_door_for
from door_trajopt.problem import TrajoptError

__all__ = ["MotionJob", "PlanningRefused", "Snapshot", "grasping_hand", "motion_figures", "motion_job",
           "planning_outcome"]


class PlanningRefused(TrajoptError):
    """A request that cannot be planned from its inputs (unknown motion or backend, no usable
    door estimate, no joint states or odometry yet): answered REJECTED with this reason. Any
    other :class:`~door_trajopt.problem.TrajoptError` of a built problem is a bug."""


@dataclass(frozen=True)
class Snapshot:
    """The inputs a request is planned from, taken when it arrives (the measured state):
    joint positions by name (rad), the base pose (4×4 in ``odom``), the named door estimate."""

    joint_positions: dict[str, float] | None
    base_pose: np.ndarray | None
    estimate: DoorEstimate | None


@dataclass(frozen=True)
class MotionJob:
    """What :meth:`~door_trajopt.library.MotionLibrary.plan` is called with for a request."""

    motion: Motion
    backend: Backend
    side: Side  # the arm that moves
    setup: MotionSetup
    start: np.ndarray  # the chain's configuration at the measured joint positions


def motion_job(request: MotionRequest, snapshot: Snapshot, kinematics: RobotKinematics, options: MotionOptions,
               default_backend: Backend, lever_radius: float) -> MotionJob:
    """The library job of ``request``: raises :class:`PlanningRefused` naming what is wrong or
    missing. The grasping arm is the request's (the FSM names the one its approach moved), or,
    for the approach, the one on the handle's side (:func:`grasping_hand`: after a pull door's
    doorway walk the robot faces the hinge and that rule no longer holds); motions that use the
    other arm (blocking the door, tucking) take the other one."""
    motion = Motion(request.motion)  # decoding the request refused any other
    estimate = snapshot.estimate
    problem = requested_estimate_problem(estimate, request.door_stamp)
    if problem or estimate is None:
        raise PlanningRefused(problem or "no door estimate")
    if snapshot.joint_positions is None or snapshot.base_pose is None:
        raise PlanningRefused("no valid joint states / odometry yet")
    backend = Backend(request.backend or default_backend)
    known = kinematics.joint_names
    body_q = kinematics.configuration({k: v for k, v in snapshot.joint_positions.items() if k in known})
    hand = request.hand or grasping_hand(estimate, snapshot.base_pose)
    side = hand.other if motion.moves_other_arm(request.opening) else hand
    chain = ArmChain(kinematics, side, body_q)
    door = door_model_from_estimate(estimate, np.linalg.inv(snapshot.base_pose),
                                    push=request.opening is DoorOpening.PUSH, lever_radius=lever_radius)
    setup = MotionSetup.measured(chain, door, estimate.width, snapshot.base_pose[:3, :3],
                                 start_door_for(motion, request.door_angle, options))
    return MotionJob(motion, backend, side, setup, chain.chain_of(body_q))


def grasping_hand(estimate: DoorEstimate, base_pose: np.ndarray) -> Side:
    """The arm on the handle's side of the base (the handle's y in the base frame, ``base_pose``
    4×4 in the estimate's frame): the latch-side hand of a robot facing a push door from its
    stand pose (the handle 0.20 m towards the latch), the hinge-side hand of one facing a pull
    door from beyond its latch edge, and the hinge-side hand of one standing sideways, its back
    to the hinge (:mod:`footstep_planner.push_passage`) — whatever the stance, the hand nearest
    the handle."""
    handle = np.linalg.inv(base_pose) @ np.append(np.asarray(estimate.handle_position, dtype=float), 1.0)
    return Side.LEFT if handle[1] >= 0.0 else Side.RIGHT


def planning_outcome(request_id: int, status: OutcomeStatus, reason: str, plan: MotionPlan | None,
                     backend: Backend, proposal_stamp_ns: int = -1) -> PlanningOutcome:
    """A request's PlanningOutcome: the proposal's stamp (-1: nothing proposed) and, with a plan
    (converged or not), its planning time, the hinge angle it leaves the door at and its figures."""
    if plan is None:
        return PlanningOutcome(request_id, status, reason, stamp_ns=proposal_stamp_ns)
    return PlanningOutcome(request_id, status, reason, plan.planning_time_s, proposal_stamp_ns,
                           finite_or_none(round(float(plan.final_door[0]), 5)),
                           motion=motion_figures(plan, backend))


def motion_figures(plan: MotionPlan, backend: Backend) -> MotionFigures:
    """A plan's cost, violation, iterations, guesses, duration and backend (rounded; not finite:
    None) and, with a trajectory, the chain's initial guess and optimised trajectory."""
    result = plan.result
    figures = MotionFigures(finite_or_none(round(float(result.cost), 6)),
                            finite_or_none(float(f"{result.max_violation:.3g}")), int(result.iterations),
                            plan.attempts, round(float(plan.path.times[-1]), 3) if plan.path else 0.0, backend)
    if plan.path is None or plan.initial_guess is None:
        return figures
    k = len(plan.path.joint_names)
    guess, optimised = plan.initial_guess[:, :k], result.trajectory[:, :k]
    if not (np.all(np.isfinite(guess)) and np.all(np.isfinite(optimised))):
        return figures  # a diverged trajectory: nothing to plot, and JSON has no NaN
    return replace(figures, joint_names=tuple(plan.path.joint_names), initial_guess=_rows(guess),
                   optimised=_rows(optimised))


def _rows(array: np.ndarray) -> tuple[tuple[float, ...], ...]:
    """The rows of ``array`` rounded to 10⁻⁴ (rad), as tuples."""
    return tuple(tuple(row) for row in np.round(array, 4).tolist())
