"""``door_passage_rig``: the door task without ROS, to study the physical walk through a doorway.

The graph takes ~3 min per door; this runs the same cores in one process in ~10 s: a perfect
detector (the sim's ground truth), the stand pose the footstep planner chooses, the motion
library's motions in the FSM's order (approach, grasp, turn, push | pull and block, release,
ready to walk), then the footstep planner's passage, walked by the physical robot. Each run
prints how it ended and which robot links struck the door hardest (in the walk through, or
while opening when it stopped there) — what issue #11 needs to know about a fall. ``--trials``
jitters the stand pose by up to ±2 cm and ±1° per trial: a single run of a balancing robot
proves little. ``--robot`` is the main job's robot option: the
sim's robot, the kinematics the motions are planned with, and the footstep planner's limits.

``--pull-passage`` chooses how a pull door is passed: ``facing`` and ``sideways`` are the
footstep planner's ``pull_passage`` values; ``tuck`` side-steps facing the hinge with the
blocking hand on the leaf to ``--tuck-at`` m before the door plane, brings that arm to the
walking posture (the leaf follows it and comes to rest on the front of the body, far from
its axis, instead of on the hand near it), and side-steps the rest: a study of a passage
the FSM does not run yet (issue #11).

    python -m door_bringup.passage_rig --robot g1 --openings push pull --hinges left right --trials 3
    python -m door_bringup.passage_rig --openings pull --pull-passage tuck --trials 5
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from dataclasses import dataclass, replace
from enum import Enum

import numpy as np

from door_bringup.robot_option import add_robot_argument, check_robot
from door_contract.converters.trajectory import JointPath
from door_contract.payloads import DoorEstimate, FootstepRequest, OutcomeStatus
from door_contract.vocabulary import DoorOpening, HingeSide, Side, grasp_hand
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_sim_bridge.execution import ExecutionResult, FootstepExecution, TrajectoryExecution
from door_sim_bridge.world import DoorConfig, DoorWorld, StanceConfig, WorldConfig
from door_trajopt.chain import ArmChain
from door_trajopt.door_model import door_model_from_estimate
from door_trajopt.library import Backend, MotionLibrary
from door_trajopt.motions import Motion, MotionSetup, start_door_for, support_polygon
from footstep_planner.footstep import Pose2D
from footstep_planner.legs import Leg
from footstep_planner.narrow import SIDEWAYS
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.parameters import PLANNER_PARAMETERS
from footstep_planner.proposal import contract_footsteps
from footstep_planner.requests import (
    GoalSettings,
    Snapshot,
    WalkGoal,
    WalkPlanners,
    WalkProblem,
    door_geometry_from_estimate,
    options_for_problem,
    planner_options,
    problem_for_request,
    snapshot_stance,
    stand_pose,
)

NODE_DEFAULTS = {spec.name: spec.default for spec in PLANNER_PARAMETERS}
"""The footstep planner node's default parameters (search settings and goal settings)."""
JITTER = np.array([0.02, 0.02, np.radians(1.0)])
"""Largest stand-pose error a trial adds: along the normal, along the wall (m), yaw (rad)."""
GRASP, RELEASE = "grasp", "release"
TUCK_DURATION = 2.0
"""Seconds the blocking arm takes to the walking posture in a tucked passage."""


class PullPassageStudy(Enum):
    """How the rig passes a pull door (see the module docstring)."""

    FACING = "facing"
    SIDEWAYS = "sideways"
    TUCK = "tuck"


@dataclass(frozen=True)
class PassageRun:
    """How one door ended: ``stage`` is the motion or "walk through" it ended in."""

    robot: str
    opening: DoorOpening
    hinge: HingeSide
    trial: int
    stage: str
    status: str
    reason: str
    door_angle: float  # rad, at the end
    strikes: tuple[tuple[str, float], ...]  # (robot link | door part, peak normal force N), hardest first

    def line(self) -> str:
        strikes = ", ".join(f"{name} {force:.0f} N" for name, force in self.strikes) or "none"
        return (f"{self.robot} {self.opening.value:4s} {self.hinge.value:5s} #{self.trial}: {self.stage}: {self.status}"
                f"{(' (' + self.reason + ')') if self.reason else ''}; door {self.door_angle:.2f} rad; "
                f"hardest contacts: {strikes}")


