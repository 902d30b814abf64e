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

The walk through is the FSM's: to the doorway, the tuck of the arm on the leaf, and on through
(a pull door's blocking arm, :mod:`footstep_planner.pull_passage`; a wide push door's pushing
arm, :mod:`footstep_planner.push_passage`); a narrow push door in one walk. ``--pull-passage``,
``--push-passage`` and ``--tuck-at`` are the footstep planner's parameters of those names, for
studies (the default ``--push-passage sideways``: the push door opened and passed sideways, its
back to the hinge, :mod:`footstep_planner.push_passage`; ``facing`` the earlier way). The hand is
the optimiser node's: the arm on the handle's side. ``--estimate-error CM DEG`` gives every plan
the door as a detector would, moved up to CM cm per axis and turned up to DEG degrees.

    python -m door_bringup.passage_rig --robot g1 --openings push pull --hinges left right --trials 3
    python -m door_bringup.passage_rig --openings pull --trials 5 --tuck-at 0.5
    python -m door_bringup.passage_rig --openings push --trials 10 --estimate-error 0.6 0.5
    python -m door_bringup.passage_rig --openings push --walk-from 2.5 --trials 4

``--walk-from M`` starts the robot M m in front of the door and walks it to the stand pose
first, as the graph does (the walk's landing and sway matter: the rig's placed robot hid them).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import Enum
from types import MappingProxyType
from typing import Any

import numpy as np

from door_bringup.fall_trace import FallTrace
from door_bringup.robot_option import add_robot_argument, check_robot
from door_contract.errors import ParameterRangeError
from door_contract.parameters import validate_all
from door_contract.payloads import DoorEstimate, FootstepRequest, OutcomeStatus
from door_contract.vocabulary import Backend, DetectionMode, DoorOpening, HingeSide, Motion, Side, TaskState, WalkGoal
from door_fsm.wiring import WiringError, success_sequence
from door_fsm.work import STATE_WORK, WorkKind
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.execution import ExecutionResult, FootstepExecution, TrajectoryExecution
from door_sim_bridge.world import ContactSolver, DoorConfig, DoorWorld, StanceConfig, WindConfig, WorldConfig
from door_trajopt.chain import ArmChain
from door_trajopt.door_model import door_model_from_estimate
from door_trajopt.library import MotionLibrary
from door_trajopt.motions import MotionSetup, start_door_for
from door_trajopt.requests import grasping_hand
from footstep_planner.errors import NoWalkForDoor
from footstep_planner.narrow import PullPassage
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.parameters import PLANNER_PARAMETERS
from footstep_planner.proposal import contract_footsteps
from footstep_planner.push_passage import PushPassage
from footstep_planner.requests import (
    GoalSettings,
    Snapshot,
    WalkPlanners,
    door_geometry_from_estimate,
    options_for_problem,
    planner_options,
    problem_for_request,
    stand_pose,
)

__all__ = ["NODE_DEFAULTS", "WALKED_THROUGH", "DoorShape", "EstimateError", "HandCommand", "PassageRun", "erroneous_estimate",
           "main", "motion_setup", "open_door", "opening_hand", "opening_sequence", "passage_steps", "perfect_estimate",
           "run_door", "stand_world"]

NODE_DEFAULTS = {spec.name: spec.default for spec in PLANNER_PARAMETERS}
"""The footstep planner node's default parameters (search settings and goal settings)."""
JITTER = np.array([0.02, 0.02, np.radians(1.0)])
"""Largest stand-pose error a trial adds: along the normal, along the wall (m), yaw (rad)."""


class HandCommand(str, Enum):
    """The grasp service's two calls, as steps of the opening (the FSM's GRASP state and the
    release READY_TO_WALK makes before it plans)."""

    GRASP = "grasp"
    RELEASE = "release"


WALKED_THROUGH = "walk through"
"""The stage of a door whose last walk ran (to its end, or to a fall)."""
WALK_TO_DOOR = "walk to the door"
"""The stage of a door whose walk to the stand pose did not succeed (``--walk-from``)."""


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
    fall_trace: tuple[str, ...] = ()  # FallTrace.report() of a fall traced with --trace-falls

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
                        1.0, 10, DetectionMode.AUTOMATIC)


