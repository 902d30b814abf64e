"""Goal poses from a door estimate, and when to re-plan through a moving door.

All poses are body poses (the stance centre) in ``odom``; door coordinates
(u along the wall from hinge to latch, s along the normal towards the robot)
are defined in :mod:`~footstep_planner.door`.
"""

from __future__ import annotations

import math

from door_contract.vocabulary import DoorOpening
from footstep_planner.door import DoorGeometry
from footstep_planner.footstep import Pose2D
from footstep_planner.geometry import wrap_angle
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.validation import FieldRange, check_range

__all__ = ["DEFAULT_BEYOND_LATCH", "DEFAULT_HANDLE_OFFSET", "DEFAULT_PULL_SWEEP_ANGLE", "DEFAULT_REACH",
           "DEFAULT_SWEEP_CLEARANCE", "PUSH_LINE_CLEARANCE", "pull_passage_waypoints", "push_line", "push_stand_pose",
           "replan_needed", "stand_pose_for_opening", "through_door_pose", "towards_latch"]

DEFAULT_REACH = 0.50
"""Distance from the door plane to the robot base when opening (m); 0.45-0.55 suits TALOS."""
DEFAULT_HANDLE_OFFSET = 0.20
"""Lateral distance from the base to the handle (m): puts it before the handle-side shoulder."""
DEFAULT_SWEEP_CLEARANCE = 0.05
"""Gap kept between the robot's footprint and a pull door's swing (m)."""
DEFAULT_PULL_SWEEP_ANGLE = 0.45
"""How far a pull door swings while the robot pulls it (rad): the pull's 0.35 rad and a margin."""
DEFAULT_BEYOND_LATCH = 0.05
"""Base past a pull door's latch edge along the wall (m), between the handle and the gap."""


def stand_pose_for_opening(door: DoorGeometry, options: FootstepPlannerOptions,
                           reach: float = DEFAULT_REACH,
                           handle_offset: float = DEFAULT_HANDLE_OFFSET,
                           sweep_clearance: float = DEFAULT_SWEEP_CLEARANCE,
                           sweep_half_depth: float | None = None,
                           pull_sweep_angle: float = DEFAULT_PULL_SWEEP_ANGLE,
                           beyond_latch: float = DEFAULT_BEYOND_LATCH) -> Pose2D:
    """Where the robot stands, facing the door, to grasp and open it.

    The base stands ``reach`` m in front of the door plane (s = reach).

    PUSH doors: along the wall it stands ``handle_offset`` m on the hinge side of the
    handle (u = u_handle - handle_offset, u_handle = leaf width - the handle's distance
    from the free edge), so the handle is in front of the handle-side arm.

    PULL doors ([Banerjee 2015] Fig. 2: pull with one hand, block with the other): the base
    stands ``beyond_latch`` m past the latch edge (u = W + beyond_latch). The hinge-side
    hand reaches the handle; the other hand reaches the gap that opens at the free edge,
    to go behind the leaf; and from there the robot can turn towards the hinge and sweep
    the leaf open (:func:`pull_passage_waypoints`). The leaf swings towards the robot
    through the sector of radius R = W + thickness + clearance up to
    ``pull_sweep_angle``, which the footprint (``sweep_half_depth`` deep ahead of the
    base when given: while opening, the arms are on the handle) must miss: with
    near = reach - half_depth, the sector never reaches the footprint's near face when
    near >= R sin(angle); otherwise the footprint must be beside the whole arc,
    u - half_width >= sqrt(R^2 - near^2).
    """
    check_range("reach", reach, FieldRange(0.2, 1.5, "m"))
    check_range("handle_offset", handle_offset, FieldRange(-1.0, 1.0, "m"))
    check_range("sweep_clearance", sweep_clearance, FieldRange(0.0, 0.5, "m"))
    check_range("pull_sweep_angle", pull_sweep_angle, FieldRange(0.0, math.pi / 2, "rad", low_open=True))
    check_range("beyond_latch", beyond_latch, FieldRange(-0.5, 1.0, "m"))
    if door.opening is DoorOpening.PULL:
        along = max(door.leaf_width + beyond_latch,
                    _outside_sweep(door, options, reach, sweep_clearance, sweep_half_depth, pull_sweep_angle))
    else:
        along = door.leaf_width - door.handle_offset - handle_offset
    x, y = door.to_world(along, reach)
    return Pose2D(x, y, door.facing_yaw)


def push_stand_pose(door: DoorGeometry, options: FootstepPlannerOptions, reach: float, offset: float) -> Pose2D:
    """The stance that opens a push door sideways (:mod:`~footstep_planner.push_passage`): at
    s = ``reach`` (m) in front of the door plane, on the side-step line (:func:`push_line`),
    facing along the wall from the hinge towards the latch (its back to the hinge)."""
    check_range("reach", reach, FieldRange(0.2, 1.5, "m"))
    x, y = door.to_world(push_line(door, options, offset), reach)
    return Pose2D(x, y, towards_latch(door))


