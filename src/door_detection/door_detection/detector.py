"""The door detector without ROS: matched camera frames and scribbles in, what to publish out.

:class:`DoorDetector` is what ``/door_detector`` does between its messages: each decoded frame
(colour, depth, intrinsics, the camera's pose in ``odom``) goes through the automatic pipeline
([Banerjee 2015] Sec. III-A) or, while an operator's scribble is recent, the operator-aided one
(Sec. III-B); the estimate is moved into ``odom`` (``odom_T_optical`` · p) and voted over the
last N frames (:mod:`door_detection.voting`); a confirmed vote becomes the contract's
:class:`~door_contract.payloads.DoorEstimate` and the handle pose. It keeps the counters the
node reports (frames taken in, rejected, dropped incomplete).

The camera comes from the robot profile (:class:`DetectorCamera`): its images and CameraInfo
are in the contract's optical frame, which the robot's TF tree hangs below the profile's
``head_camera_frame``. A frame stamped in another frame is some other camera's and is refused.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from door_contract.converters.camera_info import CameraIntrinsics
from door_contract.door_estimates import normal_is_horizontal
from door_contract.frames import Frame
from door_contract.parameters import require_ordered
from door_contract.payloads import DoorEstimate
from door_detection.automatic import detect_automatic
from door_detection.estimate import DetectedDoor, DetectionOutcome, DetectionResult
from door_detection.frame_sync import DroppedFrame
from door_detection.operator_aided import detect_from_scribble
from door_detection.options import DetectionOptions
from door_detection.payload import NominalDoor, contract_estimate
from door_detection.scribble import scribble_problem
from door_detection.voting import Voter
from door_robot.profile import RobotProfile

__all__ = ["CameraFrame", "DetectorCamera", "DoorDetector", "FrameReport", "upright_problem"]

UP = np.array([0.0, 0.0, 1.0])
"""The world's up in ``odom`` (REP-103: z up)."""


def upright_problem(normal_in_odom: np.ndarray) -> str | None:
    """Why a door plane with this normal (odom, z up) is no door, or None: a door is vertical
    (:func:`~door_contract.door_estimates.normal_is_horizontal`, the FSM's own test of a
    published estimate). A head search looking down once confirmed the floor between two lines
    as a door (normal straight up, the handle on the floor); the FSM refused it and the search
    had stopped."""
    if normal_is_horizontal(normal_in_odom):
        return None
    norm = float(np.linalg.norm(normal_in_odom))
    tilt = np.degrees(np.arccos(min(1.0, abs(float(normal_in_odom[2])) / norm))) if norm > 0.0 else float("nan")
    return f"the plane's normal is {tilt:.0f}° from vertical, not horizontal (a door is a vertical plane)"


@dataclass(frozen=True)
class DetectorCamera:
    """The head camera of the robot profile ``robot``: its images and CameraInfo are stamped in
    ``optical_frame`` (the contract's), the camera's pose in ``pose_frame``; TF hangs the optical
    frame below ``camera_link`` (the profile's ``head_camera_frame``)."""

    robot: str
    camera_link: str
    optical_frame: str = Frame.HEAD_CAMERA_OPTICAL.value
    pose_frame: str = Frame.ODOM.value

    @classmethod
    def of(cls, profile: RobotProfile) -> DetectorCamera:
        return cls(profile.name, profile.head_camera_frame)

    def frame_problem(self, image_frames: dict[str, str], pose_frame: str) -> str | None:
        """Why a frame whose streams are stamped in ``image_frames`` (stream → frame id) and
        whose camera pose is in ``pose_frame`` is not this camera's, or None."""
        wrong = {stream: frame for stream, frame in image_frames.items() if frame != self.optical_frame}
        if wrong:
            found = ", ".join(f"{stream} in {frame!r}" for stream, frame in sorted(wrong.items()))
            return (f"{found}: {self.robot}'s head camera publishes in {self.optical_frame!r} "
                    f"(below {self.camera_link!r})")
        if pose_frame != self.pose_frame:
            return f"camera pose in {pose_frame!r}, expected {self.pose_frame!r}"
        return None


@dataclass(frozen=True)
class CameraFrame:
    """One matched frame, decoded: images in the optical frame, ``camera_pose`` = odom_T_optical."""

    stamp: float  # s
    rgb: np.ndarray  # H×W×3 uint8
    depth: np.ndarray  # H×W metres, NaN where unknown
    intrinsics: CameraIntrinsics
    camera_pose: np.ndarray  # 4×4


@dataclass(frozen=True)
class FrameReport:
    """What one frame (or one refusal) gave: a note for the heartbeat (and the log, if
    ``logged``), whether that is a warning, the frame's own estimate (optical frame, for the
    debug overlay) and, when the vote confirmed a door, the estimate to publish and its handle
    pose (odom)."""

    note: str
    warning: bool = False
    logged: bool = True
    seen: DetectedDoor | None = None
    confirmed: DoorEstimate | None = None
    handle_pose: np.ndarray | None = None
    values: dict[str, object] = field(default_factory=dict)


