"""The detector's output values: the door estimate, outcomes and failure reasons.

Everything is expressed in the **camera optical frame** (x right, y down, z forward,
metres), the frame the depth image is registered in.  The node transforms the pose to
``odom``/``base_link`` with tf; the core never needs to know where the camera is.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from enum import Enum

import numpy as np

from door_contract.ranges import FieldRange, check_fields
from door_contract.vocabulary import DetectionMode, Side
from door_detection.errors import DetectionError

__all__ = ["DetectedDoor", "DetectionOutcome", "DetectionResult", "FloatArray"]

FloatArray = np.ndarray
"""A float64 numpy array (shape given in each docstring)."""


class DetectionOutcome(Enum):
    """What one detection call (or one vote) ended with."""

    DETECTED = "detected"
    """An estimate is available."""
    BAD_INPUT = "bad_input"
    """Empty image, size mismatch, inconsistent intrinsics, scribble outside the image."""
    NO_VALID_DEPTH = "no_valid_depth"
    """The depth image (or the sampled region) holds too few valid pixels."""
    NO_VERTICAL_LINES = "no_vertical_lines"
    """The 2-D stage found fewer than two near-vertical lines."""
    NO_DOOR_PAIR = "no_door_pair"
    """No line pair is 3-D consistent with a door of the accepted width."""
    NO_DOOR_PLANE = "no_door_plane"
    """Door pairs were found but none holds a solid plane between its edges."""
    NO_HANDLE = "no_handle"
    """A door was found but no handle blob on either side."""
    PLANE_FIT_FAILED = "plane_fit_failed"
    """Operator-aided: the points around the scribble do not hold a plane."""
    NOT_UPRIGHT = "not_upright"
    """The plane found between two lines is not vertical in odom (e.g. the floor between a door's
    jambs seen from a head tilted down): no door."""
    INTERNAL_ERROR = "internal_error"
    """An unforeseen failure inside the pipeline (a bug); the reason names it."""
    VOTING = "voting"
    """Voter: fewer than N frames seen so far."""
    NO_CONSENSUS = "no_consensus"
    """Voter: no majority of the last N estimates agree."""


_ESTIMATE_RANGES = {"confidence": FieldRange(0.0, 1.0, ""), "frames_voted": FieldRange(1, math.inf, "frames")}
"""The interval of :class:`DetectedDoor`'s scalar fields."""

