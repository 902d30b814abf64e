"""From a footstep request to a planning problem, without ROS.

The node converts messages and calls these: the planner's options from the robot
profile's walking limits, the door from the detector's estimate, the stance the feet
start from, and the goal poses and obstacles of a "stand" or "through" request.
All poses are in ``odom`` (m, rad).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from door_contract.converters.footsteps import FootPlacement
from door_contract.door_estimates import requested_estimate_problem
from door_contract.geometry import yaw_of
from door_contract.payloads import DoorEstimate, FootstepRequest
from door_contract.vocabulary import DoorOpening, Foot, WalkGoal
from door_robot.profile import load_profile
from footstep_planner.astar import FootstepPlanner
from footstep_planner.door import DoorGeometry, wall_obstacles
from footstep_planner.errors import NoWalkForDoor, RequestRefused
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.goals import push_stand_pose, stand_pose_for_opening
from footstep_planner.legs import Leg, plan_legs
from footstep_planner.narrow import PullPassage, passage_legs
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import InputProblem, PlanResult
from footstep_planner.pull_passage import DOORWAY_REACHED, doorway_legs, in_doorway, onward_legs, pull_passage_legs
from footstep_planner.push_passage import DoorwayCut, PushPassage, push_passage_legs, tucks_before_passing
from footstep_planner.robot_limits import options_for_walking, planner_options
from footstep_planner.world import World

__all__ = ["GoalSettings", "Snapshot", "WalkPlanners", "WalkProblem", "door_geometry_from_estimate",
           "options_for_problem", "options_for_walking", "passage_angle", "planner_options", "problem_for_request",
           "snapshot_stance", "stand_pose", "start_stance", "walk_problem"]

PLANNED_STANCE_TOLERANCE = (0.03, 0.05)
"""The base within (m, rad) of where the last plan left it: that plan was walked."""


def door_geometry_from_estimate(estimate: DoorEstimate, opening: DoorOpening, angle: float,
                                handle_standoff: float) -> DoorGeometry:
    """The planner's door from a detector estimate (odom): the handle's face point fixes the
    door along the wall; the measured edges (``corners``: bottom-hinge, bottom-free, …) give
    the opening between the jambs and the handle's distance from the free edge. Without
    edges (operator-aided estimates) the DRC door's dimensions are assumed."""
    normal = np.asarray(estimate.normal[:2]) / np.linalg.norm(estimate.normal[:2])
    face = np.asarray(estimate.handle_position[:2]) - handle_standoff * normal
    dimensions = {}
    corners = np.asarray(estimate.corners, dtype=float)
    if corners.shape == (4, 3) and np.isfinite(corners).all():
        hinge, free = corners[0, :2], corners[1, :2]
        width = float(np.linalg.norm(free - hinge))
        handle_offset = width - float((face - hinge) @ (free - hinge)) / max(width, 1e-9)
        if 0.5 <= width <= 1.5 and 0.0 < handle_offset < width:
            dimensions = {"leaf_width": width, "clear_opening": width, "handle_offset": handle_offset}
    return DoorGeometry.from_handle(float(face[0]), float(face[1]), math.atan2(normal[1], normal[0]),
                                    estimate.hinge_side, opening, angle=angle, **dimensions)


def start_stance(body: Pose2D, separation: float, feet: tuple[Pose2D, Pose2D] | None = None,
                 planned: Stance | None = None) -> Stance:
    """The feet to plan from: measured (``feet`` = left, right soles) when the robot reports
    them; else where the last plan left them (``planned``) if the base stands at that
    stance's midpoint (the plan was walked); else the nominal stance around the base."""
    if feet is not None:
        left, right = feet
        return Stance(Footstep(left.x, left.y, left.yaw, Foot.LEFT),
                      Footstep(right.x, right.y, right.yaw, Foot.RIGHT))
    if planned is not None:
        middle = planned.body_pose
        near, turned = PLANNED_STANCE_TOLERANCE
        if middle.distance_to(body) < near and middle.yaw_difference(body) < turned:
            return planned
    return Stance.nominal(body, separation)


