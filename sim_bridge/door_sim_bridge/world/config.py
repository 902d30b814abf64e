"""Validated, frozen configuration of the simulated door world.

Every value is checked on construction; a bad one raises :class:`SimulationError` naming the
field and its allowed range. Defaults describe the DARPA Robotics Challenge door (36 × 82 in,
lever handle at 0.91 m) and a MultiSense-like head camera. All randomness of a run (wind
phase, image noise) is derived from :attr:`WorldConfig.seed`, so equal configurations give
identical runs.

Units are SI throughout: metres, radians, seconds, newtons, newton-metres; colours are RGB in
[0, 1].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import Enum

from door_contract.vocabulary import DoorOpening, HingeSide
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.validation import FieldRange, check_ranges, require
from door_sim_bridge.walking.gait import GaitOptions
from door_sim_bridge.walking.stabilizer import StabilizerOptions
from door_sim_bridge.world_ranges import (
    CAMERA_RANGES,
    COLOUR_COMPONENT,
    COLOUR_FIELDS,
    DIRECTION_COMPONENT,
    DOOR_RANGES,
    EXECUTION_RANGES,
    FALL_RANGES,
    POSTURE_OVERRIDE,
    STANCE_RANGES,
    WIND_RANGES,
    WORLD_RANGES,
)

__all__ = ["CameraConfig", "Colour", "ContactSolver", "Direction", "DoorConfig", "ExecutionConfig", "FallConfig",
           "GraspModel", "RobotMode", "RobotVisuals", "StanceConfig", "WindConfig", "WorldConfig"]

Colour = tuple[float, float, float]
"""RGB in [0, 1]."""

Direction = tuple[float, float, float]
"""A direction in odom (any non-zero length; normalised where used)."""

DEFAULT_LIGHT_DIRECTION: Direction = (-50.0, 30.0, 100.0)
"""PyBullet TinyRenderer's own light for a z-up world (towards the light, odom axes): passing
it explicitly renders exactly what the renderer did unasked."""


class RobotMode(str, Enum):
    """How the robot is simulated."""

    PHYSICAL = "physical"  # floating base on the floor, walking controller, can fall (the default)
    KINEMATIC = "kinematic"  # base fixed to the world and glided along footsteps: fast unit tests only


class GraspModel(str, Enum):
    """How a closed hand holds the lever (the constraint :mod:`door_sim_bridge.world.grasp` makes)."""

    COMPLIANT = "compliant"
    """At a point, free to turn about it: the hand passes forces to the lever but no torques, as
    a compliant hand's padded fingers give way (the default). A hand a few mm off the lever's
    estimated axis, or turned a degree, then follows the lever's true arc instead of fighting it."""
    RIGID = "rigid"
    """Locked in orientation, sliding only along the lever: the wrist must turn exactly with the
    lever; an estimate 1 cm or 1.5° off held the wrist 0.1-0.25 rad from its goal (issue #11)."""


class ContactSolver(str, Enum):
    """The algorithm PyBullet solves its constraints with each step (joint motors, contacts, grasps).

    Under either, a stance leg can give way at lift-off (issue #11, stop 27). The pattern's ZMP
    leaves the feet's midpoint for the stance sole in one 0.06 s QP step, the CoM 5.4 cm beside
    that sole; under the iterative solver the stance ankle roll's motor then applies 0-7 of its
    100 N·m while its error grows to 0.27 rad and the sole's edge sinks 45 mm into the floor (a
    solver short of convergence, not the motor's limit); under the direct one the hip and knee
    motors of that leg reach their limits (160, 300 N·m) instead. Either way the pelvis drops
    3-5 cm in 0.2 s.
    """

    SEQUENTIAL_IMPULSE = "sequential_impulse"
    """PyBullet's default (projected Gauss-Seidel), ``solver_iterations`` sweeps per step (the
    default). 50 sweeps: the lift-off dip; 400 sweeps (2.7× the CPU) removed it from one
    replayed approach walk but not from the push passage."""
    DANTZIG = "dantzig"
    """A direct (pivoting) LCP solver (``solver_iterations`` is the iterative one's): it removed the dip
    from the replayed approach walk at the iterative solver's cost, but in the passage rig the
    robot fell as often (push door from 2.5 m: 0/4) and a pull door's tuck missed its goal by
    0.26-0.28 rad (arm_left_6)."""


