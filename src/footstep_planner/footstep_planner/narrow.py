"""Doorways narrower than the body: pass them sideways, through waypoints on the centre line.

A body rectangle of half extents a (across the shoulders) and b (front to back), both
grown by ``body_margin``, walking through the doorway along the door normal at yaw phi
from facing it, sweeps a band of the wall line as wide as its projection on the wall:

    width(phi) = 2 (a |cos phi| + b |sin phi|).

Translating straight along the normal, it clears the jambs exactly when that band fits
between them, width(phi) <= W - 2 c (W the clear opening, c :data:`PASSAGE_CLEARANCE` on
each side).  Facing the door (phi = 0) the band is 2a; when that does not fit, the body
goes sideways (phi = pi/2, band 2b).  Not at the smallest turn that fits (for a > b,
phi* = atan2(b, a) + arccos((W/2 - c) / sqrt(a^2 + b^2))): that turn leaves the least
slack, and at phi* every side step also drifts across the doorway by cos(phi*) of its
length, so the search has to mix in forward steps to stay within c.
(TALOS, 0.80 m door: phi* = 78 degrees, 1.2 cm of drift per side step against 1 cm of
clearance: 20,000 expansions.)  Sideways, a side step moves the body straight along the
normal and the slack is W - 2b - 2c (TALOS: 16 cm).

The footstep search alone finds such passages too, but slowly: its heuristic knows
nothing of the jambs (a 0.80 m door took it 25,000 expansions, 6 s).  Waypoints on the
centre line make each leg easy: turn sideways in front of the wall, side-step through
with the heading held (the search prunes the states that turn away), and turn to face
away once the body is clear of the wall and of a push door's open leaf.
"""

from __future__ import annotations

import math

from door_contract.vocabulary import DoorOpening
from footstep_planner.door import DoorGeometry
from footstep_planner.footstep import Pose2D
from footstep_planner.geometry import wrap_angle
from footstep_planner.goals import through_door_pose
from footstep_planner.legs import Leg
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.pruning import LegPruning

PASSAGE_CLEARANCE = 0.01
"""Gap kept between the body (with its margin) and each jamb while passing (m)."""
WALL_CLEARANCE = 0.05
"""Gap between the turning body and the frame (or a push door's leaf) either side (m)."""
SIDEWAYS = LegPruning(yaw_window=0.1, corridor=0.05)
"""While side-stepping through: the feet within 0.1 rad of sideways, the stance centre within
5 cm of the centre line (:mod:`~footstep_planner.pruning`)."""


def passage_turn(door: DoorGeometry, options: FootstepPlannerOptions) -> float | None:
    """The body's yaw from facing the door while it passes (rad): 0 when it fits facing,
    pi/2 (sideways) when only that fits, None when it does not fit even sideways."""
    across = options.body_half_width + options.body_margin
    deep = options.body_half_depth + options.body_margin
    half_gap = door.clear_opening / 2.0 - PASSAGE_CLEARANCE
    if across <= half_gap + _SLACK:
        return 0.0
    if deep <= half_gap + _SLACK:
        return math.pi / 2.0
    return None


_SLACK = 1e-9
"""Float noise allowed in the fit tests (m)."""


def passage_legs(door: DoorGeometry, options: FootstepPlannerOptions, distance_beyond: float,
                 heading: float | None = None) -> tuple[Leg, ...]:
    """The legs through the doorway, ending at the through-door pose.

    A body that fits facing the door walks straight to :func:`through_door_pose`
    (one leg). Otherwise (a door narrower than the body, see :func:`passage_turn`):

    1. to the centre line in front of the wall, turned sideways, far enough out that the
       body turns in place there clear of the frame (its corners lie within R =
       sqrt(a^2 + b^2) of its centre);
    2. side-step straight through along the centre line, every state within
       0.1 rad of that heading and 5 cm of the line (:data:`SIDEWAYS`), to where the body turns clear of the
       frame and of a push door's open leaf (any angle: within W + leaf thickness of the
       hinge);
    3. turn to face away, at the through-door pose (moved to that point when nearer).

    The turn is towards ``heading`` (e.g. the yaw the robot already has), by default
    towards the hinge. A doorway too narrow even sideways gets the direct leg: its
    search then reports why it cannot pass.
    """
    final = through_door_pose(door, distance_beyond)
    turn = passage_turn(door, options)
    if not turn:
        return (Leg(final, "through the doorway"),)
    yaw = _turned_yaw(door, turn, heading)
    radius = math.hypot(options.body_half_width + options.body_margin,
                        options.body_half_depth + options.body_margin) + WALL_CLEARANCE
    near_face, far_face = _wall_faces(door)
    beyond = far_face - radius
    if door.opening is DoorOpening.PUSH:
        around_leaf = door.leaf_width + door.leaf_thickness + radius
        beyond = min(beyond, -math.sqrt(max(around_leaf ** 2 - (door.clear_opening / 2.0) ** 2, 0.0)))
    if distance_beyond < -beyond:
        final = through_door_pose(door, -beyond)
    return (Leg(_on_centre_line(door, near_face + radius, yaw), "turn sideways before the doorway"),
            Leg(_on_centre_line(door, beyond, yaw), "side-step through the doorway", SIDEWAYS),
            Leg(final, "turn to face away"))


def _turned_yaw(door: DoorGeometry, turn: float, heading: float | None) -> float:
    """facing_yaw turned by ``turn`` towards ``heading`` (default: towards the hinge)."""
    latch_x, latch_y = door.latch_direction
    towards = math.atan2(-latch_y, -latch_x) if heading is None else heading
    side = 1.0 if wrap_angle(towards - door.facing_yaw) >= 0.0 else -1.0
    return wrap_angle(door.facing_yaw + side * turn)


def _wall_faces(door: DoorGeometry) -> tuple[float, float]:
    """s of the frame's face on the approach side and on the far side (m).

    The slab is centred on s = -swing_sign t / 2 and the posts stand out of it by the
    protrusion on both faces (:func:`~footstep_planner.door.wall_obstacles`).
    """
    centre = -door.swing_sign * door.wall_thickness / 2.0
    half = door.wall_thickness / 2.0 + door.post_protrusion
    return centre + half, centre - half


def _on_centre_line(door: DoorGeometry, normal_offset: float, yaw: float) -> Pose2D:
    x, y = door.to_world(door.clear_opening / 2.0, normal_offset)
    return Pose2D(x, y, yaw)
