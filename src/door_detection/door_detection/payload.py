"""The detector's estimate (odom frame) as the contract's DoorEstimate payload.

The contract's corners are bottom-hinge, bottom-free, top-free, top-hinge; the detector's
are bottom-left, bottom-right, top-right, top-left as seen from the camera. Operator-aided
estimates measure no edges: their corners come from the nominal door (width, height, the
grasp point's distance to the free edge) laid out in the measured plane, on the floor z = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from door_contract.payloads import DoorEstimate
from door_contract.vocabulary import Side
from door_detection.estimate import DetectedDoor

__all__ = ["NominalDoor", "Point", "contract_corners", "contract_estimate"]

UP = np.array([0.0, 0.0, 1.0])
Point = tuple[float, float, float]


@dataclass(frozen=True)
class NominalDoor:
    """What the operator-aided mode assumes of the door it does not measure (m)."""

    width: float = 0.914
    height: float = 2.083
    grasp_to_free_edge: float = 0.136


def contract_corners(estimate: DetectedDoor, nominal: NominalDoor) -> np.ndarray:
    corners = np.asarray(estimate.corners)
    if np.all(np.isfinite(corners)):
        if estimate.hinge_side is Side.LEFT:
            return corners
        return corners[[1, 0, 3, 2]]
    return _nominal_corners(estimate, nominal)


def _nominal_corners(estimate: DetectedDoor, nominal: NominalDoor) -> np.ndarray:
    normal = np.asarray(estimate.normal) - (np.asarray(estimate.normal) @ UP) * UP
    normal /= np.linalg.norm(normal)
    # facing the door the robot looks along −n; its left is z × (−n)
    left = np.cross(UP, -normal)
    towards_hinge = left if estimate.hinge_side is Side.LEFT else -left
    free_edge = np.asarray(estimate.handle_position) - nominal.grasp_to_free_edge * towards_hinge
    hinge_edge = free_edge + nominal.width * towards_hinge

    def at_height(edge: np.ndarray, z: float) -> np.ndarray:
        return np.array([edge[0], edge[1], z])
    return np.array([at_height(hinge_edge, 0.0), at_height(free_edge, 0.0), at_height(free_edge, nominal.height),
                     at_height(hinge_edge, nominal.height)])


def _point(values: np.ndarray) -> Point:
    x, y, z = (float(v) for v in values)
    return x, y, z


def contract_estimate(estimate: DetectedDoor, stamp: float, nominal: NominalDoor) -> DoorEstimate:
    corners = contract_corners(estimate, nominal)
    width = estimate.width if np.isfinite(estimate.width) else nominal.width
    return DoorEstimate(
        stamp=stamp, frame_id="odom", handle_position=_point(estimate.handle_position),
        normal=_point(estimate.normal), hinge_side=estimate.hinge_side,
        width=float(width), corners=tuple(_point(c) for c in corners),
        confidence=float(estimate.confidence), frames_voted=int(estimate.frames_voted),
        mode=estimate.mode)