@dataclass(frozen=True)
class EstimateError:
    """Largest error a trial puts into the rig's (otherwise perfect) estimate, as the
    detector's: the whole door shifted along its normal, along the wall and in height (m),
    and turned about the vertical through the handle (rad). Each trial draws uniformly
    within these bounds (trial 0 too); zero is the perfect detector."""

    position: float = 0.0
    yaw: float = 0.0

    def drawn(self, rng: np.random.Generator) -> tuple[np.ndarray, float]:
        """(shift along normal, along wall, up; yaw) for one trial."""
        return rng.uniform(-1.0, 1.0, 3) * self.position, float(rng.uniform(-1.0, 1.0) * self.yaw)


@dataclass(frozen=True)
class DoorShape:
    """The leaf's width and the lever's height (m); None keeps :class:`DoorConfig`'s."""

    width: float | None = None
    handle_height: float | None = None

    def applied(self, door: DoorConfig) -> DoorConfig:
        if self.width is not None:
            door = dataclasses.replace(door, width=self.width)
        if self.handle_height is not None:
            door = dataclasses.replace(door, handle_height=self.handle_height)
        return door


def erroneous_estimate(estimate: DoorEstimate, shift: np.ndarray, yaw: float) -> DoorEstimate:
    """``estimate`` moved rigidly: turned by ``yaw`` about the vertical through the handle,
    then shifted by ``shift`` = (along its normal, along the wall, up) in metres."""
    normal = np.array(estimate.normal)
    along = np.cross([0.0, 0.0, 1.0], normal)
    along /= np.linalg.norm(along)
    c, s = np.cos(yaw), np.sin(yaw)
    turn = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    handle = np.array(estimate.handle_position)
    offset = shift[0] * normal + shift[1] * along + shift[2] * np.array([0.0, 0.0, 1.0])

    def moved(point: Sequence[float]) -> tuple[float, float, float]:
        x, y, z = turn @ (np.asarray(point) - handle) + handle + offset
        return float(x), float(y), float(z)

    nx, ny, nz = turn @ normal
    return dataclasses.replace(estimate, handle_position=moved(estimate.handle_position),
                               normal=(float(nx), float(ny), float(nz)),
                               corners=tuple(moved(corner) for corner in estimate.corners))


def stand_world(door: DoorConfig, offset: tuple[float, float, float] = (0.0, 0.0, 0.0),
                robot: str = "talos", parameters: Mapping[str, object] = NODE_DEFAULTS,
                error: tuple[np.ndarray, float] = (np.zeros(3), 0.0),
                physics: Mapping[str, Any] = MappingProxyType({})) -> DoorWorld:
    """``robot`` at the stand pose the footstep planner (with ``parameters``) chooses for
    ``door`` as estimated with ``error`` (:func:`erroneous_estimate`), plus ``offset`` (along
    the door normal, along the wall, yaw), standing on the floor: facing the door, or sideways
    beside a push door's opening (``push_passage``). ``physics`` are :class:`WorldConfig` fields
    (``physics_rate``, ``contact_solver``, ``solver_iterations``) over their defaults."""
    with DoorWorld(WorldConfig(robot_profile=robot, door=door)) as probe:
        estimate = erroneous_estimate(perfect_estimate(probe), *error)
    settings = GoalSettings.for_robot(robot, parameters)
    options = planner_options(robot, parameters)
    geometry = door_geometry_from_estimate(estimate, door.opening, 0.0, settings.handle_standoff)
    stand = stand_pose(geometry, options, settings)
    return DoorWorld(WorldConfig(robot_profile=robot, door=door, **physics, stance=StanceConfig(
        distance=-stand.x + offset[0], lateral_offset=stand.y + offset[1], yaw=stand.yaw + offset[2])))


def motion_setup(world: DoorWorld, kinematics: RobotKinematics, estimate: DoorEstimate, hand: Side,
                 door_angles: tuple[float, float]) -> MotionSetup:
    """The motion library's set-up from the measured posture and the (pre-opening) estimate."""
    push = world.config.door.opening is DoorOpening.PUSH
    body_q = kinematics.configuration({name: value for name, value in world.joint_positions().items()
                                       if name in kinematics.joint_names})
    chain = ArmChain(kinematics, hand, body_q)
    door = door_model_from_estimate(estimate, np.linalg.inv(world.base_pose()), push=push)
    return MotionSetup.measured(chain, door, estimate.width, world.base_pose()[:3, :3], door_angles)


