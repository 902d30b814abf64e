"""The door as the planner sees it: wall with a doorway, frame posts, a leaf on a hinge.

Door coordinates (u, s), metres, anchored at the hinge axis:

* ``u`` runs along the wall from the hinge towards the latch (free) edge;
* ``s`` runs along the door normal towards the approach side (the robot).

A world point is ``hinge + u * latch_direction + s * normal``.  The door
plane is ``s = 0`` (the plane of the closed leaf's hinge face).  For a PUSH
door the wall slab lies on the robot's side of that plane (``0 <= s <= t``)
and the leaf swings to ``s < 0``; for a PULL door the wall lies behind
(``-t <= s <= 0``) and the leaf swings towards the robot, ``s > 0``.  The
clear opening is ``0 <= u <= clear_opening``: the hinge axis sits on the
hinge-side jamb, so a leaf open at 90 degrees lies beside the opening.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from door_contract.vocabulary import DoorOpening, HingeSide
from footstep_planner.geometry import wrap_angle
from footstep_planner.obstacles import Obstacle, Point
from footstep_planner.validation import FieldRange, check_range

__all__ = ["DoorGeometry", "door_obstacles", "leaf_obstacle", "sweep_obstacle", "wall_obstacles"]

_SWEEP_ARC_STEP = 0.3
"""Angular spacing of the polygon that over-approximates the leaf's swept arc (rad)."""


@dataclass(frozen=True)
class DoorGeometry:
    """A door estimate in ``odom`` (m, rad).

    Defaults are the DRC Finals door: 36 in (0.914 m) leaf, about 0.87 m of
    clear opening between the jambs.
    """

    hinge_x: float
    """Hinge axis position x (m)."""
    hinge_y: float
    """Hinge axis position y (m)."""
    normal_yaw: float
    """Yaw of the door normal pointing to the approach side, towards the robot (rad)."""
    hinge_side: HingeSide = HingeSide.LEFT
    opening: DoorOpening = DoorOpening.PUSH
    angle: float = 0.0
    """Door opening angle: 0 closed, positive towards the swing side (rad), [-0.2, 3]."""
    leaf_width: float = 0.914
    """Leaf width, hinge axis to free edge (m), (0.3, 2]."""
    clear_opening: float = 0.87
    """Free width between the jambs (m), (0.3, leaf_width]."""
    wall_thickness: float = 0.10
    """Wall thickness (m), (0, 1]."""
    leaf_thickness: float = 0.04
    """Leaf thickness (m), (0, 0.2]."""
    post_width: float = 0.05
    """Width of each frame post (jamb) along the wall (m), (0, 0.5]."""
    post_protrusion: float = 0.02
    """How far the frame (casing) stands out of each wall face (m), [0, 0.2]."""
    wall_extent: float = 3.0
    """Length of wall on each side of the doorway (m), (0, 100]."""
    handle_offset: float = 0.07
    """Distance of the handle from the leaf's free edge (m), (0, leaf_width)."""

    def __post_init__(self) -> None:
        for name in ("hinge_x", "hinge_y", "normal_yaw"):
            check_range(name, getattr(self, name), FieldRange(-math.inf, math.inf, ""), "door")
        for name, allowed in self._ranges().items():
            check_range(name, getattr(self, name), allowed, "door")

    def _ranges(self) -> dict[str, FieldRange]:
        """Allowed ranges of the dimensions (some depend on the leaf width)."""
        return {
            "angle": FieldRange(-0.2, 3.0, "rad"),
            "leaf_width": FieldRange(0.3, 2.0, "m", low_open=True),
            "clear_opening": FieldRange(0.3, self.leaf_width, "m", low_open=True),
            "wall_thickness": FieldRange(0.0, 1.0, "m", low_open=True),
            "leaf_thickness": FieldRange(0.0, 0.2, "m", low_open=True),
            "post_width": FieldRange(0.0, 0.5, "m", low_open=True),
            "post_protrusion": FieldRange(0.0, 0.2, "m"),
            "wall_extent": FieldRange(0.0, 100.0, "m", low_open=True),
            "handle_offset": FieldRange(0.0, self.leaf_width, "m", low_open=True,
                                        high_open=True),
        }

    @classmethod
    def from_handle(cls, handle_x: float, handle_y: float, normal_yaw: float,
                    hinge_side: HingeSide, opening: DoorOpening,
                    **dimensions: float) -> DoorGeometry:
        """The door whose handle (projected on the door plane) is at (handle_x, handle_y).

        This is what the detector measures (``/door/handle_pose``: x axis =
        door normal towards the robot).  ``dimensions`` are the other fields.
        """
        probe = cls(0.0, 0.0, normal_yaw, hinge_side, opening, **dimensions)
        latch = probe.latch_direction
        back = probe.leaf_width - probe.handle_offset
        return cls(handle_x - back * latch[0], handle_y - back * latch[1], normal_yaw,
                   hinge_side, opening, **dimensions)

    def with_angle(self, angle: float) -> DoorGeometry:
        """The same door at another opening angle (rad)."""
        return replace(self, angle=angle)

    @property
    def normal(self) -> Point:
        """Unit door normal towards the approach side."""
        return (math.cos(self.normal_yaw), math.sin(self.normal_yaw))

    @property
    def latch_direction(self) -> Point:
        """Unit vector along the wall from the hinge to the latch edge.

        Facing the door the robot looks along -n, so its left is
        ``z x (-n) = -(z x n)``: a LEFT hinge puts the latch at ``+ z x n``.
        """
        normal_x, normal_y = self.normal
        sign = 1.0 if self.hinge_side is HingeSide.LEFT else -1.0
        return (-sign * normal_y, sign * normal_x)

    @property
    def swing_sign(self) -> float:
        """+1 when the leaf swings towards the robot (PULL), -1 away from it (PUSH)."""
        return 1.0 if self.opening is DoorOpening.PULL else -1.0

    @property
    def facing_yaw(self) -> float:
        """Yaw of a robot facing the door from the approach side (rad)."""
        return wrap_angle(self.normal_yaw + math.pi)

    def to_world(self, along: float, normal_offset: float) -> Point:
        """World point of door coordinates (u = ``along``, s = ``normal_offset``)."""
        latch_x, latch_y = self.latch_direction
        normal_x, normal_y = self.normal
        return (self.hinge_x + along * latch_x + normal_offset * normal_x,
                self.hinge_y + along * latch_y + normal_offset * normal_y)

    def to_door(self, x: float, y: float) -> Point:
        """Door coordinates (u, s) of a world point."""
        dx, dy = x - self.hinge_x, y - self.hinge_y
        latch_x, latch_y = self.latch_direction
        normal_x, normal_y = self.normal
        return (dx * latch_x + dy * latch_y, dx * normal_x + dy * normal_y)

    def leaf_direction(self, angle: float) -> Point:
        """Door coordinates (du, ds) of the unit vector from hinge to free edge at ``angle``."""
        return (math.cos(angle), self.swing_sign * math.sin(angle))

    @property
    def handle_point(self) -> Point:
        """World position of the handle on the door plane (closed leaf)."""
        return self.to_world(self.leaf_width - self.handle_offset, 0.0)