class RobotVisuals(str, Enum):
    """Which robot links the camera renders (TinyRenderer cost grows with mesh triangles)."""

    ALL = "all"
    ARMS = "arms"  # only links moved by the arm joints the two arms do not share
    NONE = "none"


def _require_enum(owner: str, name: str, value: object, kind: type[Enum]) -> None:
    if not isinstance(value, kind):
        allowed = ", ".join(member.value for member in kind)
        raise SimulationError(f"{owner}.{name} must be one of {allowed}, got {value!r}")


def _require_colour(owner: str, name: str, value: object) -> None:
    if not isinstance(value, tuple) or len(value) != 3:
        raise SimulationError(f"{owner}.{name} must be an (r, g, b) tuple in [0, 1], got {value!r}")
    for component in value:
        require(owner, name, component, COLOUR_COMPONENT)


def _require_direction(owner: str, name: str, value: object) -> None:
    """A finite (x, y, z) tuple with a length: a zero vector points nowhere."""
    if not isinstance(value, tuple) or len(value) != 3:
        raise SimulationError(f"{owner}.{name} must be an (x, y, z) tuple, got {value!r}")
    for component in value:
        require(owner, name, component, DIRECTION_COMPONENT)
    if math.hypot(*value) < 1e-9:
        raise SimulationError(f"{owner}.{name} = {value!r} has no direction (zero length)")


@dataclass(frozen=True)
class WindConfig:
    """Wind torque on the hinge: tau_w(t) = bias + amplitude * sin(2 pi frequency t + phase).

    Positive torque opens the door. The phase is drawn from the world seed. Off by default.
    """

    amplitude: float = 0.0  # N·m
    frequency: float = 0.3  # Hz
    bias: float = 0.0  # N·m

    def __post_init__(self) -> None:
        check_ranges(self, WIND_RANGES)

    @property
    def enabled(self) -> bool:
        return self.amplitude > 0.0 or self.bias != 0.0


@dataclass(frozen=True)
class DoorConfig:
    """The door leaf, its frame and wall, the lever handle, the latch and the springs.

    Physics (applied as joint torques every physics step, since PyBullet clears them):

    * hinge: tau = -(closer_preload + closer_stiffness * theta) - hinge_damping * dtheta + wind,
      plus Coulomb friction ``hinge_friction`` (a velocity motor with target 0 and that force
      limit, which the constraint solver handles without chatter);
    * handle: tau = -(handle_preload + handle_stiffness * phi) - handle_damping * dphi, plus
      friction ``handle_friction``;
    * latch: while latched the hinge may open only ``latch_play``; turning the handle past
      ``latch_release_angle`` retracts the bolt, and the latch re-engages once the handle is back
      below the release angle and the door within ``latch_engage_angle`` of closed.
    """

    opening: DoorOpening = DoorOpening.PUSH
    hinge_side: HingeSide = HingeSide.LEFT
    width: float = 0.914  # m, leaf (DRC: 36 in)
    height: float = 2.083  # m, leaf (DRC: 82 in)
    thickness: float = 0.04  # m
    mass: float = 25.0  # kg, leaf
    floor_gap: float = 0.01  # m under the leaf
    handle_height: float = 0.91  # m above the floor, lever axis
    handle_backset: float = 0.07  # m, latch edge to lever axis
    lever_length: float = 0.11  # m, axis to lever tip (points towards the hinge side)
    lever_standoff: float = 0.06  # m, door face to the lever's centre line
    grasp_fraction: float = 0.6  # grasp point along the lever, as a fraction of its length
    handle_max_angle: float = 1.0  # rad, handle stop
    hinge_max_angle: float = 1.75  # rad, door stop (about 100 deg)
    latch_release_angle: float = 0.52  # rad of handle turn that retracts the bolt (~30 deg)
    latch_engage_angle: float = 0.035  # rad from closed where the bolt catches again (~2 deg)
    latch_play: float = 0.004  # rad the latched door can move (a few mm at the latch edge)
    closer_stiffness: float = 8.0  # N·m/rad
    closer_preload: float = 2.0  # N·m at closed
    # N·m·s/rad: a closer is a hydraulic damper, overdamped on this leaf (I = m w²/3 ≈ 7 kg m²,
    # ζ = c / (2 √(k I)) ≈ 1.3; real closers take seconds to shut from 90°). At 3 the leaf rang
    # (ζ ≈ 0.2), bounced off its stop and swung back into the walking robot at 1 rad/s.
    hinge_damping: float = 20.0
    hinge_friction: float = 0.5  # N·m
    handle_stiffness: float = 2.0  # N·m/rad
    handle_preload: float = 0.3  # N·m at rest
    handle_damping: float = 0.02  # N·m·s/rad
    handle_friction: float = 0.02  # N·m
    handle_mass: float = 0.3  # kg
    door_colour: Colour = (0.55, 0.33, 0.17)
    frame_colour: Colour = (0.92, 0.92, 0.88)
    handle_colour: Colour = (0.85, 0.70, 0.15)
    wall_colour: Colour = (0.45, 0.58, 0.72)
    floor_colour: Colour = (0.30, 0.30, 0.30)
    wind: WindConfig = field(default_factory=WindConfig)

    def __post_init__(self) -> None:
        _require_enum("DoorConfig", "opening", self.opening, DoorOpening)
        _require_enum("DoorConfig", "hinge_side", self.hinge_side, HingeSide)
        check_ranges(self, DOOR_RANGES)
        self._check_relations()
        self._check_colours()
        if not isinstance(self.wind, WindConfig):
            raise SimulationError(f"DoorConfig.wind must be a WindConfig, got {self.wind!r}")

    def _check_relations(self) -> None:
        """The intervals that depend on other fields (each within its own of :data:`DOOR_RANGES`)."""
        top = self.floor_gap + self.height
        check_ranges(self, {
            "handle_height": FieldRange(self.floor_gap + 0.2, top - 0.2, "m"),
            "lever_length": FieldRange(0.05, self.width - self.handle_backset - 0.02, "m"),
            "latch_release_angle": FieldRange(0.05, self.handle_max_angle - 0.05, "rad"),
            "latch_play": FieldRange(0.0, self.latch_engage_angle, "rad")})

    def _check_colours(self) -> None:
        """Each colour must be RGB in [0, 1]; any combination renders, so none is refused (a
        white leaf on a white wall is a scene to detect, not a configuration error)."""
        for name in COLOUR_FIELDS:
            _require_colour("DoorConfig", name, getattr(self, name))


