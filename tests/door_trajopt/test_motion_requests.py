"""From a motion request to a library job without ROS: refusals name what is wrong or missing
(and are the only TrajoptError answered as bad input), the arm follows from hinge and opening,
and a plan's outcome carries what the FSM and the report read."""

from __future__ import annotations

import json

import numpy as np
import pytest
from door_scenes import talos_kinematics

from door_contract.errors import ContractError
from door_contract.payloads import (
    DoorEstimate,
    MotionFigures,
    MotionRequest,
    OutcomeStatus,
    PlanningOutcome,
    decode,
    encode,
)
from door_contract.vocabulary import Backend, DoorOpening, HingeSide, Motion, Side
from door_trajopt.library import MotionLibrary, MotionPlan
from door_trajopt.problem import TrajoptError
from door_trajopt.requests import PlanningRefused, Snapshot, motion_job, planning_outcome
from door_trajopt.result import OptimizationResult, Outcome

# base at (-0.5, -0.12) facing +x, door plane x = 0, left hinge: the footstep planner's stand pose
ESTIMATE = DoorEstimate(1.0, "odom", (-0.06, -0.321, 0.91), (-1.0, 0.0, 0.0), HingeSide.LEFT, 0.914,
                        ((0.0, 0.457, 0.01), (0.0, -0.457, 0.01), (0.0, -0.457, 2.09), (0.0, 0.457, 2.09)),
                        1.0, 10, "automatic")
BASE = np.eye(4)
BASE[:3, 3] = -0.5, -0.12, 1.0


@pytest.fixture(scope="module")
def kinematics():
    return talos_kinematics()


def _snapshot(kinematics, estimate=ESTIMATE, joints=True, base=True) -> Snapshot:
    positions = {name: 0.0 for name in kinematics.joint_names} if joints else None
    return Snapshot(positions, BASE.copy() if base else None, estimate)


def _job(kinematics, request, snapshot):
    return motion_job(request, snapshot, kinematics, MotionLibrary().options, Backend.SQP, 0.1)


@pytest.mark.parametrize("request_, snapshot_args, reason", [
    (MotionRequest(2, "approach_handle", DoorOpening.PUSH), {"estimate": None}, "no door estimate yet"),
    (MotionRequest(3, "approach_handle", DoorOpening.PUSH, door_stamp=2.5), {"estimate": None},
     "door estimate of stamp 2.500 s was not received"),
    (MotionRequest(4, "approach_handle", DoorOpening.PUSH), {"joints": False}, "no valid joint states / odometry yet"),
    (MotionRequest(5, "approach_handle", DoorOpening.PUSH), {"base": False}, "no valid joint states / odometry yet"),
])
def test_a_request_that_cannot_be_planned_is_refused_with_the_reason(kinematics, request_, snapshot_args, reason):
    with pytest.raises(PlanningRefused, match=reason) as refused:
        _job(kinematics, request_, _snapshot(kinematics, **snapshot_args))
    assert isinstance(refused.value, TrajoptError) and not isinstance(refused.value, ValueError)


@pytest.mark.parametrize("field, value", [("motion", "dance"), ("backend", "rrt")])
def test_an_unknown_motion_or_backend_is_refused_by_the_contract_naming_the_known_ones(field, value):
    """The vocabulary is the contract's (door_contract.vocabulary): a request naming anything
    else never decodes, so it never reaches the core (the node answers it REJECTED)."""
    text = encode(MotionRequest(1, Motion.APPROACH_HANDLE, DoorOpening.PUSH, Backend.CHOMP))
    assert decode(MotionRequest, text).backend is Backend.CHOMP
    assert decode(MotionRequest, text.replace('"backend": "chomp"', '"backend": null')).backend is None
    bad = json.loads(text) | {field: value}
    with pytest.raises(ContractError, match=f"unknown {field} '{value}'; use one of") as refused:
        decode(MotionRequest, json.dumps(bad))
    assert ("tuck_arm" if field == "motion" else "chomp") in str(refused.value)


def test_an_estimate_with_a_bad_normal_is_refused(kinematics):
    tilted = DoorEstimate(**{**ESTIMATE.__dict__, "normal": (0.0, 0.0, 1.0)})
    with pytest.raises(PlanningRefused, match="not horizontal"):
        _job(kinematics, MotionRequest(7, "approach_handle", DoorOpening.PUSH), _snapshot(kinematics, tilted))


def test_the_job_takes_the_grasping_arm_and_the_default_backend(kinematics):
    job = _job(kinematics, MotionRequest(8, "approach_handle", DoorOpening.PUSH), _snapshot(kinematics))
    assert job.motion is Motion.APPROACH_HANDLE and job.backend is Backend.SQP
    assert job.side is Side.RIGHT                                  # the handle on the base's right
    assert job.start.shape == (len(job.setup.chain.joint_names),) and np.allclose(job.start, 0.0)
    chomp = _job(kinematics, MotionRequest(9, "approach_handle", DoorOpening.PUSH, backend="chomp"),
                 _snapshot(kinematics))
    assert chomp.backend is Backend.CHOMP


def test_the_job_takes_the_hand_the_fsm_names_and_the_other_for_the_other_arms_motions(kinematics):
    """Once an approach chose the hand, the FSM names it (after a pull door's doorway walk the
    handle's side of the base no longer tells)."""
    named = _job(kinematics, MotionRequest(10, "approach_handle", DoorOpening.PUSH, hand=Side.LEFT),
                 _snapshot(kinematics))
    assert named.side is Side.LEFT
    tuck = _job(kinematics, MotionRequest(11, "tuck_arm", DoorOpening.PULL, hand=Side.RIGHT), _snapshot(kinematics))
    assert tuck.side is Side.LEFT  # the blocking arm: the other one