@dataclass(frozen=True)
class GoalSettings:
    """Where the robot stands to open a door and where a passage ends (the node's
    parameters of the same names; ranges in :mod:`footstep_planner.parameters`)."""

    stand_reach: float = 0.50
    """Base to the door plane when opening a push door (m)."""
    stand_reach_pull: float = 0.65
    """Base to the door plane when opening a pull door (m)."""
    stand_handle_offset: float = 0.20
    """Base to the handle along the wall, towards the hinge (m)."""
    pull_sweep_half_depth: float = 0.15
    """How far the torso reaches ahead of the base at a pull door (m)."""
    pull_sweep_angle: float = 0.45
    """How far a pull door swings while pulled (rad)."""
    pull_stand_beyond_latch: float = 0.05
    """Base past a pull door's latch edge along the wall (m)."""
    handle_standoff: float = 0.06
    """Door face behind the handle grasp point (m)."""
    beyond_door: float = 1.0
    """Goal distance past the door plane (m)."""
    passage_door_angle: float = 1.57
    """Push-door angle assumed while passing: the body pushes the leaf open (rad)."""
    push_passage: PushPassage = PushPassage.SIDEWAYS
    """How a push door is passed (:class:`~footstep_planner.push_passage.PushPassage`)."""
    push_side_reach: float = 0.50
    """Sideways: base to the door plane when opening a push door (m)."""
    push_stand_offset: float = 0.12
    """Sideways: the stand pose and side-step line from the opening's centre towards the latch (m)."""
    push_side_beyond: float = 0.9
    """Sideways: the side-step through ends this far past the door plane (m)."""
    push_step_away: float = 0.5
    """Sideways: then the robot steps this far forward, away from the hinge, out of the closing leaf's sweep (m)."""
    pull_passage: PullPassage = PullPassage.SIDEWAYS
    """How a blocked pull door is passed (:class:`~footstep_planner.narrow.PullPassage`)."""
    pull_passage_shift: float = 0.0
    """Sideways: the side-step line from the opening's centre towards the body's back (m)
    (:func:`~footstep_planner.narrow.hold_leaf_line`; the tuck takes the hand off the leaf
    before the wall plane, so there is no pinch to shift away from)."""
    tuck_at: float = 0.45
    """A pull door's doorway walk ends this far before the door plane, where the blocking arm
    tucks (m; :mod:`~footstep_planner.pull_passage`)."""
    push_tuck_min_width: float = 0.90
    """Sideways: a push door at least this wide has a doorway walk, the pushing arm tucking at
    its end (m; :mod:`~footstep_planner.push_passage`); a narrower one is walked in one go."""
    push_tuck_at: float = -0.05
    """Sideways: that doorway walk is the passage's plan up to its first stance at most this
    far before the door plane (m; :class:`~footstep_planner.push_passage.DoorwayCut`)."""

    @classmethod
    def from_parameters(cls, parameters: Mapping[str, Any]) -> GoalSettings:
        """The settings among a node's parameters (others are ignored)."""
        defaults = cls()  # each value converted to its default's type (float, PullPassage)
        return cls(**{name: type(getattr(defaults, name))(value) for name, value in parameters.items()
                      if name in cls.__dataclass_fields__})

    @classmethod
    def for_robot(cls, profile_name: str, parameters: Mapping[str, Any]) -> GoalSettings:
        """:meth:`from_parameters` with the robot profile's ``stance`` distances over the
        parameters of the same names (:data:`door_robot.profile.STANCE_FIELDS`: the parameters'
        values are TALOS's reach; a smaller robot stands closer)."""
        return cls.from_parameters({**parameters, **load_profile(profile_name).stance})


@dataclass(frozen=True)
class WalkProblem:
    """One request's planning problem: the poses to walk through in order, among obstacles."""

    start: Stance
    legs: tuple[Leg, ...]
    world: World
    door: DoorGeometry
    """The door as planned around (for a push passage: at the passage angle)."""
    cut: DoorwayCut | None = None
    """Where the walk stops in the legs' plan (a wide push door's doorway walk), None: at the end."""


def stand_pose(door: DoorGeometry, options: FootstepPlannerOptions, settings: GoalSettings) -> Pose2D:
    """Where the robot stands to open ``door`` (:func:`~footstep_planner.goals.stand_pose_for_opening`,
    or sideways :func:`~footstep_planner.goals.push_stand_pose`)."""
    if door.opening is DoorOpening.PUSH and settings.push_passage is PushPassage.SIDEWAYS:
        return push_stand_pose(door, options, settings.push_side_reach, settings.push_stand_offset)
    pull = door.opening is DoorOpening.PULL
    return stand_pose_for_opening(door, options, reach=settings.stand_reach_pull if pull else settings.stand_reach,
                                  handle_offset=settings.stand_handle_offset,
                                  sweep_half_depth=settings.pull_sweep_half_depth,
                                  pull_sweep_angle=settings.pull_sweep_angle,
                                  beyond_latch=settings.pull_stand_beyond_latch)


def passage_angle(door_angle: float, settings: GoalSettings) -> float:
    """The push door's angle planned around while passing: at least ``passage_door_angle``
    (the body pushes the leaf open), more when the door is already open further."""
    return max(door_angle, settings.passage_door_angle)


