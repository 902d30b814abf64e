"""What the footstep planner node proposes from a finished plan, without ROS.

The plan in the ``/footstep_plan`` convention (even index = left foot), the markers that
draw it (plain :class:`~door_contract.marker_shapes.MarkerShape` values; the node converts
them with :func:`door_contract.converters.markers.shapes_to_marker_array`), and the summary
the planning outcome reports. All poses are in ``odom`` (m, rad).
"""

from __future__ import annotations

import math

import numpy as np

from door_contract.converters.footsteps import FootPlacement
from door_contract.marker_shapes import MarkerKind, MarkerShape
from door_contract.vocabulary import Foot
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.plan import FootstepPlan

__all__ = ["FOOT_COLOURS", "contract_footsteps", "footstep_shapes", "walked_length"]

FOOT_COLOURS = {Foot.LEFT: (0.1, 0.4, 1.0, 0.8), Foot.RIGHT: (1.0, 0.3, 0.1, 0.8)}
"""RGBA of a footstep marker: left blue, right orange."""
MARKER_HEIGHT = 0.01
"""Height (m) of a footstep marker's centre above the ground; the marker is 0.02 m thick."""


def contract_footsteps(start: Stance, plan: FootstepPlan) -> list[FootPlacement]:
    """The plan in the /footstep_plan convention: even index = left foot (a step in place first
    when the plan starts with the right foot)."""
    steps = list(plan.steps)
    if steps and steps[0].foot is Foot.RIGHT:
        steps.insert(0, start.left)
    return [FootPlacement(s.foot, s.x, s.y, s.yaw) for s in steps]


def footstep_shapes(steps: list[FootPlacement], foot_length: float, foot_width: float) -> list[MarkerShape]:
    """One sole-sized box a step (namespace ``footsteps``, id = index), coloured by foot."""
    shapes = []
    for index, step in enumerate(steps):
        pose = np.eye(4)
        cos, sin = math.cos(step.yaw), math.sin(step.yaw)
        pose[:2, :2] = [[cos, -sin], [sin, cos]]
        pose[:3, 3] = step.x, step.y, MARKER_HEIGHT
        shapes.append(MarkerShape("footsteps", index, MarkerKind.CUBE, FOOT_COLOURS[step.foot],
                                  (foot_length, foot_width, 0.02), pose=pose))
    return shapes


def walked_length(start: Stance, goal: Pose2D) -> float:
    """Straight-line distance (m) from the middle of the start stance to the last leg's goal."""
    middle_x, middle_y = (start.left.x + start.right.x) / 2, (start.left.y + start.right.y) / 2
    return float(np.hypot(goal.x - middle_x, goal.y - middle_y))
