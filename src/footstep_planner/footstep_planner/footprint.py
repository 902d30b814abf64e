"""Collision checks of the robot's soles and body against a :class:`World`.

The body is a rectangle ``2 * body_half_width`` wide (across the shoulders,
along the body's y axis) and ``2 * body_half_depth`` deep (along its x axis),
centred between the feet and turned with the stance yaw.  Walking through a
doorway sideways (stance yaw +-90 degrees from the door normal) therefore puts
the body's depth, not its width, across the opening.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.geometry import BoolArray, FloatArray
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.world import World

__all__ = ["FootprintChecker", "body_box_centre"]


@dataclass(frozen=True)
class FootprintChecker:
    """Sole and body collision checks with the options' dimensions and margins."""

    world: World
    options: FootstepPlannerOptions

    def soles_collide(self, x: FloatArray, y: FloatArray, yaw: FloatArray) -> BoolArray:
        """For N sole poses, does each sole (grown by foot_margin) touch an obstacle?"""
        options = self.options
        return self.world.rectangles_collide(x, y, yaw, options.foot_length, options.foot_width,
                                             options.foot_margin)

    def bodies_collide(self, x: FloatArray, y: FloatArray, yaw: FloatArray) -> BoolArray:
        """For N body poses, does each body rectangle (grown by body_margin) touch an obstacle?"""
        options = self.options
        x, y = body_box_centre(x, y, yaw, options.body_offset)
        return self.world.rectangles_collide(x, y, yaw, 2.0 * options.body_half_depth,
                                             2.0 * options.body_half_width, options.body_margin)

    def footstep_collides(self, step: Footstep) -> bool:
        """Does this sole touch an obstacle?"""
        return bool(self.soles_collide(np.array([step.x]), np.array([step.y]),
                                       np.array([step.yaw]))[0])

    def body_collides(self, pose: Pose2D) -> bool:
        """Does the body at ``pose`` touch an obstacle?"""
        return bool(self.bodies_collide(np.array([pose.x]), np.array([pose.y]),
                                        np.array([pose.yaw]))[0])

    def stance_collision(self, stance: Stance) -> str | None:
        """Why the stance collides ("left sole touches wall_hinge_side"), or None when free."""
        options = self.options
        for step in (stance.left, stance.right):
            names = self.world.colliding_obstacles(step.x, step.y, step.yaw, options.foot_length,
                                                   options.foot_width, options.foot_margin)
            if names:
                return f"{step.foot.value} sole touches {', '.join(names)}"
        body = stance.body_pose
        box_x, box_y = body_box_centre(body.x, body.y, body.yaw, options.body_offset)
        names = self.world.colliding_obstacles(box_x, box_y, body.yaw,
                                               2.0 * options.body_half_depth,
                                               2.0 * options.body_half_width, options.body_margin)
        return f"body touches {', '.join(names)}" if names else None


def body_box_centre(x: Any, y: Any, yaw: Any, offset: float) -> tuple[Any, Any]:
    """Centre of the body rectangle of bodies at (x, y, yaw): ``offset`` ahead along the
    heading (scalars or arrays alike)."""
    if offset == 0.0:
        return x, y
    return x + offset * np.cos(yaw), y + offset * np.sin(yaw)