def opening_sequence(opening: DoorOpening) -> tuple[Motion | HandCommand, ...]:
    """The FSM's OPEN_DOOR as motions and grasp calls, read off its wiring (the sub-states of
    :func:`~door_fsm.wiring.success_sequence` and their work): approach, grasp, turn,
    push | pull and block, release, ready to walk."""
    steps: list[Motion | HandCommand] = []
    for state in success_sequence(opening):
        if not state.is_open_door_substate:
            continue
        work = STATE_WORK[state]
        if work.kind is WorkKind.GRASP:
            steps.append(HandCommand.GRASP)
            continue
        if work.release_first:
            steps.append(HandCommand.RELEASE)
        if not isinstance(work.target, Motion):
            raise WiringError(f"{state.label} is neither a grasp nor a motion")
        steps.append(work.target)
    return tuple(steps)


def run_recording(world: DoorWorld, execution: FootstepExecution | TrajectoryExecution,
                  peaks: dict[str, float], trace: FallTrace | None = None) -> ExecutionResult | None:
    """Step ``execution`` to its end, keeping the peak normal force of every robot-door contact
    in ``peaks`` (and sampling ``trace`` each step); its result (None: it ended without one)."""
    while not execution.command():
        world.step()
        if trace is not None:
            trace.step()
        for name, force in world.door_contact_forces().items():
            peaks[name] = max(peaks.get(name, 0.0), force)
    return execution.result


def opening_hand(world: DoorWorld, estimate: DoorEstimate) -> Side:
    """The hand that opens the door, as the trajectory optimiser node picks it: the arm on the
    handle's side of the base (:func:`door_trajopt.requests.grasping_hand`)."""
    return grasping_hand(estimate, world.base_pose())


def open_door(world: DoorWorld, kinematics: RobotKinematics, estimate: DoorEstimate,
              peaks: dict[str, float], hand: Side, trace: FallTrace | None = None) -> tuple[str, str, str]:
    """Run the opening sequence with ``hand``; (stage, status, reason) of the step it stopped
    in, or of the last; the contacts' peak forces go into ``peaks``."""
    opening = world.config.door.opening
    library, door_angle = MotionLibrary(), 0.0
    for step in opening_sequence(opening):
        if isinstance(step, HandCommand):
            answer = world.grasp(hand, step is HandCommand.GRASP)
            if not answer.success:
                return step.value, "failure", answer.message
            continue
        status, reason, door_angle = run_motion(world, kinematics, estimate, step, library, door_angle, peaks, hand,
                                                trace)
        if status != OutcomeStatus.SUCCESS.value:
            return step.value, status, reason
    return Motion.READY_TO_WALK.value, "success", ""


def run_motion(world: DoorWorld, kinematics: RobotKinematics, estimate: DoorEstimate, motion: Motion,
               library: MotionLibrary, door_angle: float, peaks: dict[str, float],
               hand: Side, trace: FallTrace | None = None) -> tuple[str, str, float]:
    """Plan ``motion`` from the measured posture, as the trajectory optimiser node does, for
    ``hand`` (the other arm's motions for the other), and execute it: (status, reason, the
    door angle the plan ends at)."""
    side = hand.other if motion.moves_other_arm(world.config.door.opening) else hand
    setup = motion_setup(world, kinematics, estimate, side, start_door_for(motion, door_angle, library.options))
    plan = library.plan(motion, setup, setup.chain.chain_of(setup.chain.body_q), Backend.SQP)
    if not plan.succeeded or plan.path is None:
        return "planning failed", plan.result.message, door_angle
    result = run_recording(world, TrajectoryExecution.from_joint_path(world, plan.path), peaks, trace)
    if result is None:
        return "failure", "the motion ended without an outcome", door_angle
    return result.status.value, result.reason, float(plan.final_door[0])


def passage_steps(opening: DoorOpening) -> tuple[tuple[TaskState, WalkGoal | Motion], ...]:
    """The FSM's WALK_THROUGH as its states' walks and motions, read off its wiring: the walk to
    the doorway, the tuck, the walk on (:mod:`footstep_planner.pull_passage`,
    :mod:`footstep_planner.push_passage`); a door without a doorway walk skips to the state
    the wiring says (:attr:`~door_fsm.work.StateWork.skip_to`)."""
    passage = [state for state in success_sequence(opening)
               if state is TaskState.WALK_THROUGH or state.is_walk_through_substate]
    return tuple((state, _walk_or_motion(STATE_WORK[state].target)) for state in passage)