def walk_problem(goal: WalkGoal, door: DoorGeometry, start: Stance, options: FootstepPlannerOptions,
                 settings: GoalSettings) -> WalkProblem:
    """The poses and obstacles of a request.

    * stand: the door is shut while the robot walks there, so its leaf is an obstacle;
      the stand pose itself keeps the torso out of a pulled leaf's swing;
    * a PULL door: the other hand blocks the leaf and the walk sweeps it open
      (:mod:`~footstep_planner.pull_passage`): only wall and posts count. ``doorway`` walks to
      where the blocking arm tucks; ``through`` walks on from there, or, from anywhere else,
      the whole passage. The first turn is in place where the robot stands (measured), not at
      the planned stand pose: a walk there lands within 5 cm, and stepping back onto the planned
      pose while turning, the blocking hand on the leaf, brought the hinge-side knee onto the
      leaf's free edge;
    * through a PUSH door: the leaf at :func:`passage_angle` is an obstacle; sideways
      (``push_passage``), wall and posts only: :func:`_sideways_push_problem`.

    A doorway narrower than the body is passed sideways
    (:func:`~footstep_planner.narrow.passage_legs`). Raises
    :class:`~footstep_planner.errors.NoWalkForDoor` for a doorway walk at a push door that
    has none (passed facing, or sideways narrower than ``push_tuck_min_width``).
    """
    if goal is WalkGoal.STAND:
        legs: tuple[Leg, ...] = (Leg(stand_pose(door, options, settings), "to the stand pose"),)
        return WalkProblem(start, legs, World.from_door(door), door)
    if door.opening is DoorOpening.PULL:
        held = settings.pull_passage_shift if settings.pull_passage is PullPassage.SIDEWAYS else None
        legs = pull_passage_legs(door, start.body_pose, options, settings.beyond_door, held)
        doorway = doorway_legs(door, legs, settings.tuck_at)
        if goal is WalkGoal.DOORWAY:
            legs = doorway
        elif in_doorway(start, doorway):
            legs = onward_legs(legs)
        return WalkProblem(start, legs, World(wall_obstacles(door)), door)
    if settings.push_passage is PushPassage.SIDEWAYS:
        return _sideways_push_problem(goal, door, start, options, settings)
    if goal is WalkGoal.DOORWAY:
        raise NoWalkForDoor("a push door passed facing is walked through in one go: it has no doorway walk")
    door = door.with_angle(passage_angle(door.angle, settings))
    return WalkProblem(start, passage_legs(door, options, settings.beyond_door), World.from_door(door), door)


def _sideways_push_problem(goal: WalkGoal, door: DoorGeometry, start: Stance, options: FootstepPlannerOptions,
                           settings: GoalSettings) -> WalkProblem:
    """A push door passed sideways (:mod:`~footstep_planner.push_passage`): side-step from the
    stand pose, step away from the leaf and turn to face away
    (:func:`~footstep_planner.push_passage.push_passage_legs`), first to the stand pose when
    the robot is not on the side-step line. A door at least ``push_tuck_min_width`` wide is
    walked in two parts: ``doorway`` is that plan cut short where the pushing arm tucks
    (:class:`~footstep_planner.push_passage.DoorwayCut`), ``through`` the plan from where it
    stands; a narrower door has no ``doorway`` walk."""
    if goal is WalkGoal.DOORWAY and not tucks_before_passing(door, settings.push_tuck_min_width):
        raise NoWalkForDoor(f"a push door {door.leaf_width:.2f} m wide (< push_tuck_min_width "
                            f"{settings.push_tuck_min_width:.2f} m) is side-stepped through in one go: "
                            f"it has no doorway walk")
    legs = push_passage_legs(door, options, settings.push_stand_offset, settings.push_side_beyond,
                             settings.push_step_away, settings.beyond_door)
    stand = stand_pose(door, options, settings)
    if not _on_side_step_line(start, door, stand, legs[0].goal):
        legs = (Leg(stand, "to the side-step line"), *legs)  # from anywhere but where it opened the door
    cut = DoorwayCut(door, settings.push_tuck_at) if goal is WalkGoal.DOORWAY else None
    return WalkProblem(start, legs, World(wall_obstacles(door)), door, cut)


def _on_side_step_line(start: Stance, door: DoorGeometry, stand: Pose2D, through: Pose2D) -> bool:
    """Whether ``start`` stands on the side-step line from ``stand`` to ``through`` (its end; a
    line across the door plane, of constant ``along`` in :meth:`~footstep_planner.door.DoorGeometry.to_door`'s
    coordinates), heading as at ``stand``, within :data:`~footstep_planner.pull_passage.DOORWAY_REACHED`:
    where it opened the door, or where a doorway walk left it."""
    near, turned = DOORWAY_REACHED
    body = start.body_pose
    along, normal = door.to_door(body.x, body.y)
    line, stand_normal = door.to_door(stand.x, stand.y)
    end_normal = door.to_door(through.x, through.y)[1]
    return (abs(along - line) < near and end_normal < normal < stand_normal + near
            and body.yaw_difference(stand) < turned)


