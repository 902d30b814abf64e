"""A quick proof that a goal is unreachable, before any footstep search.

The search checks the body rectangle at a chain of centres
c(F0), midpoint(F0, F1), c(F1), midpoint(F1, F2), ... each within
``hop`` = the action set's ``max_body_hop`` of the previous one.  A free body
rectangle contains the disc of radius ``r = min(half width, half depth) +
body_margin`` about its centre, so every chain point has clearance >= r and
every point of the segments between them has clearance >= r - hop / 2.  The
grid cells such a segment crosses form a 4-connected chain, and each cell's
centre lies within h (half the cell diagonal) of the segment, so has
clearance >= tau = r - hop / 2 - h.

So: mark a cell blocked only when its centre is within tau of an obstacle;
if no 4-connected chain of free cells joins the start's centre to a cell near
the goal, no footstep plan exists and the planner answers UNREACHABLE at
once instead of exhausting its expansion budget.  When tau <= 0 nothing can
be proved and the check says "maybe reachable".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from footstep_planner.geometry import BoolArray, Bounds
from footstep_planner.world import World

__all__ = ["CELL_SIZE", "ReachabilityQuery", "flood_fill", "may_reach"]

CELL_SIZE = 0.05
"""Grid cell of the reachability check (m)."""
MAX_CELLS = 1_000_000
"""Larger regions (about 2.5 km^2) are not checked: the search and its bounds decide."""


@dataclass(frozen=True)
class ReachabilityQuery:
    """A start-to-goal question for body centres that keep ``body_radius`` clearance.

    Attributes:
        bounds: the region the body centres stay in (m).
        seeds: start body centres (m).
        goal: the goal body centre (m).
        goal_radius: how close to ``goal`` the final centre must come (m).
        body_radius: clearance every checked body centre has (m).
        hop: the largest distance between consecutive checked body centres (m).
    """

    bounds: Bounds
    seeds: tuple[tuple[float, float], ...]
    goal: tuple[float, float]
    goal_radius: float
    body_radius: float
    hop: float

    @property
    def threshold(self) -> float:
        """tau: cells closer than this to an obstacle cannot hold the body's path (m)."""
        return self.body_radius - self.hop / 2.0 - CELL_SIZE * math.sqrt(0.5)


def may_reach(world: World, query: ReachabilityQuery) -> bool:
    """False only when the goal is provably unreachable (see the module docstring).

    Answering True is always safe (the search then decides), so a clear
    straight line from a start centre to the goal skips the grid.
    """
    threshold = query.threshold - 1e-6
    grid = _Grid.over(query.bounds)
    if threshold <= 0.0 or grid.size > MAX_CELLS or _straight_line_clear(world, query, threshold):
        return True
    free = ~world.near_obstacles(grid.centres(), threshold).reshape(grid.shape)
    seeds = grid.cells_near(query.seeds, 0.0) & free
    goal_cells = grid.cells_near((query.goal,), query.goal_radius + grid.half_diagonal)
    if not seeds.any():
        return True  # the start is off the grid or hemmed in: nothing to prove
    return bool((flood_fill(free, seeds) & goal_cells).any())


def _straight_line_clear(world: World, query: ReachabilityQuery, threshold: float) -> bool:
    """Some start centre sees the goal along a line that keeps ``threshold`` clearance."""
    goal = np.array(query.goal)
    for seed in query.seeds:
        start = np.array(seed)
        count = max(2, math.ceil(float(np.hypot(*(goal - start))) / (CELL_SIZE / 2.0)) + 1)
        samples = start + np.linspace(0.0, 1.0, count)[:, None] * (goal - start)
        if not world.near_obstacles(samples, threshold).any():
            return True
    return False


@dataclass(frozen=True)
class _Grid:
    """A regular grid of CELL_SIZE cells covering some bounds; row = y index, column = x."""

    x0: float
    y0: float
    shape: tuple[int, int]

    @classmethod
    def over(cls, bounds: Bounds) -> _Grid:
        columns = max(1, math.ceil((bounds.x_max - bounds.x_min) / CELL_SIZE))
        rows = max(1, math.ceil((bounds.y_max - bounds.y_min) / CELL_SIZE))
        return cls(bounds.x_min, bounds.y_min, (rows, columns))

    @property
    def size(self) -> int:
        """Number of cells."""
        return self.shape[0] * self.shape[1]

    @property
    def half_diagonal(self) -> float:
        return CELL_SIZE * math.sqrt(0.5)

    def centres(self) -> np.ndarray:
        """Cell centres, (rows * columns, 2), row-major."""
        xs = self.x0 + (np.arange(self.shape[1]) + 0.5) * CELL_SIZE
        ys = self.y0 + (np.arange(self.shape[0]) + 0.5) * CELL_SIZE
        grid_x, grid_y = np.meshgrid(xs, ys)
        return np.column_stack((grid_x.ravel(), grid_y.ravel()))

    def cells_near(self, points: tuple[tuple[float, float], ...], radius: float) -> BoolArray:
        """Cells containing a point, or whose centre lies within ``radius`` of one."""
        mask = np.zeros(self.shape, dtype=bool)
        for x, y in points:
            column, row = int((x - self.x0) // CELL_SIZE), int((y - self.y0) // CELL_SIZE)
            if 0 <= row < self.shape[0] and 0 <= column < self.shape[1]:
                mask[row, column] = True
            span = math.ceil(radius / CELL_SIZE) + 1
            rows = np.arange(max(row - span, 0), min(row + span + 1, self.shape[0]))
            columns = np.arange(max(column - span, 0), min(column + span + 1, self.shape[1]))
            centre_x = self.x0 + (columns + 0.5) * CELL_SIZE
            centre_y = self.y0 + (rows + 0.5) * CELL_SIZE
            within = np.hypot(centre_x[None, :] - x, centre_y[:, None] - y) <= radius
            if within.size:
                mask[np.ix_(rows, columns)] |= within
        return mask


def flood_fill(free: BoolArray, seeds: BoolArray) -> BoolArray:
    """Cells of ``free`` 4-connected to a seed.

    Alternates two sweeps until nothing changes: every horizontal run of free
    cells touching a reached cell becomes reached, then every vertical run.
    Each round costs a few array operations; the number of rounds is the
    number of turns the connecting paths need, not their length.
    """
    reached = seeds & free
    while True:
        count = int(reached.sum())
        reached = _spread_along_rows(free, reached)
        reached = _spread_along_rows(free.T, reached.T).T
        if int(reached.sum()) == count:
            return reached


def _spread_along_rows(free: BoolArray, reached: BoolArray) -> BoolArray:
    """Mark whole horizontal runs of free cells that contain a reached cell."""
    starts = free.copy()
    starts[:, 1:] &= ~free[:, :-1]
    labels = np.cumsum(starts.ravel()).reshape(free.shape) * free
    touched = np.zeros(int(labels.max()) + 1, dtype=bool)
    touched[labels[reached & free]] = True
    touched[0] = False
    return touched[labels]