VOTE_PARAMETERS = ("vote_frames", "vote_min_agreeing", "vote_handle_confidence", "vote_normal_confidence_deg")
"""Node parameters that are the sequential vote's DetectionOptions fields of the same name."""


class DoorDetector:
    """The detector's state between frames: the vote, the operator's scribble, the counters."""

    def __init__(self, options: DetectionOptions, camera: DetectorCamera, nominal: NominalDoor = NominalDoor(),
                 scribble_timeout: float = 30.0) -> None:
        self.options, self.camera, self.nominal = options, camera, nominal
        self.scribble_timeout = scribble_timeout  # s, wall clock
        self.voter = Voter(options)
        self.scribble: tuple[float, np.ndarray] | None = None  # (wall time, N×2 pixels)
        self.image_size: tuple[int, int] | None = None  # (width, height) of the last CameraInfo
        self.frames = self.rejected = self.incomplete = 0

    @classmethod
    def from_parameters(cls, p: Mapping[str, Any], camera: DetectorCamera) -> DoorDetector:
        """The detector of the node's parameters (:mod:`door_detection.parameters`); a width range
        the wrong way round is a ParameterRangeError, options out of range a DetectionError."""
        require_ordered(p, "door_width_min", "door_width_max")
        options = DetectionOptions(door_width_min=p["door_width_min"], door_width_max=p["door_width_max"],
                                   **{name: p[name] for name in VOTE_PARAMETERS})
        nominal = NominalDoor(p["nominal_door_width"], p["nominal_door_height"], p["grasp_to_free_edge"])
        return cls(options, camera, nominal, p["scribble_timeout"])

    def counters(self) -> dict[str, object]:
        return {"frames": self.frames, "rejected": self.rejected}

    def take_scribble(self, pixels: np.ndarray, now: float) -> FrameReport:
        """An operator's scribble (N×2 pixels) at wall time ``now``: checked against the image size;
        a good one replaces the vote so far and is used for the next ``scribble_timeout`` s."""
        problem = scribble_problem(pixels, *(self.image_size or (None, None)))
        if problem:
            return FrameReport(f"scribble refused: {problem}; automatic detection goes on", warning=True)
        self.scribble = (now, pixels)
        self.voter.reset()  # the operator's word replaces what was voted so far
        return FrameReport(f"scribble with {len(pixels)} points: operator-aided detection next")

    def reject_input(self, stamp: float, problem: str) -> FrameReport:
        """A frame that arrived but cannot be used (its messages did not decode, or came from
        another camera): counted as taken in and rejected."""
        self.frames += 1
        return self.refuse(f"frame at {stamp:.2f} s rejected: {problem}")

    def refuse(self, reason: str, warning: bool = True) -> FrameReport:
        """A frame that gave no estimate (no door: ``warning`` False; a crash), counted as rejected."""
        self.rejected += 1
        return FrameReport(reason, warning)

    def dropped(self, frame: DroppedFrame) -> FrameReport:
        """An incomplete frame given up, saying which streams it lacked."""
        self.incomplete += 1
        missing = frame.describe()
        return FrameReport(f"frame at {frame.stamp:.2f} s dropped: no {missing} with its stamp", warning=True,
                           values={"incomplete": self.incomplete, "missing": missing})

    def process(self, frame: CameraFrame, now: float) -> FrameReport:
        """Detect in ``frame`` (at wall time ``now``), vote, and say what to publish."""
        self.frames += 1
        result = self._detect(frame, now)
        if not result.ok or result.estimate is None:
            self.voter.add(None)
            return self.refuse(f"frame at {frame.stamp:.2f} s: {result.outcome.value}: {result.reason}", False)
        seen = result.estimate.transformed(frame.camera_pose)
        if (tilt := upright_problem(seen.normal)) is not None:
            self.voter.add(None)
            return self.refuse(f"frame at {frame.stamp:.2f} s: {DetectionOutcome.NOT_UPRIGHT.value}: {tilt}", False)
        vote = self.voter.add(seen)
        report: dict[str, Any] = {"note": f"{vote.outcome.value} {vote.agreeing}/{vote.window}",
                                  "logged": False, "seen": result.estimate,
                                  "values": {"frame_ms": round(result.elapsed * 1000.0, 1),
                                             "mode": result.estimate.mode.value}}
        if vote.ok and vote.estimate is not None:
            report["confirmed"] = contract_estimate(vote.estimate, frame.stamp, self.nominal)
            report["handle_pose"] = vote.estimate.handle_pose(up=UP)
        return FrameReport(**report)

    def _detect(self, frame: CameraFrame, now: float) -> DetectionResult:
        if self.scribble is not None and now - self.scribble[0] <= self.scribble_timeout:
            up_in_optical = frame.camera_pose[:3, :3].T @ UP
            return detect_from_scribble(frame.rgb, frame.depth, frame.intrinsics, self.scribble[1], self.options,
                                        up=up_in_optical)
        return detect_automatic(frame.rgb, frame.depth, frame.intrinsics, self.options)
