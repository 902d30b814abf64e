"""Randomised door scenes for the Table II evaluation with the head search (sim core).

A :class:`TrialScene` is one start of the door task as the graph has it: the robot (TALOS,
the sim bridge's 640×480 head camera with its 60° vertical field of view, its arms rendered)
stands ``distance`` from the door plane, ``lateral`` aside, turned by ``yaw`` from facing
the door (the paper's "orientation ... about the vertical where the robot is standing",
[Banerjee 2015] Sec. V); the door and its appearance are drawn over the Monte-Carlo's full ranges
(issue 13): width 0.80–1.00 m, handle height 0.85–1.10 m, push/pull, left/right hinge, depth
noise k ≤ 0.005 (σ = k·z², 8 cm at 4 m), colours from the palettes below (a white leaf in a
white wall and frame included), and a room light from a random direction in front of the wall.

Only the evaluation and the tests import this module (it needs the sim).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from door_contract.vocabulary import DoorOpening, HingeSide

if TYPE_CHECKING:  # the sim is imported where a world is built, not with this module
    from door_sim_bridge.world import WorldConfig

__all__ = ["Appearance", "Colour", "TrialScene", "random_appearance", "random_scene", "world_config"]

Colour = tuple[float, float, float]

LEAF_COLOURS: tuple[Colour, ...] = ((0.55, 0.33, 0.17), (0.76, 0.60, 0.42), (0.20, 0.40, 0.25),
                                    (0.60, 0.15, 0.12), (1.0, 1.0, 1.0), (0.45, 0.52, 0.60))
"""Brown, light wood, green, red, white, grey-blue."""
FRAME_COLOURS: tuple[Colour, ...] = ((0.92, 0.92, 0.88), (1.0, 1.0, 1.0), (0.35, 0.22, 0.12), (0.55, 0.55, 0.55))
"""Off-white, white, dark wood, grey."""
HANDLE_COLOURS: tuple[Colour, ...] = ((0.85, 0.70, 0.15), (0.75, 0.75, 0.78), (0.08, 0.08, 0.08), (0.25, 0.25, 0.25))
"""Brass, steel, black, dark grey."""
WALL_COLOURS: tuple[Colour, ...] = ((0.45, 0.58, 0.72), (1.0, 1.0, 1.0), (0.85, 0.80, 0.68), (0.70, 0.80, 0.65))
"""Blue-grey, white, beige, light green."""
FLOOR_COLOURS: tuple[Colour, ...] = ((0.30, 0.30, 0.30), (0.15, 0.15, 0.15), (0.60, 0.50, 0.38))
"""Grey, dark grey, tan."""


@dataclass(frozen=True)
class Appearance:
    """Scene colours (RGB in [0, 1]) and the light direction (towards the light, odom)."""

    leaf: Colour = LEAF_COLOURS[0]
    frame: Colour = FRAME_COLOURS[0]
    handle: Colour = HANDLE_COLOURS[0]
    wall: Colour = WALL_COLOURS[0]
    floor: Colour = FLOOR_COLOURS[0]
    light: tuple[float, float, float] = (-50.0, 30.0, 100.0)


@dataclass(frozen=True)
class TrialScene:
    """One randomised start (see the module docstring); lengths in m, angles in rad."""

    distance: float
    yaw: float
    lateral: float = 0.0
    width: float = 0.914
    handle_height: float = 0.91
    opening: DoorOpening = DoorOpening.PUSH
    hinge_side: HingeSide = HingeSide.LEFT
    depth_noise: float = 0.0
    appearance: Appearance = Appearance()
    seed: int = 0


def random_appearance(rng: np.random.Generator) -> Appearance:
    """Colours drawn from the palettes; the light above the robot's side of the wall.

    The light's azimuth is within ±60° of −x (towards the robot), its elevation 30–70°: a room
    light in front of the wall. TinyRenderer casts no shadows, so a light behind the wall
    would still light the jambs' side faces while the faces towards the robot get ambient
    light only — a scene no camera sees (a white leaf in a white frame then shows only one
    side face of each jamb, a door-width apart but off by a jamb).
    """
    def pick(palette: tuple[Colour, ...]) -> Colour:
        return palette[int(rng.integers(len(palette)))]

    azimuth = math.pi + math.radians(rng.uniform(-60.0, 60.0))
    elevation = math.radians(rng.uniform(30.0, 70.0))
    light = (math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth), math.sin(elevation))
    return Appearance(pick(LEAF_COLOURS), pick(FRAME_COLOURS), pick(HANDLE_COLOURS), pick(WALL_COLOURS),
                      pick(FLOOR_COLOURS), light)


def random_scene(distance: float, yaw: float, rng: np.random.Generator, seed: int,
                 lateral_range: float = 0.6, max_depth_noise: float = 0.005) -> TrialScene:
    """A scene of one Table II cell (``distance``, ``yaw``) with everything else drawn."""
    return TrialScene(distance, yaw, float(rng.uniform(-lateral_range, lateral_range)),
                      float(rng.uniform(0.80, 1.00)), float(rng.uniform(0.85, 1.10)),
                      (DoorOpening.PUSH, DoorOpening.PULL)[int(rng.integers(2))],
                      (HingeSide.LEFT, HingeSide.RIGHT)[int(rng.integers(2))],
                      float(rng.uniform(0.0, max_depth_noise)), random_appearance(rng), seed)


def world_config(scene: TrialScene) -> WorldConfig:
    """The sim core's WorldConfig of a scene: the sim bridge's camera and robot visuals, on the
    kinematic robot (:class:`~door_sim_bridge.world.config.RobotMode`): the search turns the body
    in place by placing the base (:mod:`door_evaluation.detection.search_trial`), which the physical robot
    refuses, and only the camera's view is measured."""
    from door_sim_bridge.world import CameraConfig, DoorConfig, RobotMode, StanceConfig, WorldConfig

    look = scene.appearance
    door = DoorConfig(opening=scene.opening, hinge_side=scene.hinge_side,
                      width=scene.width, handle_height=scene.handle_height, door_colour=look.leaf,
                      frame_colour=look.frame, handle_colour=look.handle, wall_colour=look.wall,
                      floor_colour=look.floor)
    camera = CameraConfig(depth_noise_coefficient=scene.depth_noise, light_direction=look.light)
    stance = StanceConfig(distance=scene.distance, lateral_offset=scene.lateral, yaw=scene.yaw)
    return WorldConfig(door=door, stance=stance, camera=camera, seed=scene.seed,
                       robot_mode=RobotMode.KINEMATIC)
