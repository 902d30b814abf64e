"""The simulated world of the sim bridge's node parameters, without ROS."""

from __future__ import annotations

from typing import Any

from door_contract.vocabulary import DoorOpening, HingeSide
from door_sim_bridge.world import (
    CameraConfig,
    ContactSolver,
    DoorConfig,
    GraspModel,
    StanceConfig,
    WindConfig,
    WorldConfig,
)
from door_sim_bridge.world_ranges import COLOUR_FIELDS

__all__ = ["world_config"]



def world_config(p: dict[str, Any]) -> WorldConfig:
    """The world of the node's parameters (SimulationError names a bad field)."""
    camera_rate = p["camera_rate"] if p["camera_rate"] > 0 else 1.0
    colours: dict[str, Any] = {name: tuple(p[name]) for name in COLOUR_FIELDS}  # DoorConfig checks each
    return WorldConfig(
        robot_profile=p["robot_profile"], physics_rate=p["physics_rate"], seed=p["seed"],
        grasp_break_force=p["grasp_break_force"], grasp_model=GraspModel(p["grasp_model"]),
        contact_solver=ContactSolver(p["contact_solver"]), solver_iterations=p["solver_iterations"],
        door=DoorConfig(opening=DoorOpening(p["door_opening"]), hinge_side=HingeSide(p["hinge_side"]),
                        width=p["door_width"], handle_height=p["handle_height"],
                        closer_stiffness=p["closer_stiffness"], wind=WindConfig(amplitude=p["wind_amplitude"]),
                        **colours),
        stance=StanceConfig(distance=p["stance_distance"], lateral_offset=p["stance_lateral"], yaw=p["stance_yaw"]),
        camera=CameraConfig(width=p["camera_width"], height=p["camera_height"], frame_rate_hz=camera_rate,
                            depth_noise_coefficient=p["depth_noise"], colour_noise_sigma=p["colour_noise"],
                            light_direction=tuple(p["light_direction"])))