def _walk_or_motion(target: WalkGoal | Motion | None) -> WalkGoal | Motion:
    if target is None:
        raise WiringError("a WALK_THROUGH state without a walk goal or motion")
    return target


def walk_through(world: DoorWorld, estimate: DoorEstimate, kinematics: RobotKinematics,
                 parameters: Mapping[str, object], hand: Side,
                 trace: FallTrace | None = None) -> tuple[str, str, str, dict[str, float]]:
    """The passage as the FSM runs it (:func:`passage_steps`), each walk planned from the
    measured feet with the footstep planner node's calls and ``parameters``, each motion with
    the motion library for ``hand`` (the opening's; the FSM names it in its requests):
    (stage, status, reason, peak contact forces), the stage :data:`WALKED_THROUGH` or the step
    that did not succeed."""
    settings = GoalSettings.for_robot(world.config.robot_profile, parameters)
    options = planner_options(world.config.robot_profile, parameters)
    planners, library, peaks = WalkPlanners(), MotionLibrary(), dict[str, float]()
    skip_to: TaskState | None = None
    for state, step in passage_steps(world.config.door.opening):
        if skip_to not in (None, state):
            continue
        skip_to = None
        if isinstance(step, Motion):
            status, reason, _ = run_motion(world, kinematics, estimate, step, library,
                                           world.door_state().hinge_angle, peaks, hand, trace)
        else:
            try:
                status, reason = _walk(world, estimate, step, planners, options, settings, peaks, trace)
            except NoWalkForDoor:
                skip_to = STATE_WORK[state].skip_to
                if skip_to is None:
                    raise
                continue
        if status != OutcomeStatus.SUCCESS.value:
            return (WALKED_THROUGH if step is WalkGoal.THROUGH else f"walk through: {step.value}"), status, reason, peaks
    return WALKED_THROUGH, OutcomeStatus.SUCCESS.value, "", peaks


def measured_snapshot(world: DoorWorld, estimate: DoorEstimate) -> Snapshot:
    """What the footstep planner node would hold now: the base pose, the measured soles, the estimate."""
    feet = world.foot_placements()
    return Snapshot(world.base_pose(), [feet[Side.LEFT], feet[Side.RIGHT]], estimate, None)


def _walk(world: DoorWorld, estimate: DoorEstimate, goal: WalkGoal, planners: WalkPlanners,
          options: FootstepPlannerOptions, settings: GoalSettings, peaks: dict[str, float],
          trace: FallTrace | None = None) -> tuple[str, str]:
    """Plan the walk to ``goal`` from the measured state and walk it at the profile's crouch for
    it, recording peak contact forces: (status, reason)."""
    request = FootstepRequest(0, goal, world.config.door.opening, world.door_state().hinge_angle)
    problem = problem_for_request(request, measured_snapshot(world, estimate), options, settings)
    result, _ = planners.plan(problem, options_for_problem(problem, goal, options))
    if not result.succeeded or result.plan is None:
        return "planning failed", f"{result.outcome.value}: {result.reason}"
    crouch = world.profile.crouch.for_walk(goal, world.config.door.opening,
                                           (estimate.handle_position[2], estimate.width))  # as the FSM
    walked = run_recording(world, FootstepExecution(world, contract_footsteps(problem.start, result.plan), crouch),
                           peaks, trace)
    if walked is None:
        return "failure", "the walk ended without an outcome"
    return walked.status.value, walked.reason


