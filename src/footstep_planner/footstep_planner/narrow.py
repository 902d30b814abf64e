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

A pull door whose leaf the other hand holds open ([Banerjee 2015] Fig. 2) can be passed
sideways even where the body would fit facing (:class:`PullPassage`): turning to face the
doorway takes the hand off the leaf, and the leaf then swings into the arm and shoulder
on the hinge side, 40-200 N sideways while the robot walks through. Sideways, facing the
hinge, the hand stays on the leaf until the body is in the doorway; but as the hand nears
the wall plane the leaf closes onto it near the hinge axis (:func:`hold_leaf_line`), and on
the physical robot that is no more reliable yet, so facing is the default.
"""

from __future__ import annotations

import math
from enum import Enum

from door_contract.vocabulary import DoorOpening
from footstep_planner.door import DoorGeometry
from footstep_planner.footstep import Pose2D
from footstep_planner.geometry import wrap_angle
from footstep_planner.goals import through_door_pose
from footstep_planner.legs import Leg
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.pruning import LegPruning

__all__ = ["PASSAGE_CLEARANCE", "SIDEWAYS", "PullPassage", "hold_leaf_line", "passage_legs", "passage_turn"]


class PullPassage(Enum):
    """How the robot passes a pull door that its other hand blocks."""

    SIDEWAYS = "sideways"
    """Side-step through facing the hinge, the blocking hand on the leaf (:func:`hold_leaf_line`)."""
    FACING = "facing"
    """Turn to face the doorway (the hand leaves the leaf) and walk through."""


PASSAGE_CLEARANCE = 0.01
"""Gap kept between the body (with its margin) and each jamb while passing (m)."""
WALL_CLEARANCE = 0.05
"""Gap between the turning body and the frame (or a push door's leaf) either side (m)."""
SIDEWAYS = LegPruning(yaw_window=0.1, corridor=0.05)
"""While side-stepping through: the feet within 0.1 rad of sideways, the stance centre within
5 cm of the centre line (:mod:`~footstep_planner.pruning`)."""


def passage_turn(door: DoorGeometry, options: FootstepPlannerOptions, sideways: bool = False) -> float | None:
    """The body's yaw from facing the door while it passes (rad): 0 when it fits facing,
    pi/2 (sideways) when only that fits, None when it does not fit even sideways.
    ``sideways`` asks for pi/2 whenever the body fits so (a pull door's blocking hand)."""
    across = options.body_half_width + options.body_margin
    deep = options.body_reach_depth  # the box may sit ahead of the centre
    half_gap = door.clear_opening / 2.0 - PASSAGE_CLEARANCE
    fits_sideways = deep <= half_gap + _SLACK
    if across <= half_gap + _SLACK and not (sideways and fits_sideways):
        return 0.0
    if fits_sideways:
        return math.pi / 2.0
    return None


_SLACK = 1e-9
"""Float noise allowed in the fit tests (m)."""


def passage_legs(door: DoorGeometry, options: FootstepPlannerOptions, distance_beyond: float,
                 heading: float | None = None, hold_leaf: float | None = None) -> tuple[Leg, ...]:
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

    ``hold_leaf`` (m): a pull door whose leaf the other hand holds open: sideways whenever
    the body fits so, along the centre line moved this far towards the body's back
    (:func:`hold_leaf_line`).
    """
    final = through_door_pose(door, distance_beyond)
    turn = passage_turn(door, options, sideways=hold_leaf is not None)
    if not turn:
        return (Leg(final, "through the doorway"),)
    yaw = _turned_yaw(door, turn, heading)
    radius = math.hypot(options.body_half_width + options.body_margin, options.body_reach_depth) + WALL_CLEARANCE
    near_face, far_face = _wall_faces(door)
    beyond = far_face - radius
    if door.opening is DoorOpening.PUSH:
        around_leaf = door.leaf_width + door.leaf_thickness + radius
        beyond = min(beyond, -math.sqrt(max(around_leaf ** 2 - (door.clear_opening / 2.0) ** 2, 0.0)))
    if distance_beyond < -beyond:
        final = through_door_pose(door, -beyond)
    line = door.clear_opening / 2.0 if hold_leaf is None else hold_leaf_line(door, options, yaw, hold_leaf)
    return (Leg(_on_line(door, line, near_face + radius, yaw), "turn sideways before the doorway"),
            Leg(_on_line(door, line, beyond, yaw), "side-step through the doorway", SIDEWAYS),
            Leg(final, "turn to face away"))


def hold_leaf_line(door: DoorGeometry, options: FootstepPlannerOptions, yaw: float, shift: float) -> float:
    """u of the line a sideways body holding a pulled leaf open side-steps along (m): the
    opening's centre moved ``shift`` towards the body's back (it faces the hinge), at most as
    far as keeps the body box's back, b - offset + margin behind the centre, the passage
    clearance off the jamb there.

    The blocking hand is ahead of the body, towards the hinge, on the leaf; held h from the
    hinge axis, the closer's torque tau presses it with tau / h. As the hand reaches the wall
    plane the leaf closes onto it, and h there is u_line minus the hand's reach (TALOS: 0.50 m
    ahead). On the centre line the hand came within ~5 cm of the axis and 7.6 N·m pressed it
    with 110-180 N, sideways for the robot, which fell. Passage rig (TALOS, 0.87 m DRC door,
    trials 0-4 per hinge, 1.5 s steps): facing the doorway 3/10 through; sideways with the
    shift 0.115 m 2/10, 0.14 m 7/10 (left 5/5, right 2/5), 0.16 m 5/9 (left 5/5, right
    0/4); 0.14 m again after the body box lost its 4 cm of slack behind (legs moved by
    < 5 mm) 0/6. Millimetres decide: the hand is still only 5-12 cm from the axis there, and
    what would remove the pinch is bringing the hand in towards the body before the wall
    plane (an arm motion between two walks), not a line.
    """
    back = options.body_half_depth - options.body_offset + options.body_margin
    shift = min(shift, max(0.0, door.clear_opening / 2.0 - PASSAGE_CLEARANCE - back))
    latch_x, latch_y = door.latch_direction
    faces_hinge = math.cos(yaw) * latch_x + math.sin(yaw) * latch_y < 0.0
    return door.clear_opening / 2.0 + (shift if faces_hinge else -shift)


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


def _on_line(door: DoorGeometry, along: float, normal_offset: float, yaw: float) -> Pose2D:
    """The pose at door coordinates (``along``, ``normal_offset``) with ``yaw``."""
    x, y = door.to_world(along, normal_offset)
    return Pose2D(x, y, yaw)
