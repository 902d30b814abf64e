"""One A* search over footstep states (internal to :class:`~footstep_planner.astar.FootstepPlanner`).

States, the goal test and the closed set are described in :mod:`~footstep_planner.astar`.
The inner loop expands a state into every action of the swinging foot at once (numpy), and
drops children in this order, cheapest test first: outside the search region or pruned by
the leg (:mod:`~footstep_planner.pruning`); not cheaper than the best path known to their
closed-set cell; then, only for the survivors and only near an obstacle, colliding. Most
children of a search land in cells already reached at least as cheaply, so checking
collisions last (lazily) skips most of the rectangle tests, which dominate the cost.
"""

from __future__ import annotations

import heapq
import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from door_contract.vocabulary import Foot
from footstep_planner.actions import ActionTable
from footstep_planner.closed_set import ClosedSetGrid
from footstep_planner.footprint import FootprintChecker, body_box_centre
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.geometry import Bounds, wrap_angle, wrap_angles
from footstep_planner.heuristic import FootstepHeuristic, is_goal_centre
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import FootstepPlan, PlanOutcome, PlanResult, failed
from footstep_planner.pruning import LegPruning
from footstep_planner.snapping import snapping_steps

if TYPE_CHECKING:
    from footstep_planner.astar import FootstepPlanner

__all__ = ["Search", "SearchRequest"]

_COST_EPSILON = 1e-9
"""A path must be cheaper by more than this to replace the best one known to a cell."""
_NEAR_CELL = 0.25
"""Cell size (m) of the per-search cache of "is this expansion near an obstacle?"."""
_PRIORITY_SCALE = 1e6
"""f values are compared as integers in units of 1e-6 cost (see ``Search._add``)."""


@dataclass(frozen=True)
class SearchRequest:
    """What one search looks for, within which region, with which settings."""

    goal: Pose2D
    bounds: Bounds
    options: FootstepPlannerOptions
    """The planner's options as set for this attempt."""
    pruning: LegPruning
    origin: tuple[float, float]
    """The start's body position (the pruning corridor's line runs from it to the goal)."""


