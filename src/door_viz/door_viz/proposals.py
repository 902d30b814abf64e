"""What the FSM is offered, as markers in ``odom`` (ROS-free): footsteps, the hand's path of a
trajectory, the door estimate and the door's swing.

The door's swing: with the estimate's corners ``h`` (bottom, hinge side) and ``f`` (bottom,
free edge), the leaf's unit direction ``u = (f − h)/|f − h|`` and the door normal ``n``
(towards the robot), the leaf opened by θ has its free edge at

    h + w (cos θ · u + sin θ · s),   s = −n for a push door (away from the robot), +n for pull,

with ``w`` the door width. The swept sector θ ∈ [0, 90°] is drawn as a fan, the leaf at the
FSM's current door angle as a rectangle.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from door_contract.converters.footsteps import FootPlacement
from door_contract.geometry import planar_pose
from door_contract.marker_shapes import MarkerKind, MarkerShape
from door_contract.payloads import DoorEstimate
from door_contract.vocabulary import Foot

__all__ = ["door_shapes", "footstep_shapes", "hand_path_shapes", "leaf_axes", "swing_shapes"]

LEFT_FOOT_RGBA = (0.12, 0.47, 0.71, 0.8)
RIGHT_FOOT_RGBA = (1.0, 0.5, 0.05, 0.8)
DOOR_RGBA = (0.1, 0.9, 0.1, 1.0)
SWING_RGBA = (0.9, 0.8, 0.1, 0.25)
HAND_RGBA = {"left": (0.3, 0.6, 1.0, 1.0), "right": (1.0, 0.3, 0.3, 1.0)}
SOLE_THICKNESS = 0.01  # m
SWING_SEGMENTS = 18  # fan triangles over 90°


def footstep_shapes(steps: Sequence[FootPlacement], foot_length: float, foot_width: float) -> list[MarkerShape]:
    """One sole-sized box per step (blue left, orange right) and a line through their centres."""
    shapes = []
    for index, step in enumerate(steps):
        rgba = LEFT_FOOT_RGBA if step.foot is Foot.LEFT else RIGHT_FOOT_RGBA
        shapes.append(MarkerShape("footsteps", index, MarkerKind.CUBE, rgba,
                                  (foot_length, foot_width, SOLE_THICKNESS),
                                  pose=planar_pose(step.x, step.y, step.yaw, SOLE_THICKNESS / 2.0)))
    if len(steps) > 1:
        centres = np.array([[s.x, s.y, SOLE_THICKNESS] for s in steps])
        shapes.append(MarkerShape("footsteps", len(steps), MarkerKind.LINE_STRIP, (0.6, 0.6, 0.6, 0.8),
                                  (0.01, 0.0, 0.0), points=centres))
    return shapes


def hand_path_shapes(paths: Mapping[str, np.ndarray], min_travel: float = 0.01) -> list[MarkerShape]:
    """The path (T×3, odom) of each hand that travels more than ``min_travel`` m, with a
    sphere where it ends."""
    shapes = []
    for index, (side, points) in enumerate(sorted(paths.items())):
        points = np.asarray(points, dtype=float)
        if len(points) < 2 or np.max(np.linalg.norm(points - points[0], axis=1)) < min_travel:
            continue
        rgba = HAND_RGBA.get(side, (1.0, 1.0, 1.0, 1.0))
        shapes.append(MarkerShape("hand_path", 2 * index, MarkerKind.LINE_STRIP, rgba, (0.015, 0.0, 0.0),
                                  points=points))
        end = np.eye(4)
        end[:3, 3] = points[-1]
        shapes.append(MarkerShape("hand_path", 2 * index + 1, MarkerKind.SPHERE, rgba, (0.04, 0.04, 0.04), pose=end))
    return shapes


def door_shapes(estimate: DoorEstimate) -> list[MarkerShape]:
    """The estimate's outline, hinge axis and handle."""
    corners = np.array(estimate.corners, dtype=float)
    handle = np.eye(4)
    handle[:3, 3] = estimate.handle_position
    return [
        MarkerShape("door", 0, MarkerKind.LINE_STRIP, DOOR_RGBA, (0.02, 0.0, 0.0), points=np.vstack([corners, corners[:1]])),
        MarkerShape("door", 1, MarkerKind.LINE_STRIP, (0.1, 0.5, 0.1, 1.0), (0.05, 0.0, 0.0), points=corners[[0, 3]]),
        MarkerShape("door", 2, MarkerKind.SPHERE, (0.9, 0.1, 0.1, 1.0), (0.06, 0.06, 0.06), pose=handle),
    ]


def leaf_axes(estimate: DoorEstimate, opening: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """Hinge point ``h``, leaf direction ``u``, swing direction ``s`` (unit, horizontal) and the
    leaf's width (module docstring)."""
    corners = np.array(estimate.corners, dtype=float)
    hinge, free = corners[0], corners[1]
    leaf = free - hinge
    leaf[2] = 0.0
    u = leaf / np.linalg.norm(leaf)
    normal = np.array(estimate.normal, dtype=float)
    normal[2] = 0.0
    normal -= (normal @ u) * u  # exactly perpendicular to the leaf
    s = normal / np.linalg.norm(normal) * (-1.0 if opening == "push" else 1.0)
    return hinge, u, s, float(np.linalg.norm(free - hinge))


def swing_shapes(estimate: DoorEstimate, opening: str, door_angle: float) -> list[MarkerShape]:
    """The sector the free edge sweeps from closed to 90° (fan), and the leaf at ``door_angle``."""
    hinge, u, s, width = leaf_axes(estimate, opening)
    lift = np.array([0.0, 0.0, 0.005])
    edge = [hinge + lift + width * (math.cos(a) * u + math.sin(a) * s)
            for a in np.linspace(0.0, math.pi / 2.0, SWING_SEGMENTS + 1)]
    fan = np.array([p for a, b in zip(edge[:-1], edge[1:]) for p in (hinge + lift, a, b)])
    height = float(np.array(estimate.corners)[3, 2] - hinge[2])
    free = hinge + width * (math.cos(door_angle) * u + math.sin(door_angle) * s)
    up = np.array([0.0, 0.0, height])
    leaf = np.array([hinge, free, free + up, hinge, free + up, hinge + up])
    return [MarkerShape("door_swing", 0, MarkerKind.TRIANGLE_LIST, SWING_RGBA, (1.0, 1.0, 1.0), points=fan),
            MarkerShape("door_swing", 1, MarkerKind.LINE_STRIP, (0.9, 0.8, 0.1, 1.0), (0.01, 0.0, 0.0),
                        points=np.array(edge)),
            MarkerShape("door_swing", 2, MarkerKind.TRIANGLE_LIST, (0.1, 0.9, 0.1, 0.35), (1.0, 1.0, 1.0), points=leaf)]