@dataclass(frozen=True)
class StanceConfig:
    """Where the robot starts: its base at x = -distance, y = lateral_offset, facing +x rotated by yaw."""

    distance: float = 1.2  # m from the door plane (x = 0) to the base
    lateral_offset: float = 0.0  # m along y
    yaw: float = 0.0  # rad relative to facing the door (+x)

    def __post_init__(self) -> None:
        check_ranges(self, STANCE_RANGES)


@dataclass(frozen=True)
class CameraConfig:
    """Head RGB-D camera (MultiSense-like), rendered by PyBullet's CPU TinyRenderer.

    Noise (off by default): depth sigma = depth_noise_coefficient * z**2 (stereo error grows with
    the square of the range), colour sigma in 8-bit intensity levels. ``light_direction`` points
    from the scene towards the (directional) light in odom; TinyRenderer shades a face by
    0.6 + 0.35 max(n·l, 0) (ambient + diffuse), so faces at different angles to the light differ
    in brightness even when painted alike.
    """

    width: int = 640  # px
    height: int = 480  # px
    vertical_fov_deg: float = 60.0  # deg
    near: float = 0.1  # m
    far: float = 8.0  # m
    frame_rate_hz: float = 5.0  # frames per simulated second the node should publish
    depth_noise_coefficient: float = 0.0  # 1/m
    colour_noise_sigma: float = 0.0  # intensity levels (0..255)
    head_pitch: float = 0.3  # rad, head tilted down so a door at 1-4 m and its handle are in view
    robot_visuals: RobotVisuals = RobotVisuals.ARMS
    light_direction: Direction = DEFAULT_LIGHT_DIRECTION  # towards the light, odom

    def __post_init__(self) -> None:
        _require_direction("CameraConfig", "light_direction", self.light_direction)
        check_ranges(self, CAMERA_RANGES, integers=("width", "height"))
        require("CameraConfig", "far", self.far, FieldRange(self.near + 0.1, 100.0, "m"))
        _require_enum("CameraConfig", "robot_visuals", self.robot_visuals, RobotVisuals)