class Search:
    """One A* run: node arrays, open heap, closed set (internal, single use)."""

    def __init__(self, planner: FootstepPlanner, request: SearchRequest, started: float) -> None:
        options = request.options
        goal, bounds = request.goal, request.bounds
        self._options = options
        self._pruning, self._origin = request.pruning, request.origin
        self._tables = planner.actions.tables
        self._checker = FootprintChecker(planner.world, options)
        self._world = planner.world
        self._reach = planner.actions.body_reach
        self._goal = goal
        self._bounds = bounds
        self._grid = ClosedSetGrid.over(bounds, options)
        self._heuristic = FootstepHeuristic(goal, options, planner.progress_table_within(request.pruning.yaw_window),
                                            planner.actions.max_turn)
        self._started = started
        self._deadline = started + options.max_planning_time
        self._half_separation = options.nominal_foot_separation / 2.0
        self._half_extents = _checked_half_extents(options, len(self._tables[Foot.LEFT].cost))
        self._nodes: list[tuple[float, float, float, bool]] = []  # x, y, yaw, is_left
        self._keys: list[int] = []
        self._parents: list[int] = []
        self._costs: list[float] = []
        self._open: list[tuple[int, float, int]] = []
        self._best: dict[int, float] = {}
        self._near_cells: dict[tuple[int, int], bool] = {}
        self._closest = math.inf

    def run(self, start: Stance, roots: tuple[Footstep, ...]) -> PlanResult:
        """Search until the goal, an exhausted open list, or a bound."""
        for root in roots:
            is_left = root.foot is Foot.LEFT
            key = self._grid.keys(np.array([root.x]), np.array([root.y]), np.array([root.yaw]),
                                  is_left)[0]
            self._best[key] = 0.0
            self._add((root.x, root.y, wrap_angle(root.yaw), is_left), key, -1, 0.0,
                      self._root_estimate(root))
        expansions = 0
        while self._open:
            _, _, index = heapq.heappop(self._open)
            if self._costs[index] > self._best[self._keys[index]]:
                continue  # superseded by a cheaper path to the same cell
            if self._is_goal(index):
                return self._success(start, index, expansions)
            if expansions >= self._options.max_expansions:
                return self._stop(PlanOutcome.EXPANSION_LIMIT, expansions,
                                  f"max_expansions = {self._options.max_expansions} reached")
            if time.perf_counter() > self._deadline:
                limit = self._options.max_planning_time
                return self._stop(PlanOutcome.TIME_LIMIT, expansions,
                                  f"max_planning_time = {limit} s reached")
            expansions += 1
            self._expand(index)
        return self._stop(PlanOutcome.UNREACHABLE, expansions,
                          "every reachable footstep state within the search region was tried "
                          f"(search_margin = {self._options.search_margin} m)")

    def _root_estimate(self, root: Footstep) -> float:
        separation = self._options.nominal_foot_separation
        return self._heuristic.estimate_one(root.stance_centre(separation), root.foot.other)

    def _add(self, node: tuple[float, float, float, bool], key: int, parent: int, cost: float,
             estimate: float) -> None:
        """Record a node (x, y, yaw, is_left) and push it on the open heap.

        Heap entries are (f, h, index) with f = g + w h rounded to 1e-6: among
        equal f the state nearer the goal comes first, which walks the wide
        plateaus of equal f (many step sequences cost the same) straight to
        the goal.  Without the rounding, float noise in f (1e-15) would decide
        those ties instead and the search would go breadth-first.
        """
        index = len(self._nodes)
        self._nodes.append(node)
        self._keys.append(key)
        self._parents.append(parent)
        self._costs.append(cost)
        weighted = round((cost + self._options.heuristic_weight * estimate) * _PRIORITY_SCALE)
        heapq.heappush(self._open, (weighted, estimate, index))

    def _centre(self, index: int) -> Pose2D:
        """c(F) of node ``index``."""
        x, y, yaw, is_left = self._nodes[index]
        offset = -self._half_separation if is_left else self._half_separation
        return Pose2D(x - math.sin(yaw) * offset, y + math.cos(yaw) * offset, yaw)

    def _is_goal(self, index: int) -> bool:
        """Stance centre within tolerance and the closing step collision-free."""
        centre = self._centre(index)
        self._closest = min(self._closest, centre.distance_to(self._goal))
        if not is_goal_centre(centre, self._goal, self._options):
            return False
        return not self._checker.footstep_collides(self._closing_step(index))

    def _closing_step(self, index: int) -> Footstep:
        x, y, yaw, is_left = self._nodes[index]
        support = Footstep(x, y, yaw, Foot.LEFT if is_left else Foot.RIGHT)
        return support.nominal_partner(self._options.nominal_foot_separation)

    def _expand(self, index: int) -> None:
        """Push every valid child of node ``index`` that improves its cell's best cost
        (the order of the tests is in the module docstring)."""
        x, y, yaw, is_left = self._nodes[index]
        table = self._tables[Foot.RIGHT if is_left else Foot.LEFT]
        cos_yaw, sin_yaw = math.cos(yaw), math.sin(yaw)
        points = table.points @ np.array([[cos_yaw, sin_yaw], [-sin_yaw, cos_yaw]])
        points += (x, y)
        count = len(table.cost)
        foot_x, foot_y = points[:count, 0], points[:count, 1]
        centre_x, centre_y = points[count:2 * count, 0], points[count:2 * count, 1]
        foot_yaw = wrap_angles(yaw + table.foot[:, 2])
        valid = self._bounds.contains(foot_x, foot_y)
        if self._pruning.prunes:
            valid &= self._pruning.keeps(self._origin, self._goal, centre_x, centre_y, foot_yaw)
        keys = self._grid.keys(foot_x, foot_y, foot_yaw, not is_left)
        children = self._improving(self._costs[index], np.flatnonzero(valid).tolist(), keys, table)
        if not children:
            return
        chosen = np.array(children)
        if self._near_obstacles(points[-1, 0], points[-1, 1]):
            chosen = chosen[self._free_children(points, chosen, count, foot_yaw[chosen],
                                                yaw + table.midpoint[chosen, 2])]
            if len(chosen) == 0:
                return
        next_swing = Foot.LEFT if is_left else Foot.RIGHT  # the support foot swings after the child
        estimates = self._heuristic.estimate(centre_x[chosen], centre_y[chosen], foot_yaw[chosen],
                                             next_swing).tolist()
        self._push_children(index, chosen.tolist(), keys, estimates, table,
                            (foot_x.tolist(), foot_y.tolist(), foot_yaw.tolist()))

    def _improving(self, cost_so_far: float, candidates: list[int], keys: list[int],
                   table: ActionTable) -> list[int]:
        """The candidates whose path would be cheaper than the best known to their cell."""
        best, step_costs, infinity = self._best, table.step_costs, math.inf
        return [child for child in candidates
                if cost_so_far + step_costs[child] < best.get(keys[child], infinity) - _COST_EPSILON]

    def _push_children(self, parent: int, children: list[int], keys: list[int],
                       estimates: list[float], table: ActionTable,
                       poses: tuple[list[float], list[float], list[float]]) -> None:
        """Record and push the children (``estimates`` in the same order) that are still new
        or cheaper than their cell's best (two children may share a cell).

        This is :meth:`_add` inlined over the children: it is the planner's
        innermost loop.
        """
        best, cost_so_far, step_costs = self._best, self._costs[parent], table.step_costs
        is_left = table.swing_foot is Foot.LEFT
        nodes, node_keys, parents, costs = self._nodes, self._keys, self._parents, self._costs
        heap, weight, push = self._open, self._options.heuristic_weight, heapq.heappush
        for child, estimate in zip(children, estimates):
            key = keys[child]
            cost = cost_so_far + step_costs[child]
            if cost >= best.get(key, math.inf) - _COST_EPSILON:
                continue
            best[key] = cost
            push(heap, (round((cost + weight * estimate) * _PRIORITY_SCALE), estimate, len(nodes)))
            nodes.append((poses[0][child], poses[1][child], poses[2][child], is_left))
            node_keys.append(key)
            parents.append(parent)
            costs.append(cost)

    def _near_obstacles(self, centre_x: float, centre_y: float) -> bool:
        """Could anything checked in this expansion touch an obstacle?  (Bounding test.)

        Everything checked lies within ``body_reach`` of the support foot's
        stance centre c(F); the answer is cached per coarse cell (a cell is
        near when its centre is within body_reach + half its diagonal).
        """
        cell = (math.floor(centre_x / _NEAR_CELL), math.floor(centre_y / _NEAR_CELL))
        near = self._near_cells.get(cell)
        if near is None:
            distance = self._world.distance_lower_bound((cell[0] + 0.5) * _NEAR_CELL,
                                                         (cell[1] + 0.5) * _NEAR_CELL)
            near = distance <= self._reach + _NEAR_CELL * math.sqrt(0.5)
            self._near_cells[cell] = near
        return near

    def _free_children(self, points: np.ndarray, chosen: np.ndarray, count: int, foot_yaw: np.ndarray,
                       midpoint_yaw: np.ndarray) -> np.ndarray:
        """Which ``chosen`` children have their sole, single-support body c(F') and double-stance
        body (rows of ``points``: soles, then centres, then midpoints, ``count`` each) all free:
        one batched test of 3 n rectangles."""
        rows = np.concatenate((chosen, chosen + count, chosen + 2 * count))
        half_length, half_width = self._half_extents
        yaw = np.concatenate((foot_yaw, foot_yaw, midpoint_yaw))
        x, y = points[rows, 0], points[rows, 1]  # copies (fancy indexing)
        if self._options.body_offset:  # the bodies' boxes sit ahead of their centres; the soles' do not
            soles = len(chosen)
            x[soles:], y[soles:] = body_box_centre(x[soles:], y[soles:], yaw[soles:], self._options.body_offset)
        hits = self._world.rectangles_touch(x, y, yaw, half_length[rows], half_width[rows])
        return np.asarray(~hits.reshape(3, -1).any(axis=0))

    def _success(self, start: Stance, index: int, expansions: int) -> PlanResult:
        steps = (*self._path(index), self._closing_step(index))
        snap = snapping_steps(steps[-1], self._goal, self._options, self._checker) if self._options.snap_to_goal else ()
        steps += snap
        cost = self._costs[index] + self._options.step_cost * (1 + len(snap))
        elapsed = time.perf_counter() - self._started
        plan = FootstepPlan(start, self._goal, steps, cost, expansions, elapsed)
        return PlanResult(PlanOutcome.SUCCESS, f"{len(steps)} steps found", plan, expansions,
                          elapsed)

    def _path(self, index: int) -> tuple[Footstep, ...]:
        """Footsteps from the first step after the root to node ``index``."""
        steps = []
        while self._parents[index] >= 0:
            x, y, yaw, is_left = self._nodes[index]
            steps.append(Footstep(x, y, yaw, Foot.LEFT if is_left else Foot.RIGHT))
            index = self._parents[index]
        return tuple(reversed(steps))

    def _stop(self, outcome: PlanOutcome, expansions: int, why: str) -> PlanResult:
        reason = (f"no plan: {why} after {expansions} expansions; the closest stance centre "
                  f"came {self._closest:.2f} m from the goal")
        return failed(outcome, reason, expansions, self._started)


def _checked_half_extents(options: FootstepPlannerOptions, count: int) -> tuple[np.ndarray, np.ndarray]:
    """Half length and half width, margins included, of the rectangles one expansion checks:
    ``count`` soles, then ``count`` single-support bodies, then ``count`` double-stance bodies."""
    sole = (options.foot_length / 2.0 + options.foot_margin, options.foot_width / 2.0 + options.foot_margin)
    body = (options.body_half_depth + options.body_margin, options.body_half_width + options.body_margin)
    return (np.repeat([sole[0], body[0], body[0]], count), np.repeat([sole[1], body[1], body[1]], count))