PUSH_LINE_CLEARANCE = 0.02
"""Gap kept between the body box's front and the latch-side post on a push door's line (m)."""


def push_line(door: DoorGeometry, options: FootstepPlannerOptions, offset: float) -> float:
    """u of a sideways push door's stand pose and side-step line (m): the opening's centre W/2
    moved ``offset`` towards the latch, at most as far as keeps the body box's front (it faces
    the latch; half depth + offset + margin ahead of the base) :data:`PUSH_LINE_CLEARANCE` off
    the post. A 0.80 m door allows 0.07 m of TALOS's 0.12."""
    check_range("offset", offset, FieldRange(-0.5, 0.5, "m"))
    front = options.body_half_depth + options.body_offset + options.body_margin
    room = max(0.0, door.clear_opening / 2.0 - front - PUSH_LINE_CLEARANCE)
    return door.clear_opening / 2.0 + min(offset, room)


def towards_latch(door: DoorGeometry) -> float:
    """Yaw of a robot facing along the wall from the hinge towards the latch (rad)."""
    latch_x, latch_y = door.latch_direction
    return math.atan2(latch_y, latch_x)


def _outside_sweep(door: DoorGeometry, options: FootstepPlannerOptions, reach: float,
                   clearance: float, sweep_half_depth: float | None, sweep_angle: float) -> float:
    """Smallest u that keeps the footprint, facing the door at s = reach, out of the swing."""
    half_width, half_depth = _footprint_half_extents(options)
    if sweep_half_depth is not None:
        half_depth = sweep_half_depth
    radius = door.leaf_width + door.leaf_thickness + clearance
    near_face = reach - half_depth
    if near_face >= radius * math.sin(sweep_angle):
        return -math.inf
    return half_width + math.sqrt(radius * radius - max(near_face, 0.0) ** 2)


def pull_passage_waypoints(door: DoorGeometry, stand: Pose2D, distance_beyond: float = 1.0) -> tuple[Pose2D, ...]:
    """Body poses through a PULL door that the other hand blocks ([Banerjee 2015] Fig. 2).

    From the stand pose beside the latch edge, with the blocking hand behind the leaf near
    its free edge: (1) turn in place to face along the wall towards the hinge: the hand
    sweeps round and pushes the leaf open (to ~1 rad in the simulation); (2) walk along
    the wall to the opening's centre line, the hand pushing the leaf further; (3) turn to
    face the doorway: the leaf comes to rest on the body's hinge side; (4) walk through
    (:func:`through_door_pose`) while the leaf slides along the body and closes behind it.
    The leaf is not an obstacle of these legs (the robot pushes it); wall and posts are.
    """
    check_range("distance_beyond", distance_beyond, FieldRange(0.0, 10.0, "m", low_open=True))
    _, reach = door.to_door(stand.x, stand.y)
    latch_x, latch_y = door.latch_direction
    towards_hinge = math.atan2(-latch_y, -latch_x)
    centre_x, centre_y = door.to_world(door.clear_opening / 2.0, reach)
    return (Pose2D(stand.x, stand.y, towards_hinge),
            Pose2D(centre_x, centre_y, towards_hinge),
            Pose2D(centre_x, centre_y, door.facing_yaw),
            through_door_pose(door, distance_beyond))


def _footprint_half_extents(options: FootstepPlannerOptions) -> tuple[float, float]:
    """Half width and half depth of a rectangle holding the body and both soles (with margins)."""
    sole_half_width = (options.nominal_foot_separation + options.foot_width) / 2.0
    half_width = max(options.body_half_width + options.body_margin,
                     sole_half_width + options.foot_margin)
    half_depth = max(options.body_reach_depth,
                     options.foot_length / 2.0 + options.foot_margin)
    return half_width, half_depth


def through_door_pose(door: DoorGeometry, distance_beyond: float = 1.0) -> Pose2D:
    """A pose ``distance_beyond`` m past the door plane, centred on the clear opening,
    facing away from the approach side (the way the robot walks through)."""
    check_range("distance_beyond", distance_beyond, FieldRange(0.0, 10.0, "m", low_open=True))
    x, y = door.to_world(door.clear_opening / 2.0, -distance_beyond)
    return Pose2D(x, y, door.facing_yaw)


def replan_needed(previous_door_angle: float, measured_door_angle: float,
                  threshold: float = 0.1) -> bool:
    """Re-plan the passage when the door has swung by more than ``threshold`` rad.

    The seed system passed the door with a dynamic potential field because the
    door could swing shut; here the plan is recomputed against the newly
    measured leaf whenever |measured - previous| (wrapped) exceeds the threshold.
    """
    check_range("previous_door_angle", previous_door_angle, FieldRange(-math.inf, math.inf, "rad"))
    check_range("measured_door_angle", measured_door_angle, FieldRange(-math.inf, math.inf, "rad"))
    check_range("threshold", threshold, FieldRange(0.0, math.pi, "rad", low_open=True))
    return abs(wrap_angle(measured_door_angle - previous_door_angle)) > threshold