def run_door(opening: DoorOpening, hinge: HingeSide, trial: int, kinematics: RobotKinematics,
             planner_parameters: Mapping[str, object] | None = None, walk_from: float | None = None,
             estimate_error: EstimateError = EstimateError(), door_shape: DoorShape = DoorShape(),
             wind: float = 0.0, physics: Mapping[str, Any] = MappingProxyType({}),
             trace_falls: bool = False) -> PassageRun:
    """One door for the robot of ``kinematics``, the passage planned with the footstep planner
    node's defaults updated by ``planner_parameters``. The robot starts at the stand pose
    jittered by ``trial`` (0: none), or, with ``walk_from`` (m), that far in front of the door
    and walks to the stand pose first, as in the graph (``trial`` > 0: up to ±0.3 m aside and
    ±0.3 rad turned). Every plan uses the ground truth with ``estimate_error`` drawn for the
    trial (its own random stream: the jitter does not change with it). ``door_shape`` is the
    leaf's width and the lever's height (the DRC door's 0.914 m and 0.91 m by default); ``wind`` (N·m) is the amplitude of the wind on the hinge, as the Monte-Carlo's; ``physics``
    as :func:`stand_world`'s. With ``trace_falls`` a fall comes with a :class:`FallTrace` report."""
    rng = np.random.default_rng(trial)
    error = estimate_error.drawn(np.random.default_rng([trial, 1]))
    robot = kinematics.profile.name
    parameters = {**NODE_DEFAULTS, **(planner_parameters or {})}
    door = door_shape.applied(DoorConfig(opening=opening, hinge_side=hinge, wind=WindConfig(amplitude=wind)))
    peaks: dict[str, float] = {}
    if walk_from is None:
        jitter = np.zeros(3) if trial == 0 else rng.uniform(-1.0, 1.0, 3) * JITTER
        world = stand_world(door, (jitter[0], jitter[1], jitter[2]), robot, parameters, error, physics)
    else:
        aside, turned = (0.0, 0.0) if trial == 0 else tuple(rng.uniform(-0.3, 0.3, 2))
        world = DoorWorld(WorldConfig(robot_profile=robot, door=door, **physics,
                                      stance=StanceConfig(distance=walk_from, lateral_offset=aside, yaw=turned)))
    with world:
        trace = FallTrace(world) if trace_falls else None
        estimate = erroneous_estimate(perfect_estimate(world), *error)
        stage, status, reason = WALK_TO_DOOR, "success", ""
        if walk_from is not None:
            status, reason = _walk(world, estimate, WalkGoal.STAND, WalkPlanners(), planner_options(robot, parameters),
                                   GoalSettings.for_robot(robot, parameters), peaks, trace)
        if status == "success":
            hand = opening_hand(world, estimate)  # at the stand pose, as the approach picks it
            stage, status, reason = open_door(world, kinematics, estimate, peaks, hand, trace)
            if status == "success":  # the walk's contacts are the ones that matter then
                stage, status, reason, peaks = walk_through(world, estimate, kinematics, parameters, hand, trace)
        strikes = tuple(sorted(peaks.items(), key=lambda item: -item[1])[:3])
        fall_trace = trace.report() if trace is not None and status == OutcomeStatus.FELL.value else ()
        return PassageRun(robot, opening, hinge, trial, stage, status, reason, world.door_state().hinge_angle,
                          strikes, fall_trace)