def door_obstacles(door: DoorGeometry,
                   sweep: tuple[float, float] | None = None) -> tuple[Obstacle, ...]:
    """The wall on both sides of the doorway, the two frame posts, the leaf at ``door.angle``,
    and, when ``sweep = (a, b)`` is given, the region the leaf sweeps from angle a to b."""
    leaf = leaf_obstacle(door, door.angle)
    if sweep is None:
        return (*wall_obstacles(door), leaf)
    return (*wall_obstacles(door), leaf, sweep_obstacle(door, *sweep))


def wall_obstacles(door: DoorGeometry) -> tuple[Obstacle, ...]:
    """Wall segments beside the doorway and the two frame posts (jambs)."""
    slab_centre = door.wall_thickness / 2.0 * -door.swing_sign
    post_depth = door.wall_thickness + 2.0 * door.post_protrusion
    opening, post = door.clear_opening, door.post_width
    latch_wall_start = opening + post
    return (
        _door_rectangle(door, "wall_hinge_side", (-post - door.wall_extent, -post),
                        slab_centre, door.wall_thickness),
        _door_rectangle(door, "wall_latch_side",
                        (latch_wall_start, latch_wall_start + door.wall_extent),
                        slab_centre, door.wall_thickness),
        _door_rectangle(door, "post_hinge_side", (-post, 0.0), slab_centre, post_depth),
        _door_rectangle(door, "post_latch_side", (opening, latch_wall_start), slab_centre,
                        post_depth),
    )


def _door_rectangle(door: DoorGeometry, name: str, along: tuple[float, float],
                    normal_centre: float, depth: float) -> Obstacle:
    """A rectangle over ``along`` = (u0, u1) of the wall line, ``depth`` thick about s = centre."""
    centre = door.to_world((along[0] + along[1]) / 2.0, normal_centre)
    latch_x, latch_y = door.latch_direction
    yaw = math.atan2(latch_y, latch_x)
    return Obstacle.rectangle(name, centre, yaw, along[1] - along[0], depth)


def leaf_obstacle(door: DoorGeometry, angle: float) -> Obstacle:
    """The door leaf at ``angle``: a rectangle from the hinge to the free edge, thick towards
    the swing side (so it never pokes into the wall slab)."""
    return Obstacle.hull("door_leaf", _leaf_corners(door, angle))


def _leaf_corners(door: DoorGeometry, angle: float) -> np.ndarray:
    """World corners (4, 2) of the leaf at ``angle``: hinge + a d + b e, a in [0, W], b in [0, T],
    with d the leaf direction and e the leaf's swing-side normal."""
    du, ds = door.leaf_direction(angle)
    eu, es = -door.swing_sign * ds, door.swing_sign * du  # d turned towards the swing side
    width, thick = door.leaf_width, door.leaf_thickness
    local = [(0.0, 0.0), (width * du, width * ds),
             (width * du + thick * eu, width * ds + thick * es), (thick * eu, thick * es)]
    return np.array([door.to_world(u, s) for u, s in local])


def sweep_obstacle(door: DoorGeometry, start_angle: float, end_angle: float) -> Obstacle:
    """A convex polygon containing every pose of the leaf between the two angles (rad).

    The leaf corners are sampled every <= 0.3 rad; the free-edge corners are
    pushed out by 1 / cos(step / 2) (< 1 % of the width) so the chords between samples lie outside
    the true arc (circumscribed polygon).  The hull is convex, so for sweeps
    beyond pi it over-approximates; door sweeps are at most about pi / 2.
    """
    low, high = sorted((start_angle, end_angle))
    count = max(2, math.ceil((high - low) / _SWEEP_ARC_STEP) + 1)
    angles = np.linspace(low, high, count)
    grow = 1.0 / math.cos((high - low) / (count - 1) / 2.0)
    hinge = np.array([door.hinge_x, door.hinge_y])
    points = []
    for angle in angles:
        corners = _leaf_corners(door, float(angle))
        points.extend([corners[0], corners[3]])
        points.extend([hinge + grow * (corners[1] - hinge), hinge + grow * (corners[2] - hinge)])
    return Obstacle.hull("door_sweep", np.array(points))