@dataclass(frozen=True)
class DetectedDoor:
    """A door and its handle in the camera optical frame (metres).

    * ``handle_position`` (3,): the handle grasp point.
    * ``normal`` (3,): unit door-plane normal pointing **towards the camera**
      (``normal · (-handle_position) > 0``).
    * ``hinge_side``: hinge on the image's LEFT or RIGHT (handle on the other side).
    * ``width``: distance between the two door edges (m); ``nan`` when unknown
      (operator-aided mode measures no edges).
    * ``corners`` (4, 3): door corners bottom-left, bottom-right, top-right, top-left
      **as seen in the image**; all ``nan`` when unknown (operator-aided mode).
    * ``confidence`` in [0, 1]: single frame: plane-inlier fraction; voted: the
      fraction of the window that agrees.
    * ``frames_voted``: 1 for a single frame, the number of agreeing frames for a voted
      consensus.
    * ``up`` (3,): the door's vertical direction in the optical frame, used as the
      handle frame's z axis.  Automatic mode: the 3-D door edges (exact for a vertical
      door); operator-aided mode: the image's up direction −y (exact only for a level
      camera).  The node may override it with gravity from tf (:meth:`handle_pose`).
    """

    handle_position: FloatArray
    normal: FloatArray
    hinge_side: Side
    width: float
    corners: FloatArray
    confidence: float
    mode: DetectionMode
    frames_voted: int = 1
    up: FloatArray = field(default_factory=lambda: np.array([0.0, -1.0, 0.0]))

    def __post_init__(self) -> None:
        position = _frozen_array(self.handle_position, (3,), "handle_position")
        normal = _frozen_array(self.normal, (3,), "normal")
        if not np.all(np.isfinite(position)) or not np.all(np.isfinite(normal)):
            raise DetectionError("handle_position and normal must be finite")
        length = float(np.linalg.norm(normal))
        if not 0.99 < length < 1.01:
            raise DetectionError(f"normal must be a unit vector, |normal| = {length:.3f}")
        normal = _frozen_array(normal / length, (3,), "normal")
        object.__setattr__(self, "handle_position", position)
        object.__setattr__(self, "normal", normal)
        object.__setattr__(self, "corners", _frozen_array(self.corners, (4, 3), "corners"))
        up = _frozen_array(self.up, (3,), "up")
        if not np.all(np.isfinite(up)) or np.linalg.norm(up) < 1e-9:
            raise DetectionError("up must be a finite non-zero vector")
        object.__setattr__(self, "up", _frozen_array(up / np.linalg.norm(up), (3,), "up"))
        check_fields(self, _ESTIMATE_RANGES, DetectionError, integers=("frames_voted",))

    def transformed(self, transform: FloatArray) -> DetectedDoor:
        """The same estimate in another frame: ``transform`` (4×4) maps optical-frame
        points to that frame (e.g. the camera pose in ``odom``, so frames taken while the
        robot moves can be voted on together)."""
        matrix = np.asarray(transform, dtype=float)
        if matrix.shape != (4, 4) or not np.all(np.isfinite(matrix)):
            raise DetectionError("transform must be a finite 4×4 matrix")
        rotation, translation = matrix[:3, :3], matrix[:3, 3]
        return replace(self, handle_position=rotation @ self.handle_position + translation,
                       normal=rotation @ self.normal, corners=self.corners @ rotation.T + translation,
                       up=rotation @ self.up)

    def handle_pose(self, up: FloatArray | None = None) -> FloatArray:
        """4×4 homogeneous pose of the handle in the optical frame (``/door/handle_pose``).

        Origin at the grasp point; x = door normal towards the camera (robot); z = "up"
        made orthogonal to x by Gram–Schmidt, z = (u − (u·x)x)/|…|, with u = ``up`` if
        given (e.g. gravity from tf), else :attr:`up`; y = z × x completes a right-handed
        frame.  When u is (nearly) parallel to x, the optical −y and then −z are tried.
        """
        x_axis = self.normal
        z_axis = np.zeros(3)
        for u in (up, self.up, np.array([0.0, -1.0, 0.0]), np.array([0.0, 0.0, -1.0])):
            if u is None:
                continue
            u = np.asarray(u, dtype=float)
            z_axis = u - float(u @ x_axis) * x_axis
            if np.linalg.norm(z_axis) > 1e-6 * max(float(np.linalg.norm(u)), 1e-12):
                break
        z_axis = z_axis / np.linalg.norm(z_axis)
        pose = np.eye(4)
        pose[:3, 0] = x_axis
        pose[:3, 1] = np.cross(z_axis, x_axis)
        pose[:3, 2] = z_axis
        pose[:3, 3] = self.handle_position
        return pose


@dataclass(frozen=True)
class DetectionResult:
    """The outcome of one detection call: an estimate, or the reason there is none.

    ``elapsed`` is the wall time of the call (s); ``candidates`` the number of door
    hypotheses that survived the 3-D checks (automatic mode; diagnostics only).
    """

    outcome: DetectionOutcome
    estimate: DetectedDoor | None = None
    reason: str = ""
    elapsed: float = 0.0
    candidates: int = 0
    stages: tuple[tuple[str, float], ...] = field(default=())

    @property
    def ok(self) -> bool:
        """True when an estimate is available."""
        return self.outcome is DetectionOutcome.DETECTED and self.estimate is not None


def _frozen_array(values: object, shape: tuple[int, ...], name: str) -> FloatArray:
    array = np.array(values, dtype=float)
    if array.shape != shape:
        raise DetectionError(f"{name} must have shape {shape}, got {array.shape}")
    array.setflags(write=False)
    return array
