"""Obstacles: named convex polygons of the plane (walls, door posts, the door leaf, its sweep)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from footstep_planner.errors import FootstepPlannerError
from footstep_planner.geometry import FloatArray, convex_hull, rectangle_corners

__all__ = ["Obstacle", "Point"]

Point = tuple[float, float]


@dataclass(frozen=True)
class Obstacle:
    """A convex polygon the robot's feet and body must not touch.

    ``vertices`` are counter-clockwise, in ``odom`` (m), at least 3, with no
    repeated or collinear vertex (the constructors below guarantee it).
    """

    name: str
    vertices: tuple[Point, ...]

    def __post_init__(self) -> None:
        points = np.asarray(self.vertices, dtype=float)
        if points.ndim != 2 or points.shape[0] < 3 or points.shape[1] != 2:
            raise FootstepPlannerError(f"obstacle {self.name!r} needs at least 3 (x, y) vertices",
                                       field="vertices")
        if not np.all(np.isfinite(points)):
            raise FootstepPlannerError(f"obstacle {self.name!r} has a non-finite vertex",
                                       field="vertices")
        if not _is_strictly_convex_ccw(points):
            raise FootstepPlannerError(
                f"obstacle {self.name!r} is not a strictly convex counter-clockwise polygon",
                field="vertices")

    @classmethod
    def rectangle(cls, name: str, centre: Point, yaw: float, length: float,
                  width: float) -> Obstacle:
        """An oriented rectangle: ``length`` along ``yaw``, ``width`` across (m, > 0)."""
        if not (length > 0.0 and width > 0.0):
            raise FootstepPlannerError(
                f"obstacle {name!r} needs a positive length and width (m), got {length}, {width}",
                field="vertices")
        corners = rectangle_corners(np.array([centre[0]]), np.array([centre[1]]),
                                    np.array([yaw]), length / 2.0, width / 2.0)[0]
        return cls(name, _as_points(corners))

    @classmethod
    def segment(cls, name: str, start: Point, end: Point, thickness: float = 0.01) -> Obstacle:
        """A line segment, modelled as a rectangle ``thickness`` m thick centred on it."""
        length = math.hypot(end[0] - start[0], end[1] - start[1])
        centre = ((start[0] + end[0]) / 2.0, (start[1] + end[1]) / 2.0)
        yaw = math.atan2(end[1] - start[1], end[0] - start[0])
        return cls.rectangle(name, centre, yaw, length, thickness)

    @classmethod
    def hull(cls, name: str, points: FloatArray) -> Obstacle:
        """The convex hull of ``points`` (shape (P, 2))."""
        return cls(name, _as_points(convex_hull(points)))

    @property
    def array(self) -> FloatArray:
        """The vertices as a (K, 2) array."""
        return np.asarray(self.vertices, dtype=float)


def _as_points(array: FloatArray) -> tuple[Point, ...]:
    """A (K, 2) array as a tuple of (x, y) float pairs."""
    return tuple((float(x), float(y)) for x, y in array)


def _is_strictly_convex_ccw(points: FloatArray) -> bool:
    """Every consecutive triple turns left (positive cross product)."""
    edges = np.roll(points, -1, axis=0) - points
    following = np.roll(edges, -1, axis=0)
    cross = edges[:, 0] * following[:, 1] - edges[:, 1] * following[:, 0]
    return bool(np.all(cross > 1e-12))
