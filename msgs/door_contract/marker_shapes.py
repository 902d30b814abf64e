"""Visualisation markers as plain values (ROS-free): cores describe what to draw, the
converter :mod:`door_contract.converters.markers` turns it into ``visualization_msgs``."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

import numpy as np

__all__ = ["MarkerKind", "MarkerShape"]


class MarkerKind(str, Enum):
    """The ``visualization_msgs/Marker`` types the graph draws."""

    ARROW = "arrow"
    CUBE = "cube"
    SPHERE = "sphere"
    LINE_STRIP = "line_strip"
    LINE_LIST = "line_list"
    TRIANGLE_LIST = "triangle_list"
    TEXT = "text"


@dataclass(frozen=True, eq=False)
class MarkerShape:
    """One marker in ``odom``: ``points`` (N×3, m) for lines, arrows and triangles; ``pose``
    (4×4) and ``scale`` (m; line width in ``scale[0]``) as RViz and Foxglove read them."""

    namespace: str
    marker_id: int
    kind: MarkerKind
    rgba: tuple[float, float, float, float]
    scale: tuple[float, float, float] = (0.02, 0.02, 0.02)
    points: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    pose: np.ndarray = field(default_factory=lambda: np.eye(4))
    text: str = ""