def perfect_estimate(world: DoorWorld) -> DoorEstimate:
    """The estimate the detector should publish, from the simulator's ground truth."""
    truth = world.door_ground_truth()
    return DoorEstimate(world.time, "odom", tuple(truth.handle_grasp_pose[:3, 3]), tuple(truth.normal),
                        world.config.door.hinge_side, truth.width, tuple(tuple(c) for c in truth.corners),
                        1.0, 10, "automatic")


def stand_world(door: DoorConfig, offset: tuple[float, float, float] = (0.0, 0.0, 0.0),
                robot: str = "talos") -> DoorWorld:
    """``robot`` at the stand pose the footstep planner chooses for ``door`` (plus ``offset``:
    along the door normal, along the wall, yaw), standing on the floor."""
    with DoorWorld(WorldConfig(robot_profile=robot, door=door)) as probe:
        estimate = perfect_estimate(probe)
    settings = GoalSettings.from_parameters(NODE_DEFAULTS)
    options = planner_options(robot, NODE_DEFAULTS)
    geometry = door_geometry_from_estimate(estimate, door.opening, 0.0, settings.handle_standoff)
    stand = stand_pose(geometry, options, settings)
    return DoorWorld(WorldConfig(robot_profile=robot, door=door, stance=StanceConfig(
        distance=-stand.x + offset[0], lateral_offset=stand.y + offset[1], yaw=offset[2])))


def motion_setup(world: DoorWorld, kinematics: RobotKinematics, estimate: DoorEstimate, hand: Side,
                 door_angles: tuple[float, float]) -> MotionSetup:
    """The motion library's set-up from the measured posture and the (pre-opening) estimate."""
    push = world.config.door.opening is DoorOpening.PUSH
    body_q = kinematics.configuration({name: value for name, value in world.joint_positions().items()
                                       if name in kinematics.joint_names})
    chain = ArmChain(kinematics, hand, body_q)
    door = door_model_from_estimate(estimate, np.linalg.inv(world.base_pose()), push=push)
    return MotionSetup(chain, door, estimate.width, support_polygon(chain), door_angles)


def opening_sequence(opening: DoorOpening) -> tuple[Motion | str, ...]:
    """The FSM's OPEN_DOOR sub-states as motions and grasp commands, in order."""
    swing = (Motion.PUSH_DOOR,) if opening is DoorOpening.PUSH else (Motion.PULL_DOOR, Motion.BLOCK_DOOR)
    return (Motion.APPROACH_HANDLE, GRASP, Motion.TURN_HANDLE, *swing, RELEASE, Motion.READY_TO_WALK)


def run_recording(world: DoorWorld, execution: FootstepExecution | TrajectoryExecution,
                  peaks: dict[str, float]) -> ExecutionResult | None:
    """Step ``execution`` to its end, keeping the peak normal force of every robot-door contact
    in ``peaks``; its result (None: it ended without one)."""
    while not execution.command():
        world.step()
        for name, force in world.door_contact_forces().items():
            peaks[name] = max(peaks.get(name, 0.0), force)
    return execution.result


def open_door(world: DoorWorld, kinematics: RobotKinematics, estimate: DoorEstimate,
              peaks: dict[str, float]) -> tuple[str, str, str]:
    """Run the opening sequence; (stage, status, reason) of the step it stopped in, or of the
    last; the contacts' peak forces go into ``peaks``."""
    opening = world.config.door.opening
    hand, library, door_angle = grasp_hand(estimate.hinge_side, opening), MotionLibrary(), 0.0
    for step in opening_sequence(opening):
        if step in (GRASP, RELEASE):
            answer = world.grasp(hand, step == GRASP)
            if not answer.success:
                return str(step), "failure", answer.message
            continue
        assert isinstance(step, Motion)
        side = hand.other if step is Motion.BLOCK_DOOR else hand
        setup = motion_setup(world, kinematics, estimate, side, start_door_for(step, door_angle, library.options))
        plan = library.plan(step, setup, setup.chain.chain_of(setup.chain.body_q), Backend.SQP)
        if not plan.succeeded or plan.path is None:
            return step.value, "planning failed", plan.result.message
        result = run_recording(world, TrajectoryExecution.from_joint_path(world, plan.path), peaks)
        if result is None:
            return step.value, "failure", "the motion ended without an outcome"
        if result.status is not OutcomeStatus.SUCCESS:
            return step.value, result.status.value, result.reason
        door_angle = float(plan.final_door[0])
    return Motion.READY_TO_WALK.value, "success", ""


