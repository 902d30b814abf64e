"""The double-support polygon a walk starts from, and the CoM brought into it.

placo's LIPM pattern starts at rest: its first ZMP is the CoM's ground projection, which the
QP keeps ``zmp_margin`` inside the supports (Kajita's preview control; the ZMP of a CoM at rest
is the CoM, ``p = c - (h/g) c''``). A robot that stood leaning against a door (the stabiliser
shifts the CoM up to 10 cm to hold a force, :mod:`~door_sim_bridge.walking.stabilizer`) can
have its CoM beyond that margin, and then no pattern exists ("Failed to plan CoM trajectory":
a Monte-Carlo pull door's walk through, the CoM 10.4 cm ahead of the feet, refused 4 times).
The walk is planned from the nearest point of the shrunk polygon instead; the DCM feedback
absorbs the few centimetres between the two.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from scipy.spatial import ConvexHull

__all__ = ["into_polygon", "signed_margin", "support_polygon"]

_CORNERS = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])


def support_polygon(soles: Iterable[np.ndarray], length: float, width: float, margin: float = 0.0) -> np.ndarray:
    """Convex hull (CCW, (M, 2), m) of the sole rectangles (``length`` × ``width``, each side
    brought ``margin`` in) of the 4×4 sole frames ``soles``."""
    half = np.array([max(length / 2 - margin, 1e-4), max(width / 2 - margin, 1e-4)])
    corners = np.vstack([sole[:2, 3] + (_CORNERS * half) @ sole[:2, :2].T for sole in soles])
    vertices: np.ndarray = corners[ConvexHull(corners).vertices]  # counter-clockwise in 2-D
    return vertices


def signed_margin(point: np.ndarray, polygon: np.ndarray) -> float:
    """How far (m) ``point`` (2,) is inside the convex CCW ``polygon``: its distance to the
    nearest edge's line, + inside; outside, − its distance to the boundary."""
    point = np.asarray(point, dtype=float)
    inside = _inward_distances(point, polygon)
    if np.all(inside >= 0.0):
        return float(inside.min())
    return -float(np.linalg.norm(_nearest_on_boundary(point, polygon) - point))


def into_polygon(point: np.ndarray, polygon: np.ndarray) -> np.ndarray:
    """``point`` (2,) itself when inside the convex CCW ``polygon``, else its nearest point on
    the boundary."""
    point = np.asarray(point, dtype=float)
    if np.all(_inward_distances(point, polygon) >= 0.0):
        return point
    return _nearest_on_boundary(point, polygon)


def _inward_distances(point: np.ndarray, polygon: np.ndarray) -> np.ndarray:
    """Signed distance of ``point`` to each edge's line, + on the polygon's side."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    inward = np.column_stack([-edges[:, 1], edges[:, 0]]) / np.linalg.norm(edges, axis=1)[:, None]
    distances: np.ndarray = np.einsum("ij,ij->i", inward, point - polygon)
    return distances


def _nearest_on_boundary(point: np.ndarray, polygon: np.ndarray) -> np.ndarray:
    edges = np.roll(polygon, -1, axis=0) - polygon
    along = np.clip(np.einsum("ij,ij->i", point - polygon, edges) / np.einsum("ij,ij->i", edges, edges), 0.0, 1.0)
    nearest = polygon + along[:, None] * edges
    closest: np.ndarray = nearest[np.argmin(np.linalg.norm(nearest - point, axis=1))]
    return closest
