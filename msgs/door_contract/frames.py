"""Frame names (REP-105 style). Every ``header.frame_id`` in the graph comes from here."""

from enum import Enum


class Frame(str, Enum):
    """Coordinate frames used on the bus. Axes follow REP-103: x forward, y left, z up."""

    MAP = "map"
    ODOM = "odom"
    BASE_LINK = "base_link"
    #: Optical frame of the head camera: z forward, x right, y down (REP-103 optical convention).
    HEAD_CAMERA_OPTICAL = "head_camera_optical_frame"