def physics_overrides(parser: argparse.ArgumentParser, args: argparse.Namespace) -> dict[str, Any]:
    """The :class:`WorldConfig` physics fields the command line sets, checked by the config itself."""
    fields = {"physics_rate": args.physics_rate, "solver_iterations": args.solver_iterations,
              "contact_solver": None if args.contact_solver is None else ContactSolver(args.contact_solver)}
    physics = {name: value for name, value in fields.items() if value is not None}
    try:
        WorldConfig(**physics)
    except SimulationError as error:
        parser.error(str(error))
    return physics


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="door_passage_rig", description=__doc__.split("\n\n")[0])
    parser.add_argument("--openings", nargs="+", choices=[o.value for o in DoorOpening], default=["push", "pull"])
    parser.add_argument("--hinges", nargs="+", choices=[h.value for h in HingeSide], default=["left", "right"])
    parser.add_argument("--trials", type=int, default=1, help="per door; trial 0 is the exact stand pose")
    add_robot_argument(parser, "robot profile (params/robot_<name>.yaml); default talos")
    parser.add_argument("--pull-passage", choices=[p.value for p in PullPassage],
                        default=NODE_DEFAULTS["pull_passage"], help="the footstep planner's pull_passage")
    parser.add_argument("--push-passage", choices=[p.value for p in PushPassage],
                        default=NODE_DEFAULTS["push_passage"],
                        help="the footstep planner's push_passage (footstep_planner.push_passage)")
    parser.add_argument("--walk-from", type=float, default=None, metavar="M",
                        help="start M m in front of the door (0.8-8) and walk to the stand pose first, as in "
                             "the graph (trials > 0: up to 0.3 m aside and 0.3 rad turned); default: start there")
    parser.add_argument("--estimate-error", type=float, nargs=2, default=(0.0, 0.0), metavar=("CM", "DEG"),
                        help="plan with the door estimated up to CM cm off along each axis and DEG degrees "
                             "turned, drawn per trial (the detector's errors; default: a perfect estimate)")
    parser.add_argument("--door-width", type=float, default=None, metavar="M",
                        help="the leaf's width (0.8-1.0 m, the full range of issue #13); default 0.914 m")
    parser.add_argument("--handle-height", type=float, default=None, metavar="M",
                        help="the lever's height (0.85-1.10 m, the full range of issue #13); default 0.91 m")
    parser.add_argument("--wind", type=float, default=0.0, metavar="NM",
                        help="wind on the hinge, amplitude in N·m (0-3, as the Monte-Carlo's); default none")
    parser.add_argument("--tuck-at", type=float, default=NODE_DEFAULTS["tuck_at"],
                        help="the footstep planner's tuck_at: the doorway walk ends this far before the door plane (m)")
    parser.add_argument("--trace-falls", action="store_true",
                        help="after a fall, print the stance leg's samples around the first pelvis dip "
                             "(door_bringup.fall_trace)")
    parser.add_argument("--physics-rate", type=float, default=None, metavar="HZ",
                        help="the sim's physics rate (sim_bridge.physics_rate); default the sim's")
    parser.add_argument("--contact-solver", choices=[c.value for c in ContactSolver], default=None,
                        help="PyBullet's constraint solver (sim_bridge.contact_solver); default the sim's")
    parser.add_argument("--solver-iterations", type=int, default=None, metavar="N",
                        help="sweeps per step of the iterative solver (sim_bridge.solver_iterations)")
    args = parser.parse_args(argv)
    if args.trials < 1:
        parser.error("--trials must be at least 1")
    if args.walk_from is not None and not 0.8 <= args.walk_from <= 8.0:
        parser.error(f"--walk-from must be within [0.8, 8] m, got {args.walk_from!r}")
    overrides = {"pull_passage": args.pull_passage, "push_passage": args.push_passage, "tuck_at": args.tuck_at}
    try:
        validate_all(PLANNER_PARAMETERS, overrides)
    except ParameterRangeError as error:
        parser.error(str(error))
    if args.door_width is not None and not 0.8 <= args.door_width <= 1.0:
        parser.error(f"--door-width must be within [0.8, 1.0] m, got {args.door_width!r}")
    if args.handle_height is not None and not 0.85 <= args.handle_height <= 1.10:
        parser.error(f"--handle-height must be within [0.85, 1.10] m, got {args.handle_height!r}")
    if not 0.0 <= args.wind <= 3.0:
        parser.error(f"--wind must be within [0, 3] N·m, got {args.wind!r}")
    if not all(0.0 <= bound <= 10.0 for bound in args.estimate_error):
        parser.error(f"--estimate-error must be within [0, 10] cm and [0, 10] degrees, got {args.estimate_error}")
    estimate_error = EstimateError(args.estimate_error[0] / 100.0, np.radians(args.estimate_error[1]))
    door_shape = DoorShape(args.door_width, args.handle_height)
    physics = physics_overrides(parser, args)
    check_robot(parser, args.robot)
    kinematics = RobotKinematics(load_profile(args.robot))
    runs = []
    for opening in args.openings:
        for hinge in args.hinges:
            for trial in range(args.trials):
                runs.append(run_door(DoorOpening(opening), HingeSide(hinge), trial, kinematics, overrides,
                                     args.walk_from, estimate_error, door_shape, args.wind, physics,
                                     args.trace_falls))
                print("\n    ".join((runs[-1].line(), *runs[-1].fall_trace)), flush=True)
    through = sum(run.stage == WALKED_THROUGH and run.status == "success" for run in runs)
    fell = sum(run.status == OutcomeStatus.FELL.value for run in runs)
    print(f"through the doorway: {through}/{len(runs)}; fell: {fell}/{len(runs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