def test_a_request_naming_an_unknown_hand_is_refused_by_the_contract_and_a_known_one_decodes():
    text = encode(MotionRequest(1, Motion.TURN_HANDLE, DoorOpening.PUSH, hand=Side.LEFT))
    assert decode(MotionRequest, text).hand is Side.LEFT
    assert decode(MotionRequest, encode(MotionRequest(1, Motion.TURN_HANDLE, DoorOpening.PUSH))).hand is None
    with pytest.raises(ContractError, match="unknown hand 'middle'; use one of"):
        decode(MotionRequest, json.dumps(json.loads(text) | {"hand": "middle"}))


def test_an_outcome_without_a_plan_carries_the_stamp_only():
    outcome = planning_outcome(3, OutcomeStatus.REJECTED, "no door estimate", None, Backend.SQP, 42)
    assert outcome == PlanningOutcome(3, OutcomeStatus.REJECTED, "no door estimate", stamp_ns=42)


def test_a_diverged_plans_figures_go_out_as_null_without_its_trajectory():
    """Issue #12: a NaN cost must not stop the outcome (encode refuses NaN)."""
    trajectory = np.full((3, 2), np.nan)
    result = OptimizationResult(trajectory, Outcome.INFEASIBLE, np.nan, np.inf, "door", 40, 0.1)
    plan = MotionPlan(Motion.TURN_HANDLE, result, None, (np.nan, 0.0), 2, 0.3, np.zeros((3, 2)))
    outcome = planning_outcome(5, OutcomeStatus.FAILURE, "diverged", plan, Backend.CHOMP)
    assert outcome.door_angle is None and outcome.stamp_ns == -1 and outcome.planning_time_s == 0.3
    assert outcome.motion == MotionFigures(None, None, 40, 2, 0.0, Backend.CHOMP)
    assert decode(PlanningOutcome, encode(outcome)) == outcome


@pytest.mark.slow
def test_the_outcome_of_a_plan_carries_what_the_fsm_and_the_report_read(kinematics):
    job = _job(kinematics, MotionRequest(10, "approach_handle", DoorOpening.PUSH), _snapshot(kinematics))
    plan = MotionLibrary().plan(job.motion, job.setup, job.start, job.backend)
    outcome = planning_outcome(10, OutcomeStatus.SUCCESS, "", plan, Backend.SQP, 7)
    figures = outcome.motion
    assert outcome.stamp_ns == 7 and outcome.door_angle is not None and figures is not None
    assert figures.backend is Backend.SQP and figures.attempts == plan.attempts and figures.duration_s > 0.0
    assert figures.cost is not None and figures.max_violation is not None and figures.iterations > 0
    if plan.path is not None:
        k = len(figures.joint_names)
        assert np.asarray(figures.optimised).shape[1] == k == np.asarray(figures.initial_guess).shape[1]
    assert decode(PlanningOutcome, encode(outcome)) == outcome


def test_the_com_is_held_over_the_feet_in_the_horizontal_plane_of_the_measured_base(kinematics):
    """The physical base is never quite upright: a job takes the measured tilt, and its support
    polygon and CoM are the world's horizontal projections (turned to the base's heading), not
    the base frame's. Pitched 0.05 rad, the soles ~1 m below the base move ~5 cm in the base
    frame against the CoM (seed 5 trial 13's tuck was refused for 2 cm of that)."""
    pitch, yaw = 0.05, 0.7
    c, s = np.cos(pitch), np.sin(pitch)
    pitched = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    turned = np.array([[np.cos(yaw), -np.sin(yaw), 0.0], [np.sin(yaw), np.cos(yaw), 0.0], [0.0, 0.0, 1.0]])
    base = BASE.copy()
    base[:3, :3] = turned @ pitched
    snapshot = Snapshot({name: 0.0 for name in kinematics.joint_names}, base, ESTIMATE)
    setup = motion_job(MotionRequest(6, "approach_handle", DoorOpening.PUSH), snapshot, kinematics,
                       MotionLibrary().options, Backend.SQP, 0.1).setup
    np.testing.assert_allclose(setup.level, pitched, atol=1e-12)  # the heading taken out, the tilt kept
    chain, walking = setup.chain, kinematics.profile.walking
    unturn = turned.T
    corners = np.array([(unturn @ (base @ kinematics.frame_pose(chain.body_q, sole)
                                   @ np.array([dx, dy, 0.0, 1.0]))[:3])[:2]
                        for sole in kinematics.profile.feet.values()
                        for dx in (-walking.foot_length / 2, walking.foot_length / 2)
                        for dy in (-walking.foot_width / 2, walking.foot_width / 2)])
    horizontal = corners - (unturn @ base[:3, 3])[:2]  # relative to the base, in the world's horizontal plane
    np.testing.assert_allclose(setup.support_polygon, [horizontal[:, 0].min(), horizontal[:, 0].max(),
                                                       horizontal[:, 1].min(), horizontal[:, 1].max()], atol=1e-9)
    upright = motion_job(MotionRequest(7, "approach_handle", DoorOpening.PUSH), _snapshot(kinematics), kinematics,
                         MotionLibrary().options, Backend.SQP, 0.1).setup
    assert setup.support_polygon[0] == pytest.approx(upright.support_polygon[0] - 0.05, abs=0.01)  # ~1 m × 0.05
