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

What differs with the robot's size is the profile's too: ``stance`` sets the footstep
planner's stand distances for robots whose hands reach less or further than TALOS's (G1:
0.42 m beside a push door, where TALOS stands 0.50 m away), and an arm's ``grasp_axes_beside``
turns the hand the other way up on the lever when the door runs along the robot's side (G1's
wrist turns the lever fingers-down there, fingers-up facing the door).

``joint_efforts`` (joint → N·m) replaces a URDF's effort limits where the copy of a model is
known to have changed them: the Atlas v4 URDF in ../shared/data (roboschool's) cut the ankles
to 45 and 92 N·m and keeps the original 360 and 740 N·m in comments beside them; with the cut
ones the simulated Atlas could not walk.

``opening_crouch`` (m) lowers a tall robot for the whole task: it walks to the door that far
below its standing height (the walker's crouch), stands so while its arm opens the door and
walks through so (a push passage's crouch may take it lower still). Atlas v4's shoulders are
so high above a 0.91 m lever that upright its back bent forward into the leaf (4.7 kN); 0.15 m
lower the arm reaches the lever without it. ``low_lever_crouch`` lowers the walk to a door
whose lever is below the arm's upright reach, and ``push_passage_crouch`` the walk through a
push door whose lever meets the pelvis (:mod:`door_robot.crouch`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from door_contract.vocabulary import DoorOpening, Side
from door_robot.crouch import MAX_CROUCH, CrouchRules, LowLeverCrouch, PassageCrouch
from door_robot.errors import RobotModelError
from door_robot.locations import cmeel_share_dir, params_dir, shared_data_dir

__all__ = ["STANCE_FIELDS", "ArmSpec", "Axis", "CameraAxes", "ExtraFrame", "GraspAxes", "RobotProfile", "WalkingLimits",
           "load_profile", "profile_path", "resolve_urdf"]


@dataclass(frozen=True)
class ExtraFrame:
    """A frame the URDF lacks, fixed to ``parent`` at ``xyz`` (m, parent axes): e.g. a sole
    frame on the sole plane for a robot whose URDF has only ankle links (Atlas, G1)."""

    parent: str
    xyz: tuple[float, float, float]


AXIS_INDEX = {"x": 0, "y": 1, "z": 2}
"""The frame axes a ``head_camera_axes`` or ``grasp_axes`` entry may name, optionally signed (``-z``)."""

Axis = tuple[float, float, float]


def _cross(a: Axis, b: Axis) -> Axis:
    return a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]


def _check_axis_pair(what: str, names: tuple[str, str], axes: tuple[Axis, Axis]) -> None:
    """Both signed unit frame axes, on different axes (so that they span a right-handed frame)."""
    for name, axis in zip(names, axes):
        if sorted(abs(v) for v in axis) != [0.0, 0.0, 1.0]:
            raise RobotModelError(f"{what}.{name} must be a signed frame axis, got {axis}")
    if any(a != 0.0 and b != 0.0 for a, b in zip(*axes)):
        raise RobotModelError(f"{what}: {names[0]} {axes[0]} and {names[1]} {axes[1]} must be different frame axes")


def _axis_pair(what: str, names: tuple[str, str], document: Any) -> tuple[Axis, Axis]:
    """``{<names[0]>: x, <names[1]>: -z}`` as two signed axes (names ``x``, ``y``, ``z``)."""
    if not isinstance(document, dict):
        raise RobotModelError(f"{what} must be a mapping {{{names[0]}: …, {names[1]}: …}}, got {document!r}")
    if set(document) != set(names):
        raise RobotModelError(f"{what} needs exactly {names[0]!r} and {names[1]!r}, got {sorted(document)}")
    first, second = (_signed_axis(what, name, document[name]) for name in names)
    return first, second


def _signed_axis(what: str, name: str, label: Any) -> Axis:
    text = str(label).strip().lower()
    sign, letter = (-1.0, text[1:]) if text.startswith("-") else (1.0, text.lstrip("+"))
    if letter not in AXIS_INDEX:
        raise RobotModelError(f"{what}.{name} = {label!r}: expected x, y or z, optionally signed (-z)")
    axis = [0.0, 0.0, 0.0]
    axis[AXIS_INDEX[letter]] = sign
    return axis[0], axis[1], axis[2]


@dataclass(frozen=True)
class CameraAxes:
    """The optical axes in the camera frame's coordinates: ``forward`` (optical z, the
    viewing direction) and ``down`` (optical y, rows growing); both signed unit frame axes,
    on different axes. ``right`` (optical x) = down × forward completes the right-handed frame."""

    forward: Axis
    down: Axis

    def __post_init__(self) -> None:
        _check_axis_pair("head_camera_axes", ("forward", "down"), (self.forward, self.down))

    @property
    def right(self) -> Axis:
        """Optical x = y × z."""
        return _cross(self.down, self.forward)

    @classmethod
    def from_document(cls, document: Any) -> CameraAxes:
        """From ``{forward: x, down: -z}`` (axis names ``x``, ``y``, ``z``, optionally signed)."""
        return cls(*_axis_pair("head_camera_axes", ("forward", "down"), document))


GRASP_TARGET_AXES = np.column_stack([(-1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 1.0, 0.0)])
"""Where a :class:`GraspAxes`' into_door, up and into_door × up go in the grasp frame."""


@dataclass(frozen=True)
class GraspAxes:
    """How a hand holds a lever handle, as two signed axes of its TCP frame: ``into_door``
    points from the palm to the fingertips (into the door while grasping), ``up`` is held
    vertical (the hand closes along it, around the horizontal lever).

    In the door's grasp frame G (x = the door normal towards the robot, z up, y = z × x) the
    TCP's axes are then a ↦ −x_G, b ↦ z_G, a × b ↦ (−x_G) × z_G = y_G, so the TCP's
    orientation in G is R = [−x_G z_G y_G]·[a b a×b]ᵀ (:meth:`rotation_in_grasp`). TALOS's
    grippers (fingers along −z, closing along y): ``{into_door: -z, up: y}``, R's columns
    x_tcp = y_G, y_tcp = z_G, z_tcp = x_G."""

    into_door: Axis
    up: Axis

    def __post_init__(self) -> None:
        _check_axis_pair("grasp_axes", ("into_door", "up"), (self.into_door, self.up))

    def rotation_in_grasp(self) -> np.ndarray:
        """R (3×3), the TCP's orientation in the grasp frame: R @ into_door = −x_G, R @ up = z_G."""
        source = np.column_stack([self.into_door, self.up, _cross(self.into_door, self.up)])
        rotation: np.ndarray = GRASP_TARGET_AXES @ source.T
        return rotation

    @classmethod
    def from_document(cls, document: Any, key: str = "grasp_axes") -> GraspAxes:
        """From ``{into_door: -z, up: y}``, the profile's entry ``key`` (named in its errors)."""
        return cls(*_axis_pair(key, ("into_door", "up"), document))


@dataclass(frozen=True)
class ArmSpec:
    """The joints that move one hand (torso first), its TCP parent frame and grasp offset, and
    how the hand is turned to hold a lever (:class:`GraspAxes`): ``grasp_axes`` facing the
    door, ``grasp_axes_beside`` when the door runs along the robot's side (the sideways push
    stance, :mod:`footstep_planner.push_passage`), where a wrist may need the other way up to
    turn the lever (G1's); None: ``grasp_axes`` there too."""

    joints: tuple[str, ...]
    tcp_parent_frame: str
    grasp_offset: Axis  # m, TCP in the parent frame
    grasp_axes: GraspAxes
    gripper_joint: str | None = None
    grasp_axes_beside: GraspAxes | None = None

    def grasp_axes_for(self, beside: bool) -> GraspAxes:
        """The hand's axes on the lever, the door across the robot's front or (``beside``) along its side."""
        return self.grasp_axes_beside if beside and self.grasp_axes_beside is not None else self.grasp_axes


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
    body_depth: float  # m, front to back
    step_duration: float = 1.0  # s per footstep (robot clock): execution deadlines scale with it
    body_offset: float = 0.0  # m, the body box's centre ahead of the base (arms reach further forward than back)


@dataclass(frozen=True)
class RobotProfile:
    name: str
    urdf_path: Path
    base_frame: str
    base_height: float  # m, base frame above the sole plane in the nominal posture
    arms: dict[Side, ArmSpec]
    head_camera_frame: str
    feet: dict[Side, str]  # sole frame names
    nominal_posture: dict[str, float]  # joint -> rad
    walking: WalkingLimits
    walking_posture: dict[str, float] = field(default_factory=dict)  # joint -> rad over the nominal posture
    extra_frames: dict[str, ExtraFrame] = field(default_factory=dict)  # frame name -> ExtraFrame (added to every model)
    head_camera_axes: CameraAxes | None = None  # the optical axes in head_camera_frame; None: the sim's guess
    look_posture: dict[str, float] = field(default_factory=dict)  # joint -> rad over the walking posture, to see the door
    stance: dict[str, float] = field(default_factory=dict)  # footstep planner stand distance -> m (STANCE_FIELDS)
    joint_efforts: dict[str, float] = field(default_factory=dict)  # joint -> effort limit (N·m) replacing the URDF's
    crouch: CrouchRules = CrouchRules()  # how low it walks (door_robot.crouch; the default: upright)

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
    if not isinstance(document, dict):
        raise RobotModelError(f"robot profile {name_or_path!r} is no mapping of fields")
    try:
        return _profile_from_document(document)
    except KeyError as error:
        raise RobotModelError(f"robot profile {name_or_path!r} is incomplete: {error}") from None
    except RobotModelError as error:
        raise RobotModelError(f"robot profile {name_or_path!r}: {error}") from None


def _number(value: Any, where: str) -> float:
    """``value`` as a float; a :class:`RobotModelError` naming the field ``where`` when it is no number."""
    if isinstance(value, bool):
        raise RobotModelError(f"{where} must be a number, got {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise RobotModelError(f"{where} must be a number, got {value!r}") from None


def _numbers(values: Any, where: str, count: int) -> tuple[float, ...]:
    """``values`` as ``count`` floats (a YAML list)."""
    if not isinstance(values, (list, tuple)) or len(values) != count:
        raise RobotModelError(f"{where} must be a list of {count} numbers, got {values!r}")
    return tuple(_number(value, f"{where}[{index}]") for index, value in enumerate(values))


def _names(values: Any, where: str) -> tuple[str, ...]:
    """``values`` as a list of names (joints)."""
    if not isinstance(values, (list, tuple)) or not all(isinstance(value, str) for value in values):
        raise RobotModelError(f"{where} must be a list of names, got {values!r}")
    return tuple(values)


def _mapping(document: Any, where: str) -> dict[Any, Any]:
    """An optional mapping of the profile ({} when absent)."""
    if document is None:
        return {}
    if not isinstance(document, dict):
        raise RobotModelError(f"{where} must be a mapping, got {document!r}")
    return document


def _refuse_unknown(names: Any, known: Any, where: str) -> None:
    """A RobotModelError naming the fields of ``names`` that are not ``known``."""
    if unknown := sorted(set(names) - set(known)):
        raise RobotModelError(f"{where}: unknown field(s) {unknown}; known: {sorted(known)}")


def _side(name: Any, where: str) -> Side:
    try:
        return Side(name)
    except ValueError:
        raise RobotModelError(f"{where}: {name!r} is no side (left, right)") from None


def _xyz(values: Any, where: str) -> tuple[float, float, float]:
    x, y, z = _numbers(values, where, 3)
    return x, y, z


STANCE_FIELDS = frozenset({"stand_reach", "stand_reach_pull", "push_side_reach"})
"""The footstep planner's stand distances a profile's ``stance`` may set for its robot (m, base
to the door plane; the node's parameters of the same names are TALOS's): how far the hands
reach is the robot's, like its stride."""


def _profile_from_document(document: dict[str, Any]) -> RobotProfile:
    arms = {_side(side, "arms"): _arm(_mapping(arm, f"arms.{side}"), f"arms.{side}")
            for side, arm in _mapping(document["arms"], "arms").items()}
    posture = _posture(document, "nominal_posture", required=True)
    return RobotProfile(
        name=document["name"],
        urdf_path=resolve_urdf(document["urdf"]),
        base_frame=document["base_frame"],
        base_height=_number(document["base_height"], "base_height"),
        arms=arms,
        head_camera_frame=document["head_camera_frame"],
        feet={_side(side, "feet"): frame for side, frame in _mapping(document["feet"], "feet").items()},
        nominal_posture=posture,
        walking=_walking_limits(document["walking"]),
        walking_posture=_posture(document, "walking_posture"),
        extra_frames={name: _extra_frame(_mapping(frame, f"extra_frames.{name}"), f"extra_frames.{name}")
                      for name, frame in _mapping(document.get("extra_frames"), "extra_frames").items()},
        head_camera_axes=_camera_axes(document.get("head_camera_axes")),
        look_posture=_posture(document, "look_posture"),
        stance=_stance(document.get("stance")),
        joint_efforts=_joint_efforts(document.get("joint_efforts")),
        crouch=CrouchRules(_number(document.get("opening_crouch", 0.0), "opening_crouch"),
                           _passage_crouch(document.get("push_passage_crouch")),
                           _low_lever_crouch(document.get("low_lever_crouch"))),
    )


def _arm(document: dict[str, Any], where: str) -> ArmSpec:
    return ArmSpec(_names(document["joints"], f"{where}.joints"), document["tcp_parent_frame"],
                   _xyz(document["grasp_offset"], f"{where}.grasp_offset"),
                   GraspAxes.from_document(document["grasp_axes"]), document.get("gripper_joint"),
                   _grasp_axes_beside(document.get("grasp_axes_beside")))


def _extra_frame(document: dict[str, Any], where: str) -> ExtraFrame:
    return ExtraFrame(document["parent"], _xyz(document["xyz"], f"{where}.xyz"))


def _walking_limits(document: Any) -> WalkingLimits:
    """The ``walking`` mapping: :class:`WalkingLimits`' fields, numbers (the defaulted ones optional)."""
    limits = {str(name): _number(value, f"walking.{name}") for name, value in _mapping(document, "walking").items()}
    fields = {spec.name: spec for spec in dataclasses.fields(WalkingLimits)}
    _refuse_unknown(limits, fields, "walking")
    required = {name for name, spec in fields.items() if spec.default is dataclasses.MISSING}
    if missing := sorted(required - set(limits)):
        raise RobotModelError(f"walking: missing field(s) {missing}")
    return WalkingLimits(**limits)


def _joint_efforts(document: Any) -> dict[str, float]:
    """The optional ``joint_efforts`` mapping (joint → N·m, positive and finite): effort limits
    that replace the URDF's where a copy of a model is known to have changed them (the
    simulated motors' maximum forces; whether each joint exists is checked against the URDF
    where the robot is loaded)."""
    efforts = {str(name): _number(value, f"joint_efforts.{name}")
               for name, value in _mapping(document, "joint_efforts").items()}
    if not all(math.isfinite(v) and v > 0.0 for v in efforts.values()):
        raise RobotModelError(f"joint_efforts must be positive and finite, got {efforts}")
    return efforts


def _passage_crouch(document: Any) -> PassageCrouch | None:
    if document is None:
        return None
    where = "push_passage_crouch"
    document = _mapping(document, where)
    optional = ("min_door_width", "narrow_rise", "narrow_rise_top")
    _refuse_unknown(document, {"lever_heights", "crouch", *optional}, where)
    low, high = _numbers(document["lever_heights"], f"{where}.lever_heights", 2)
    return PassageCrouch((low, high), _number(document["crouch"], f"{where}.crouch"),
                         **{name: _number(document.get(name, 0.0), f"{where}.{name}") for name in optional})


def _low_lever_crouch(document: Any) -> LowLeverCrouch | None:
    if document is None:
        return None
    document = _mapping(document, "low_lever_crouch")
    _refuse_unknown(document, {"reach_height", "max_crouch", "openings"}, "low_lever_crouch")
    openings = document.get("openings", [opening.value for opening in DoorOpening])
    try:
        doors = frozenset(DoorOpening(opening) for opening in openings)
    except (ValueError, TypeError):
        raise RobotModelError(f"low_lever_crouch: openings must be a list of push, pull; got {openings!r}") from None
    return LowLeverCrouch(_number(document["reach_height"], "low_lever_crouch.reach_height"),
                          _number(document.get("max_crouch", MAX_CROUCH), "low_lever_crouch.max_crouch"), doors)


def _grasp_axes_beside(document: Any) -> GraspAxes | None:
    return None if document is None else GraspAxes.from_document(document, "grasp_axes_beside")


def _stance(document: Any) -> dict[str, float]:
    """The optional ``stance`` mapping: :data:`STANCE_FIELDS` names to positive finite metres."""
    stance = {str(name): _number(value, f"stance.{name}") for name, value in _mapping(document, "stance").items()}
    _refuse_unknown(stance, STANCE_FIELDS, "stance")
    if not all(math.isfinite(v) and v > 0.0 for v in stance.values()):
        raise RobotModelError(f"stance distances must be positive and finite, got {stance}")
    return stance


def _posture(document: dict[str, Any], key: str, required: bool = False) -> dict[str, float]:
    """A ``joint: rad`` mapping of the profile (optional unless ``required``), finite."""
    if required and key not in document:
        raise KeyError(key)
    posture = {name: _number(value, f"{key}.{name}") for name, value in _mapping(document.get(key), key).items()}
    if not all(math.isfinite(v) for v in posture.values()):
        raise RobotModelError(f"{key} contains NaN or infinity")
    return posture


def _camera_axes(document: Any) -> CameraAxes | None:
    return None if document is None else CameraAxes.from_document(document)
