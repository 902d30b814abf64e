"""The search's closed set: states merge in cells of (grid_resolution, yaw_resolution).

Every check of a step depends on the support foot and the action only, never on how the
foot was reached, so two states in one cell are interchangeable up to the cell's size; the
search keeps the cheapest cost known per cell (:mod:`~footstep_planner.search`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from footstep_planner.geometry import Bounds
from footstep_planner.options import FootstepPlannerOptions

__all__ = ["ClosedSetGrid"]


@dataclass(frozen=True)
class ClosedSetGrid:
    """Integer keys of states: cell of the sole centre, yaw bin, foot.

    key = ((ix * rows + iy) * yaw_bins + iyaw) * 2 + (1 for a left foot).
    """

    x0: float
    y0: float
    rows: int
    resolution: float
    yaw_bins: int

    @classmethod
    def over(cls, bounds: Bounds, options: FootstepPlannerOptions) -> ClosedSetGrid:
        rows = math.ceil((bounds.y_max - bounds.y_min) / options.grid_resolution) + 1
        yaw_bins = max(1, round(2.0 * math.pi / options.yaw_resolution))
        return cls(bounds.x_min, bounds.y_min, rows, options.grid_resolution, yaw_bins)

    def keys(self, x: np.ndarray, y: np.ndarray, yaw: np.ndarray, left: bool) -> list[int]:
        """Keys of several soles of the same foot."""
        column = np.floor((x - self.x0) / self.resolution).astype(np.int64)
        row = np.floor((y - self.y0) / self.resolution).astype(np.int64)
        bins = np.floor((yaw + math.pi) * (self.yaw_bins / (2.0 * math.pi)))
        yaw_bin = bins.astype(np.int64) % self.yaw_bins  # the bins wrap: no need to wrap yaw
        keys: list[int] = (((column * self.rows + row) * self.yaw_bins + yaw_bin) * 2 + int(left)).tolist()
        return keys