def options_for_problem(problem: WalkProblem, goal: WalkGoal,
                        options: FootstepPlannerOptions) -> FootstepPlannerOptions:
    """The stand pose is where the arm must reach the handle: the walk ends exactly on it
    (snap_to_goal; 4 cm and 3.8° off, within the search's goal tolerance, made a turn
    unreachable). So do the legs of a walk through waypoints (the pull door's turns
    sweep the door open). A plain passage keeps the search's tolerance."""
    if goal is WalkGoal.STAND or len(problem.legs) > 1:
        return replace(options, snap_to_goal=True)
    return options


@dataclass(frozen=True)
class Snapshot:
    """The inputs a request is planned from, taken when it arrives (the measured state):
    the base pose (4×4 in ``odom``), the measured soles (left, right), the door estimate the
    request names, and where the last plan left the feet."""

    base_pose: np.ndarray | None
    feet: list[FootPlacement] | None
    estimate: DoorEstimate | None
    planned_stance: Stance | None


def problem_for_request(request: FootstepRequest, snapshot: Snapshot, options: FootstepPlannerOptions,
                        settings: GoalSettings) -> WalkProblem:
    """Start stance, the legs to walk in order, and the obstacles of ``request``, from the
    snapshot. Raises :class:`~footstep_planner.errors.RequestRefused` without odometry or
    without a usable door estimate (its reason names what is missing)."""
    start = snapshot_stance(snapshot, options)
    estimate = snapshot.estimate
    problem = requested_estimate_problem(estimate, request.door_stamp)
    if problem or estimate is None:
        raise RequestRefused(problem or "no door estimate")
    door = door_geometry_from_estimate(estimate, request.opening, request.door_angle, settings.handle_standoff)
    return walk_problem(request.goal, door, start, options, settings)


def snapshot_stance(snapshot: Snapshot, options: FootstepPlannerOptions) -> Stance:
    """The stance a plan starts from, from the snapshot (:func:`start_stance`). Raises
    :class:`~footstep_planner.errors.RequestRefused` without odometry."""
    if snapshot.base_pose is None:
        raise RequestRefused("no valid odometry yet")
    pose = snapshot.base_pose
    body = Pose2D(float(pose[0, 3]), float(pose[1, 3]), yaw_of(pose))
    feet = None if snapshot.feet is None else _sole_poses(snapshot.feet)
    return start_stance(body, options.nominal_foot_separation, feet, snapshot.planned_stance)


def _sole_poses(feet: list[FootPlacement]) -> tuple[Pose2D, Pose2D]:
    """The measured (left, right) sole poses."""
    left, right = (Pose2D(f.x, f.y, f.yaw) for f in feet)
    return left, right


class WalkPlanners:
    """Plans a :class:`WalkProblem`: one :class:`~footstep_planner.astar.FootstepPlanner` per
    set of options (its tables are built once), given the problem's world for each plan."""

    def __init__(self) -> None:
        self._planners: dict[FootstepPlannerOptions, FootstepPlanner] = {}

    def plan(self, problem: WalkProblem, options: FootstepPlannerOptions, attempt: int = 0) -> tuple[PlanResult, str]:
        """The legs in order (:func:`~footstep_planner.legs.plan_legs`); from a start inside
        the safety margins once more with the first leg planned without them (a single leg:
        :meth:`~footstep_planner.astar.FootstepPlanner.plan_from_within_margins`). A sideways
        push door's measured stance after the opening once overlapped the latch post in the
        margin-inflated body box, and all three repeats of its passage failed alike. Returns
        the result and, when the margins were dropped, why (else ""); a problem with a
        :attr:`~WalkProblem.cut` gets its plan cut there."""
        result, relaxed_from = self._plan_legs(problem, options, attempt)
        if problem.cut is not None and result.plan is not None:
            result = replace(result, plan=problem.cut.cut(result.plan))
        return result, relaxed_from

    def _plan_legs(self, problem: WalkProblem, options: FootstepPlannerOptions, attempt: int) -> tuple[PlanResult, str]:
        if options not in self._planners:
            self._planners[options] = FootstepPlanner(problem.world, options)
        planner = self._planners[options].with_world(problem.world)
        if len(problem.legs) == 1:
            leg = problem.legs[0]
            return planner.plan_from_within_margins(problem.start, leg.goal, attempt, leg.pruning)
        result = plan_legs(planner, problem.start, problem.legs, attempt)
        tight = planner.without_margins()
        if result.input_problem is not InputProblem.START_COLLIDES or tight is None:
            return result, ""  # only the first leg starts where the robot stands
        return plan_legs(planner, problem.start, problem.legs, attempt, first_leg_planner=tight), result.reason
