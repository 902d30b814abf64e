"""Robot profiles: what the door task needs to know about a humanoid, read from YAML.

A profile names the URDF, the arm chains (torso + arm joints per side, as DESIGN.md
requires: the 7-DOF arm alone could not reach most handles), the hand's tool-centre-point
(TCP) frame with its grasp offset, the head camera, the feet, the nominal posture and the
walking limits. Joint limits are read from the URDF itself (:mod:`door_robot.kinematics`).

The head camera frame need not be an optical frame (z forward, x right, y down):
``head_camera_axes`` says which of its signed axes the camera looks along (``forward``, the
optical z) and which points down the image (``down``, the optical y); the optical x is
y × z. G1's ``d435_link`` is an x-forward body frame pitched 0.83 rad down, so
``{forward: x, down: -z}`` makes its camera look down by that pitch. A profile without it
leaves the choice to the simulator (the frame axes closest to the base's forward and down).

``look_posture`` (joint → rad over the walking posture) is how the robot stands to look for
the door. A head camera on a neck is tilted by the neck (the simulator's ``head_pitch``); one
fixed to the torso is not, and G1's, 48° down, sees the handle only from within ~1 m: it leans
its torso back instead (the waist pitch).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from door_contract.vocabulary import Side
from door_robot.errors import RobotModelError
from door_robot.locations import cmeel_share_dir, params_dir, shared_data_dir


@dataclass(frozen=True)
class ArmSpec:
    """The joints that move one hand (torso first), its TCP parent frame and grasp offset."""

    joints: tuple[str, ...]
    tcp_parent_frame: str
    grasp_offset: tuple[float, float, float]  # m, TCP in the parent frame
    gripper_joint: str | None = None


@dataclass(frozen=True)
class ExtraFrame:
    """A frame the URDF lacks, fixed to ``parent`` at ``xyz`` (m, parent axes): e.g. a sole
    frame on the sole plane for a robot whose URDF has only ankle links (Atlas, G1)."""

    parent: str
    xyz: tuple[float, float, float]


AXIS_INDEX = {"x": 0, "y": 1, "z": 2}
"""The frame axes a ``head_camera_axes`` entry may name, with an optional sign (``-z``)."""


@dataclass(frozen=True)
class CameraAxes:
    """The optical axes in the camera frame's coordinates: ``forward`` (optical z, the
    viewing direction) and ``down`` (optical y, rows growing); both signed unit frame axes,
    on different axes. ``right`` (optical x) = down × forward completes the right-handed frame."""

    forward: tuple[float, float, float]
    down: tuple[float, float, float]

    def __post_init__(self) -> None:
        for name, axis in (("forward", self.forward), ("down", self.down)):
            if sorted(abs(v) for v in axis) != [0.0, 0.0, 1.0]:
                raise RobotModelError(f"head_camera_axes.{name} must be a signed frame axis, got {axis}")
        if any(f != 0.0 and d != 0.0 for f, d in zip(self.forward, self.down)):
            raise RobotModelError(f"head_camera_axes: forward {self.forward} and down {self.down} "
                                  "must be different frame axes")

    @property
    def right(self) -> tuple[float, float, float]:
        """Optical x = y × z."""
        (dx, dy, dz), (fx, fy, fz) = self.down, self.forward
        return dy * fz - dz * fy, dz * fx - dx * fz, dx * fy - dy * fx

    @classmethod
    def from_document(cls, document: dict[str, Any]) -> CameraAxes:
        """From ``{forward: x, down: -z}`` (axis names ``x``, ``y``, ``z``, optionally signed)."""
        unknown = set(document) - {"forward", "down"}
        if unknown or len(document) != 2:
            raise RobotModelError(f"head_camera_axes needs exactly 'forward' and 'down', got {sorted(document)}")
        return cls(_signed_axis("forward", document["forward"]), _signed_axis("down", document["down"]))


def _signed_axis(name: str, label: Any) -> tuple[float, float, float]:
    text = str(label).strip().lower()
    sign, letter = (-1.0, text[1:]) if text.startswith("-") else (1.0, text.lstrip("+"))
    if letter not in AXIS_INDEX:
        raise RobotModelError(f"head_camera_axes.{name} = {label!r}: expected x, y or z, optionally signed (-z)")
    axis = [0.0, 0.0, 0.0]
    axis[AXIS_INDEX[letter]] = sign
    return axis[0], axis[1], axis[2]


@dataclass(frozen=True)
class WalkingLimits:
    """Footstep limits of the robot ([Banerjee 2015] Sec. II: quasi-static walking)."""

    max_stride: float  # m forward per step
    max_side_step: float  # m lateral per step
    max_turn: float  # rad per step
    foot_separation: float  # m between sole centres, standing
    foot_length: float  # m
    foot_width: float  # m
    body_width: float  # m, shoulder to shoulder with arms tucked
    body_depth: float  # m
    step_duration: float = 1.0  # s per footstep (robot clock): execution deadlines scale with it


@dataclass(frozen=True)
class RobotProfile:
    name: str
    urdf_path: Path
    base_frame: str
    base_height: float  # m, base frame above the sole plane in the nominal posture
    arms: dict  # Side -> ArmSpec
    head_camera_frame: str
    feet: dict  # Side -> sole frame name
    nominal_posture: dict  # joint -> rad
    walking: WalkingLimits
    walking_posture: dict = field(default_factory=dict)  # joint -> rad over the nominal posture
    extra_frames: dict = field(default_factory=dict)  # frame name -> ExtraFrame (added to every model)
    head_camera_axes: CameraAxes | None = None  # the optical axes in head_camera_frame; None: the sim's guess
    look_posture: dict = field(default_factory=dict)  # joint -> rad over the walking posture, to see the door

    def arm(self, side: Side) -> ArmSpec:
        return self.arms[side]

    def tcp_frame(self, side: Side) -> str:
        """Name of the TCP frame the kinematics adds for ``side``."""
        return f"{side.value}_tcp"


def resolve_urdf(source: dict[str, str]) -> Path:
    """A URDF path from ``{package: example-robot-data, path: …}`` or ``{shared_data: …}``."""
    if "package" in source:
        path = cmeel_share_dir() / source["package"] / source["path"]
    elif "shared_data" in source:
        path = shared_data_dir() / source["shared_data"]
    elif "file" in source:
        path = Path(source["file"])
    else:
        raise RobotModelError(f"urdf source needs 'package'+'path', 'shared_data' or 'file': {source}")
    if not path.is_file():
        raise RobotModelError(f"URDF not found: {path}")
    return path


def profile_path(name_or_path: str) -> Path:
    """``robot_<name>.yaml`` in the params directory, or an explicit file path."""
    candidate = Path(name_or_path)
    if candidate.suffix in (".yaml", ".yml"):
        if candidate.is_file():
            return candidate
        candidate = params_dir() / candidate.name
    else:
        candidate = params_dir() / f"robot_{name_or_path}.yaml"
    if not candidate.is_file():
        raise RobotModelError(f"robot profile not found: {candidate}")
    return candidate


def load_profile(name_or_path: str = "talos") -> RobotProfile:
    """Read and validate a robot profile (``talos``, ``atlas_v4``, ``drc_hubo``, ``g1`` or a path)."""
    document = yaml.safe_load(profile_path(name_or_path).read_text())
    try:
        return _profile_from_document(document)
    except (KeyError, TypeError) as error:
        raise RobotModelError(f"robot profile {name_or_path!r} is incomplete: {error}") from None


def _xyz(values: Any) -> tuple[float, float, float]:
    x, y, z = (float(v) for v in values)
    return x, y, z


def _profile_from_document(document: dict[str, Any]) -> RobotProfile:
    arms = {Side(side): ArmSpec(tuple(arm["joints"]), arm["tcp_parent_frame"], _xyz(arm["grasp_offset"]),
                                arm.get("gripper_joint"))
            for side, arm in document["arms"].items()}
    posture = {name: float(value) for name, value in document["nominal_posture"].items()}
    if not all(math.isfinite(v) for v in posture.values()):
        raise RobotModelError("nominal posture contains NaN or infinity")
    return RobotProfile(
        name=document["name"],
        urdf_path=resolve_urdf(document["urdf"]),
        base_frame=document["base_frame"],
        base_height=float(document["base_height"]),
        arms=arms,
        head_camera_frame=document["head_camera_frame"],
        feet={Side(side): frame for side, frame in document["feet"].items()},
        nominal_posture=posture,
        walking=WalkingLimits(**{k: float(v) for k, v in document["walking"].items()}),
        walking_posture=_posture(document, "walking_posture"),
        extra_frames={name: ExtraFrame(frame["parent"], _xyz(frame["xyz"]))
                      for name, frame in (document.get("extra_frames") or {}).items()},
        head_camera_axes=_camera_axes(document.get("head_camera_axes")),
        look_posture=_posture(document, "look_posture"),
    )


def _posture(document: dict[str, Any], key: str) -> dict[str, float]:
    """An optional ``joint: rad`` mapping of the profile, finite."""
    posture = {name: float(value) for name, value in (document.get(key) or {}).items()}
    if not all(math.isfinite(v) for v in posture.values()):
        raise RobotModelError(f"{key} contains NaN or infinity")
    return posture


def _camera_axes(document: Any) -> CameraAxes | None:
    if document is None:
        return None
    if not isinstance(document, dict):
        raise RobotModelError(f"head_camera_axes must be a mapping {{forward: …, down: …}}, got {document!r}")
    return CameraAxes.from_document(document)
