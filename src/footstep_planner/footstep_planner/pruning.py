"""Goal-directed pruning: the states one search can never need, dropped before they are checked.

The heuristic (:mod:`~footstep_planner.heuristic`) bounds the cost to go in free space;
it cannot know that a doorway narrower than the body admits it only sideways and only
near the centre line. A search for that leg then explores every way of walking facing
the doorway (which the heuristic rates cheaper) before it walks sideways: the 0.80 m
door took 25,000 expansions. A leg that knows the shape of its solution says so:

* ``yaw_window`` W: every placed foot's yaw stays within W of the goal's yaw, so the
  search never turns away (and its heuristic is built for that window, see
  :class:`~footstep_planner.progress.ProgressTable`);
* ``corridor`` r: every stance centre c(F') stays within r of the line through the
  start's body position and the goal, so the search never wanders across the doorway.
  The body checks at the midpoints between such centres lie in the corridor too (it is
  convex).

Pruning never admits anything: every kept state is still checked for collisions and step
limits, so a pruned search finds a subset of the plans of the full search, and reports
UNREACHABLE or EXPANSION_LIMIT when the leg's assumption is wrong.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from footstep_planner.footstep import Pose2D
from footstep_planner.geometry import BoolArray, FloatArray, wrap_angles
from footstep_planner.validation import FieldRange, check_range

__all__ = ["LegPruning"]


@dataclass(frozen=True)
class LegPruning:
    """Which states a search keeps (the defaults keep all)."""

    yaw_window: float = math.pi
    """Largest yaw of a placed foot from the goal's yaw (rad), (0, pi]."""
    corridor: float = math.inf
    """Largest distance of a stance centre from the start-goal line (m), (0, inf]."""

    def __post_init__(self) -> None:
        check_range("yaw_window", self.yaw_window, FieldRange(0.0, math.pi, "rad", low_open=True))
        if self.corridor != math.inf:
            check_range("corridor", self.corridor, FieldRange(0.0, math.inf, "m", low_open=True))

    @property
    def prunes(self) -> bool:
        """True when some state may be dropped."""
        return self.yaw_window < math.pi or self.corridor < math.inf

    def keeps(self, origin: tuple[float, float], goal: Pose2D, centre_x: FloatArray,
              centre_y: FloatArray, foot_yaw: FloatArray) -> BoolArray:
        """Which of the children (stance centres, foot yaws) the search keeps; ``origin`` is
        the start's body position."""
        keep = np.abs(wrap_angles(foot_yaw - goal.yaw)) <= self.yaw_window
        if self.corridor < math.inf:
            along_x, along_y = goal.x - origin[0], goal.y - origin[1]
            length = math.hypot(along_x, along_y)
            if length > 0.0:
                across = ((centre_x - origin[0]) * along_y - (centre_y - origin[1]) * along_x) / length
                keep &= np.abs(across) <= self.corridor
        return keep