def walk_through(world: DoorWorld, estimate: DoorEstimate, passage: PullPassageStudy = PullPassageStudy.FACING,
                 tuck_at: float = 0.45, kinematics: RobotKinematics | None = None) -> tuple[str, str, dict[str, float]]:
    """Plan the passage from the measured feet as the footstep planner node does (the same
    request, snapshot and planners) and walk it: (status, reason, peak contact forces).
    A tucked pull passage (:class:`PullPassageStudy`) walks it in two parts around the tuck."""
    parameters = dict(NODE_DEFAULTS)
    if passage is not PullPassageStudy.FACING:
        parameters["pull_passage"] = PullPassageStudy.SIDEWAYS.value
    if passage is PullPassageStudy.TUCK:
        parameters["pull_passage_shift"] = 0.0  # the hand leaves the leaf before the wall: no pinch to avoid
    settings = GoalSettings.from_parameters(parameters)
    options = planner_options(world.config.robot_profile, parameters)
    request = FootstepRequest(0, WalkGoal.THROUGH, world.config.door.opening, world.door_state().hinge_angle)
    problem = problem_for_request(request, measured_snapshot(world, estimate), options, settings)
    options = options_for_problem(problem, WalkGoal.THROUGH, options)
    planners, peaks = WalkPlanners(), dict[str, float]()
    if passage is PullPassageStudy.TUCK and kinematics is not None and len(problem.legs) == 5:  # the sideways legs
        status, reason = _walk_tucked(world, estimate, kinematics, planners, problem, options, tuck_at, peaks)
    else:
        status, reason = _walk(world, planners, problem, options, peaks)
    return status, reason, peaks


def measured_snapshot(world: DoorWorld, estimate: DoorEstimate) -> Snapshot:
    """What the footstep planner node would hold now: the base pose, the measured soles, the estimate."""
    feet = world.foot_placements()
    return Snapshot(world.base_pose(), [feet[Side.LEFT], feet[Side.RIGHT]], estimate, None)


def _walk_tucked(world: DoorWorld, estimate: DoorEstimate, kinematics: RobotKinematics, planners: WalkPlanners,
                 problem: WalkProblem, options: FootstepPlannerOptions, tuck_at: float,
                 peaks: dict[str, float]) -> tuple[str, str]:
    """The sideways pull legs to ``tuck_at`` before the wall, the tuck, then the rest (the
    side-step through and the turn to face away) from the measured feet: (status, reason)."""
    rest = problem.legs[3:]
    status, reason = _walk(world, planners, replace(problem, legs=(*problem.legs[:3], _tuck_stop(problem, tuck_at))),
                           options, peaks)
    if status != OutcomeStatus.SUCCESS.value:
        return status, reason
    blocking = grasp_hand(estimate.hinge_side, DoorOpening.PULL).other
    tuck = run_recording(world, TrajectoryExecution.from_joint_path(world, tuck_path(world, kinematics, blocking)),
                         peaks)
    if tuck is None:
        return "tuck: failure", "the tuck ended without an outcome"
    if tuck.status is not OutcomeStatus.SUCCESS:
        return f"tuck: {tuck.status.value}", tuck.reason
    start = snapshot_stance(measured_snapshot(world, estimate), options)
    return _walk(world, planners, replace(problem, start=start, legs=rest), options, peaks)


def _tuck_stop(problem: WalkProblem, tuck_at: float) -> Leg:
    """The side-step leg cut short ``tuck_at`` m before the door plane, on the same line."""
    through = problem.legs[3].goal
    along, _ = problem.door.to_door(through.x, through.y)
    x, y = problem.door.to_world(along, tuck_at)
    return Leg(Pose2D(x, y, through.yaw), "side-step to the wall (tuck there)", SIDEWAYS)


