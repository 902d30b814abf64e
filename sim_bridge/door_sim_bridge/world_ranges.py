"""The intervals of the simulated world's configuration (:mod:`door_sim_bridge.world.config`),
by field name, apart from it so that the node's parameters can take them without importing the
simulator (:mod:`door_sim_bridge.parameters`). Ranges that depend on other fields are the
configuration's own checks.
"""

from __future__ import annotations

import math

from door_contract.ranges import FieldRange

__all__ = ["CAMERA_RANGES", "COLOUR_COMPONENT", "COLOUR_FIELDS", "DIRECTION_COMPONENT", "DOOR_RANGES",
           "EXECUTION_RANGES", "FALL_RANGES", "POSTURE_OVERRIDE", "STANCE_RANGES", "WIND_RANGES", "WORLD_RANGES"]

COLOUR_COMPONENT = FieldRange(0.0, 1.0, "")
"""Each of a colour's red, green and blue."""

COLOUR_FIELDS = ("door_colour", "frame_colour", "handle_colour", "wall_colour", "floor_colour")
"""The scene's colours: :class:`~door_sim_bridge.world.config.DoorConfig` fields and sim bridge
parameters of the same names (RGB, each in :data:`COLOUR_COMPONENT`)."""

DIRECTION_COMPONENT = FieldRange(-1e6, 1e6, "")
"""Each of a direction's x, y and z."""

WIND_RANGES = {"amplitude": FieldRange(0.0, 100.0, "N·m"), "frequency": FieldRange(0.0, 10.0, "Hz"),
               "bias": FieldRange(-100.0, 100.0, "N·m")}
"""The interval of every :class:`~door_sim_bridge.world.config.WindConfig` field."""

DOOR_RANGES: dict[str, FieldRange] = {
    "width": FieldRange(0.5, 1.5, "m"), "height": FieldRange(1.5, 3.0, "m"), "thickness": FieldRange(0.01, 0.1, "m"),
    "mass": FieldRange(1.0, 200.0, "kg"), "floor_gap": FieldRange(0.0, 0.05, "m"),
    "handle_height": FieldRange(0.4, 2.0, "m"), "handle_backset": FieldRange(0.03, 0.2, "m"),
    "lever_length": FieldRange(0.05, 0.25, "m"), "lever_standoff": FieldRange(0.03, 0.12, "m"),
    "grasp_fraction": FieldRange(0.2, 1.0, ""), "handle_max_angle": FieldRange(0.2, 1.5, "rad"),
    "hinge_max_angle": FieldRange(0.5, 3.0, "rad"), "latch_release_angle": FieldRange(0.05, 1.45, "rad"),
    "latch_engage_angle": FieldRange(0.002, 0.2, "rad"), "latch_play": FieldRange(0.0, 0.2, "rad"),
    "closer_stiffness": FieldRange(0.0, 200.0, "N·m/rad"), "closer_preload": FieldRange(0.0, 50.0, "N·m"),
    "hinge_damping": FieldRange(0.0, 100.0, "N·m·s/rad"), "hinge_friction": FieldRange(0.0, 20.0, "N·m"),
    "handle_stiffness": FieldRange(0.0, 20.0, "N·m/rad"), "handle_preload": FieldRange(0.0, 5.0, "N·m"),
    "handle_damping": FieldRange(0.0, 5.0, "N·m·s/rad"), "handle_friction": FieldRange(0.0, 2.0, "N·m"),
    "handle_mass": FieldRange(0.05, 5.0, "kg"),
}
"""The interval of every numeric :class:`~door_sim_bridge.world.config.DoorConfig` field (some
narrowed further by the others)."""

STANCE_RANGES = {"distance": FieldRange(0.3, 8.0, "m"), "lateral_offset": FieldRange(-3.0, 3.0, "m"),
                 "yaw": FieldRange(-math.pi, math.pi, "rad")}
"""The interval of every :class:`~door_sim_bridge.world.config.StanceConfig` field."""

CAMERA_RANGES = {
    "width": FieldRange(16, 4096, "px"), "height": FieldRange(16, 4096, "px"),
    "vertical_fov_deg": FieldRange(10.0, 120.0, "deg"), "near": FieldRange(0.01, 1.0, "m"),
    "frame_rate_hz": FieldRange(0.1, 60.0, "Hz"), "depth_noise_coefficient": FieldRange(0.0, 0.1, "1/m"),
    "colour_noise_sigma": FieldRange(0.0, 50.0, "levels"), "head_pitch": FieldRange(-1.0, 1.0, "rad"),
}
"""The interval of every numeric :class:`~door_sim_bridge.world.config.CameraConfig` field but
``far`` (beyond ``near``)."""

EXECUTION_RANGES = {
    "settle_time": FieldRange(0.0, 5.0, "s"), "goal_tolerance": FieldRange(1e-4, 1.0, "rad"),
    "held_wrist_tolerance": FieldRange(1e-4, 1.0, "rad"), "start_tolerance": FieldRange(1e-4, 3.2, "rad"),
    "velocity_limit_scale": FieldRange(0.1, 10.0, ""), "step_duration": FieldRange(0.05, 10.0, "s"),
    "collision_depth": FieldRange(0.0, 0.5, "m"),
}
"""The interval of every :class:`~door_sim_bridge.world.config.ExecutionConfig` field."""

FALL_RANGES = {"height_fraction": FieldRange(0.1, 0.95, ""), "max_tilt": FieldRange(0.1, 1.5, "rad")}
"""The interval of every :class:`~door_sim_bridge.world.config.FallConfig` field."""

WORLD_RANGES = {
    "seed": FieldRange(0, 2**31 - 1, ""), "grasp_break_steps": FieldRange(1, 1000, "steps"),
    "physics_rate": FieldRange(60.0, 2000.0, "Hz"), "gravity": FieldRange(0.0, 20.0, "m/s²"),
    "grasp_distance": FieldRange(0.001, 0.2, "m"), "grasp_break_force": FieldRange(1.0, 1e5, "N"),
    "joint_force_scale": FieldRange(0.1, 100.0, ""), "floor_friction": FieldRange(0.05, 3.0, ""),
    "solver_iterations": FieldRange(1, 10000, "sweeps"),
}
"""The interval of every numeric :class:`~door_sim_bridge.world.config.WorldConfig` field."""

POSTURE_OVERRIDE = FieldRange(-2 * math.pi, 2 * math.pi, "rad")
"""Each joint angle of :attr:`~door_sim_bridge.world.config.WorldConfig.posture_overrides`."""
