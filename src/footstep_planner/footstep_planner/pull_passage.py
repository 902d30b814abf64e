"""A blocked pull door's passage, in two walks around the tuck of the blocking arm.

The legs ([Banerjee 2015] Fig. 2, :func:`~footstep_planner.goals.pull_passage_waypoints`):
turn in place towards the hinge (the blocking hand sweeps the leaf open), walk along the
wall to the opening's line, then either face the doorway and walk through
(:attr:`~footstep_planner.narrow.PullPassage.FACING`) or, sideways, side-step through still
facing the hinge and turn to face away (:attr:`~footstep_planner.narrow.PullPassage.SIDEWAYS`,
and any door narrower than the body: :func:`~footstep_planner.narrow.passage_legs`).

Walked in one go, both fell on the physical robot: facing, the hand leaves the leaf, which
swings into the hinge-side arm and shoulder; sideways, the leaf closes onto the hand near its
axis as the hand reaches the wall plane (110-180 N at 5-12 cm from the axis). So the FSM walks
it in two parts with an arm motion between (the passage rig: 7/10 through and no fall, against
3/10 and 7 falls facing):

1. :attr:`~door_contract.vocabulary.WalkGoal.DOORWAY`: the legs up to the opening's line
   and, sideways, the side-step cut short ``tuck_at`` before the door plane
   (:func:`doorway_legs`);
2. the blocking arm tucks to the walking posture (the trajectory optimiser's ``tuck_arm``):
   the leaf follows it and comes to rest on the front of the body, 0.3-0.9 m from its axis,
   pressing with 10-20 N along the feet;
3. :attr:`~door_contract.vocabulary.WalkGoal.THROUGH` from there: the legs that remain
   (:func:`onward_legs`), chosen because the robot stands where the first walk ended
   (:func:`in_doorway`); a THROUGH from anywhere else plans the whole passage.
"""

from __future__ import annotations

from footstep_planner.door import DoorGeometry
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.goals import pull_passage_waypoints
from footstep_planner.legs import Leg
from footstep_planner.narrow import SIDEWAYS, passage_legs
from footstep_planner.options import FootstepPlannerOptions

__all__ = ["DOORWAY_REACHED", "PULL_LEG_NAMES", "doorway_legs", "in_doorway", "onward_legs", "pull_passage_legs"]

PULL_LEG_NAMES = ("turn towards the hinge", "along the wall", "face the doorway", "through the doorway")
"""The legs of :func:`~footstep_planner.goals.pull_passage_waypoints`, in order."""
DOORWAY_REACHED = (0.10, 0.3)
"""A stance centre within (m, rad) of the doorway's pose stands where the first walk ended
(twice the walker's landing tolerance)."""
_ALONG_THE_WALL = 2
"""The legs every pull passage starts with: the turn towards the hinge and the walk along the wall."""


def pull_passage_legs(door: DoorGeometry, stand: Pose2D, options: FootstepPlannerOptions, distance_beyond: float,
                      hold_leaf: float | None) -> tuple[Leg, ...]:
    """The whole passage from the stand pose: four legs facing the doorway, or five sideways
    when ``hold_leaf`` (m: the side-step line's shift, :func:`~footstep_planner.narrow.hold_leaf_line`)
    is given or the doorway is narrower than the body."""
    poses = pull_passage_waypoints(door, stand, distance_beyond)
    legs = tuple(Leg(pose, name) for pose, name in zip(poses, PULL_LEG_NAMES))
    sideways = passage_legs(door, options, distance_beyond, heading=poses[1].yaw, hold_leaf=hold_leaf)
    if len(sideways) > 1:
        return (*legs[:_ALONG_THE_WALL], *sideways)
    return legs


def doorway_legs(door: DoorGeometry, legs: tuple[Leg, ...], tuck_at: float) -> tuple[Leg, ...]:
    """The legs of ``legs`` (:func:`pull_passage_legs`) up to where the arm tucks: along the
    wall, and, sideways, the turn before the doorway and the side-step cut short at
    ``tuck_at`` m before the door plane (on the same line, heading held), unless the turn
    already ends nearer the plane."""
    if not _is_sideways(legs):
        return legs[:_ALONG_THE_WALL]
    before, through = legs[_ALONG_THE_WALL], legs[_ALONG_THE_WALL + 1]
    if door.to_door(before.goal.x, before.goal.y)[1] <= tuck_at:
        return legs[:_ALONG_THE_WALL + 1]
    along, _ = door.to_door(through.goal.x, through.goal.y)
    x, y = door.to_world(along, tuck_at)
    stop = Leg(Pose2D(x, y, through.goal.yaw), "side-step to where the arm tucks", SIDEWAYS)
    return (*legs[:_ALONG_THE_WALL + 1], stop)


def onward_legs(legs: tuple[Leg, ...]) -> tuple[Leg, ...]:
    """The legs of ``legs`` after :func:`doorway_legs`: the side-step through and the turn to
    face away, or (facing) the turn to face the doorway and the walk through."""
    return legs[_ALONG_THE_WALL + 1:] if _is_sideways(legs) else legs[_ALONG_THE_WALL:]


def in_doorway(start: Stance, doorway: tuple[Leg, ...]) -> bool:
    """Whether ``start`` stands where the doorway walk ends (within :data:`DOORWAY_REACHED`)."""
    near, turned = DOORWAY_REACHED
    body, goal = start.body_pose, doorway[-1].goal
    return body.distance_to(goal) < near and body.yaw_difference(goal) < turned


def _is_sideways(legs: tuple[Leg, ...]) -> bool:
    return len(legs) == _ALONG_THE_WALL + 3