def tuck_path(world: DoorWorld, kinematics: RobotKinematics, side: Side) -> JointPath:
    """The ``side`` arm's joints (not the torso, which the other arm shares) from where they are
    to the walking posture, linearly over :data:`TUCK_DURATION`."""
    chain = ArmChain(kinematics, side, kinematics.nominal_q)
    walking = dict(zip(chain.joint_names, chain.chain_of(kinematics.walking_q)))
    names = tuple(name for name in kinematics.profile.arm(side).joints
                  if name not in kinematics.profile.arm(side.other).joints)
    now = world.joint_positions()
    start, goal = np.array([now[name] for name in names]), np.array([walking[name] for name in names])
    times = np.linspace(0.0, TUCK_DURATION, 21)[1:]
    return JointPath(times, names, np.array([start + (goal - start) * t / TUCK_DURATION for t in times]))


def _walk(world: DoorWorld, planners: WalkPlanners, problem: WalkProblem, options: FootstepPlannerOptions,
          peaks: dict[str, float]) -> tuple[str, str]:
    """Plan ``problem`` and walk it, recording peak contact forces: (status, reason)."""
    result, _ = planners.plan(problem, options)
    if not result.succeeded or result.plan is None:
        return "planning failed", f"{result.outcome.value}: {result.reason}"
    walked = run_recording(world, FootstepExecution(world, contract_footsteps(problem.start, result.plan)), peaks)
    if walked is None:
        return "failure", "the walk ended without an outcome"
    return walked.status.value, walked.reason


def run_door(opening: DoorOpening, hinge: HingeSide, trial: int, kinematics: RobotKinematics,
             passage: PullPassageStudy = PullPassageStudy.FACING, tuck_at: float = 0.45) -> PassageRun:
    """One door, its stand pose jittered by ``trial`` (0: none), for the robot of ``kinematics``."""
    rng = np.random.default_rng(trial)
    jitter = np.zeros(3) if trial == 0 else rng.uniform(-1.0, 1.0, 3) * JITTER
    robot = kinematics.profile.name
    with stand_world(DoorConfig(opening=opening, hinge_side=hinge), (jitter[0], jitter[1], jitter[2]),
                     robot) as world:
        estimate = perfect_estimate(world)
        peaks: dict[str, float] = {}
        stage, status, reason = open_door(world, kinematics, estimate, peaks)
        if status == "success":  # the walk's contacts are the ones that matter then
            stage = "walk through"
            status, reason, peaks = walk_through(world, estimate, passage, tuck_at, kinematics)
        strikes = tuple(sorted(peaks.items(), key=lambda item: -item[1])[:3])
        return PassageRun(robot, opening, hinge, trial, stage, status, reason, world.door_state().hinge_angle,
                          strikes)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="door_passage_rig", description=__doc__.split("\n\n")[0])
    parser.add_argument("--openings", nargs="+", choices=[o.value for o in DoorOpening], default=["push", "pull"])
    parser.add_argument("--hinges", nargs="+", choices=[h.value for h in HingeSide], default=["left", "right"])
    parser.add_argument("--trials", type=int, default=1, help="per door; trial 0 is the exact stand pose")
    add_robot_argument(parser, "robot profile (params/robot_<name>.yaml); default talos")
    parser.add_argument("--pull-passage", choices=[p.value for p in PullPassageStudy], default="facing",
                        help="how pull doors are passed (module docstring)")
    parser.add_argument("--tuck-at", type=float, default=0.45,
                        help="tuck: how far before the door plane the blocking arm is tucked (m)")
    args = parser.parse_args(argv)
    if args.trials < 1:
        parser.error("--trials must be at least 1")
    if not 0.3 <= args.tuck_at <= 1.0:
        parser.error("--tuck-at must be within [0.3, 1.0] m (the body turned sideways is 0.4 m wide)")
    check_robot(parser, args.robot)
    kinematics = RobotKinematics(load_profile(args.robot))
    runs = []
    for opening in args.openings:
        for hinge in args.hinges:
            for trial in range(args.trials):
                runs.append(run_door(DoorOpening(opening), HingeSide(hinge), trial, kinematics,
                                     PullPassageStudy(args.pull_passage), args.tuck_at))
                print(runs[-1].line(), flush=True)
    through = sum(run.stage == "walk through" and run.status == "success" for run in runs)
    fell = sum(run.status == OutcomeStatus.FELL.value for run in runs)
    print(f"through the doorway: {through}/{len(runs)}; fell: {fell}/{len(runs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