@dataclass(frozen=True)
class ExecutionConfig:
    """How joint trajectories and footstep plans are executed and judged."""

    settle_time: float = 0.25  # s held at the final point before judging
    goal_tolerance: float = 0.05  # rad; a joint farther than this at the end is a FAILURE
    held_wrist_tolerance: float = 0.15  # rad, instead, for the wrist of a hand holding the handle or touching the door
    # (the lever's true arc holds it off a path planned on the estimated axis: 0.06-0.09 rad seen)
    start_tolerance: float = 0.2  # rad; a first point at t = 0 farther than this is REJECTED
    velocity_limit_scale: float = 1.0  # x URDF velocity limit allowed between waypoints
    step_duration: float = 1.0  # s of simulated time per footstep (quasi-static)
    collision_depth: float = 0.01  # m of penetration into the wall or frame that stops walking

    def __post_init__(self) -> None:
        check_ranges(self, EXECUTION_RANGES)


@dataclass(frozen=True)
class FallConfig:
    """When the physical robot counts as fallen (checked every physics step).

    A humanoid standing or walking keeps its base near its nominal height and nearly upright;
    below ``height_fraction`` × the nominal base height, or tilted more than ``max_tilt``, it
    has fallen, and it stays fallen: nothing executes any more.
    """

    height_fraction: float = 0.6  # × the profile's base height
    max_tilt: float = 0.6  # rad between the base's z axis and the vertical

    def __post_init__(self) -> None:
        check_ranges(self, FALL_RANGES)


@dataclass(frozen=True)
class WorldConfig:
    """The whole scene: robot, door, starting stance, camera, physics, grasp and seed."""

    robot_profile: str = "talos"
    door: DoorConfig = field(default_factory=DoorConfig)
    stance: StanceConfig = field(default_factory=StanceConfig)
    camera: CameraConfig = field(default_factory=CameraConfig)
    execution: ExecutionConfig = field(default_factory=ExecutionConfig)
    physics_rate: float = 240.0  # Hz
    seed: int = 0
    gravity: float = 9.81  # m/s²
    grasp_distance: float = 0.02  # m, TCP to handle grasp point, to close a grasp
    grasp_break_force: float = 200.0  # N, grip: constraint force beyond which the hand slips
    grasp_break_steps: int = 3  # consecutive physics steps above the limit before it slips
    grasp_model: GraspModel = GraspModel.COMPLIANT
    joint_force_scale: float = 1.0  # x URDF effort limit given to each position motor
    robot_mode: RobotMode = RobotMode.PHYSICAL
    gait: GaitOptions = field(default_factory=GaitOptions)
    stabilizer: StabilizerOptions = field(default_factory=StabilizerOptions)
    fall: FallConfig = field(default_factory=FallConfig)
    floor_friction: float = 1.0  # Coulomb coefficient between soles and floor
    contact_solver: ContactSolver = ContactSolver.SEQUENTIAL_IMPULSE
    solver_iterations: int = 50  # sweeps per step of the iterative solver
    posture_overrides: tuple[tuple[str, float], ...] = ()  # (joint, rad) over the nominal posture

    def __post_init__(self) -> None:
        if not isinstance(self.robot_profile, str) or not self.robot_profile:
            raise SimulationError(f"WorldConfig.robot_profile must be a profile name, "
                                  f"got {self.robot_profile!r}")
        for name, kind in (("door", DoorConfig), ("stance", StanceConfig), ("camera", CameraConfig),
                           ("execution", ExecutionConfig), ("gait", GaitOptions),
                           ("stabilizer", StabilizerOptions), ("fall", FallConfig)):
            if not isinstance(getattr(self, name), kind):
                raise SimulationError(f"WorldConfig.{name} must be a {kind.__name__}")
        check_ranges(self, WORLD_RANGES, integers=("seed", "grasp_break_steps", "solver_iterations"))
        _require_enum("WorldConfig", "robot_mode", self.robot_mode, RobotMode)
        _require_enum("WorldConfig", "grasp_model", self.grasp_model, GraspModel)
        _require_enum("WorldConfig", "contact_solver", self.contact_solver, ContactSolver)
        self._check_overrides()

    def _check_overrides(self) -> None:
        for entry in self.posture_overrides:
            if (not isinstance(entry, tuple) or len(entry) != 2 or not isinstance(entry[0], str)):
                raise SimulationError(f"WorldConfig.posture_overrides entries must be (joint, rad), "
                                      f"got {entry!r}")
            require("WorldConfig", f"posture_overrides[{entry[0]}]", entry[1], POSTURE_OVERRIDE)

    @property
    def time_step(self) -> float:
        """Seconds per physics step."""
        return 1.0 / self.physics_rate


