"""From a motion request to a motion library job, and from its plan to the outcome's
details, without ROS.

The node converts messages and calls these: the motion, backend and arm a request names,
the arm chain at the measured joint positions, the door model in the base frame, and the
summary a :class:`~door_contract.payloads.PlanningOutcome` carries (with the initial guess
and the optimised trajectory for the report's before/after plot, [Zucker 2013] Fig. 4).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from door_contract.door_estimates import requested_estimate_problem
from door_contract.payloads import DoorEstimate, MotionRequest
from door_contract.vocabulary import Backend, DoorOpening, Motion, Side
from door_robot.kinematics import RobotKinematics
from door_trajopt.chain import ArmChain
from door_trajopt.door_model import door_model_from_estimate
from door_trajopt.library import MotionPlan
from door_trajopt.motions import MotionOptions, MotionSetup, start_door_for, support_polygon
from door_trajopt.problem import TrajoptError

__all__ = ["MotionJob", "PlanningRefused", "Snapshot", "motion_job", "outcome_details"]


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
    side = hand.other if motion.uses_other_arm else hand
    chain = ArmChain(kinematics, side, body_q)
    door = door_model_from_estimate(estimate, np.linalg.inv(snapshot.base_pose),
                                    push=request.opening is DoorOpening.PUSH, lever_radius=lever_radius)
    setup = MotionSetup(chain, door, estimate.width, support_polygon(chain),
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


def outcome_details(plan: MotionPlan | None, backend: str, proposal_stamp_ns: int = -1) -> dict[str, Any]:
    """The details of a request's PlanningOutcome: the proposal's stamp and, with a plan, its
    cost, violation, iterations, guesses, final door angle, duration and backend, and the
    chain's initial guess and optimised trajectory (rounded)."""
    details: dict[str, Any] = {"stamp_ns": proposal_stamp_ns}
    if plan is None:
        return details
    result = plan.result
    details.update(cost=round(result.cost, 6), max_violation=float(f"{result.max_violation:.3g}"),
                   iterations=result.iterations, attempts=plan.attempts, door_angle=round(plan.final_door[0], 5),
                   duration_s=round(float(plan.path.times[-1]), 3) if plan.path else 0.0, backend=backend)
    if plan.path is not None and plan.initial_guess is not None:
        k = len(plan.path.joint_names)
        details.update(joint_names=list(plan.path.joint_names),
                       initial_guess=np.round(plan.initial_guess[:, :k], 4).tolist(),
                       optimised=np.round(plan.result.trajectory[:, :k], 4).tolist())
    return details
