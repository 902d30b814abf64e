"""Frame names (REP-105 style). Every ``header.frame_id`` in the graph comes from here."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import numpy as np

__all__ = ["Frame", "FrameTransform"]


class Frame(str, Enum):
    """Coordinate frames used on the bus. Axes follow REP-103: x forward, y left, z up."""

    MAP = "map"
    ODOM = "odom"
    BASE_LINK = "base_link"
    #: Optical frame of the head camera: z forward, x right, y down (REP-103 optical convention).
    HEAD_CAMERA_OPTICAL = "head_camera_optical_frame"


@dataclass(frozen=True, eq=False)
class FrameTransform:
    """Where frame ``child`` is in frame ``parent``: a 4×4 rigid transform ``parent_T_child``.

    A point p given in ``child`` coordinates is ``parent_T_child @ p`` in ``parent``
    coordinates, which is what a ``geometry_msgs/TransformStamped`` with ``header.frame_id =
    parent`` and ``child_frame_id = child`` carries on /tf.
    """

    parent: str
    child: str
    matrix: np.ndarray
