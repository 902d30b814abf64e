"""A* (and weighted A*) over footstep states.

A state is the support foot F just placed: (x, y, yaw, which foot).  From F
the other foot swings by one of the :mod:`~footstep_planner.actions`; the
child state is the landed foot.  A step is valid when

* the landed sole is collision-free and inside the search region,
* the body is collision-free at the double stance (F, F') (centred between
  the soles, mean yaw) and at c(F'), the nominal single-support pose over F'.

Every check depends on F and the action only, never on how F was reached, so
states merge in a closed set keyed on a (grid_resolution, yaw_resolution)
grid: a dictionary of the cheapest cost known per cell.  A state popped at a
higher cost than its cell's best is skipped; a cheaper path to an expanded
cell re-opens it (the progress heuristic is admissible but not consistent).

The goal test runs when a state is popped: its stance centre c(F) is within
the goal tolerances and the closing step (the other foot beside F) is free;
the plan is the path plus that closing step.  Costs and the admissible
heuristic are in :mod:`~footstep_planner.heuristic`; a coarse
reachability check (:mod:`~footstep_planner.reachability`) answers hopeless
requests at once; ``max_expansions`` and ``max_planning_time`` bound every
search.
"""

from __future__ import annotations

import copy
import heapq
import math
import time
from dataclasses import dataclass, replace

import numpy as np

from footstep_planner.actions import ActionSet, ActionTable, is_reachable_step
from footstep_planner.footprint import FootprintChecker
from footstep_planner.footstep import Foot, Footstep, Pose2D, Stance
from footstep_planner.geometry import Bounds, wrap_angle, wrap_angles
from footstep_planner.heuristic import FootstepHeuristic, ProgressTable, is_goal_centre
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import FootstepPlan, PlanOutcome, PlanResult
from footstep_planner.reachability import CELL_SIZE, ReachabilityQuery, may_reach
from footstep_planner.world import World

_COST_EPSILON = 1e-9
"""A path must be cheaper by more than this to replace the best one known to a cell."""
_NEAR_CELL = 0.25
"""Cell size (m) of the per-search cache of "is this expansion near an obstacle?"."""
_PRIORITY_SCALE = 1e6
"""f values are compared as integers in units of 1e-6 cost (see ``_Search._add``)."""


class FootstepPlanner:
    """Plans footsteps in one world with one set of options (both fixed at construction)."""

    def __init__(self, world: World, options: FootstepPlannerOptions | None = None) -> None:
        self._world = world
        self._options = options if options is not None else FootstepPlannerOptions()
        self._actions = ActionSet.from_options(self._options)
        self._checker = FootprintChecker(world, self._options)
        self._progress = ProgressTable.build(self._actions.centre_shifts, self._actions.max_turn,
                                             self._options.goal_yaw_tolerance)

    def with_world(self, world: World) -> FootstepPlanner:
        """The same planner in another world (e.g. a new door estimate), reusing the action
        and heuristic tables, which depend on the options only."""
        planner = copy.copy(self)
        planner._world = world
        planner._checker = FootprintChecker(world, self._options)
        return planner

    @property
    def world(self) -> World:
        """The obstacles planned around."""
        return self._world

    @property
    def options(self) -> FootstepPlannerOptions:
        """Limits, dimensions, costs and bounds."""
        return self._options

    @property
    def actions(self) -> ActionSet:
        """The tabulated action set."""
        return self._actions

    @property
    def progress_table(self) -> ProgressTable:
        """The heuristic's progress bounds (depend on the options only)."""
        return self._progress

    def plan(self, start: Stance, goal: Pose2D) -> PlanResult:
        """Footsteps from the ``start`` stance to a nominal stance centred on ``goal``.

        Never raises on bad input: NaN/inf or colliding start and goal end in
        INVALID_START / INVALID_GOAL, hopeless goals in UNREACHABLE, and the
        search ends within ``max_expansions`` and ``max_planning_time``.
        """
        started = time.perf_counter()
        rejection = self._reject(start, goal)
        if rejection is not None:
            return _failure(rejection[0], rejection[1], 0, started)
        if self._at_goal(start, goal):
            plan = FootstepPlan(start, goal, (), 0.0, 0, time.perf_counter() - started)
            return PlanResult(PlanOutcome.SUCCESS, "already standing at the goal", plan, 0,
                              plan.planning_time)
        bounds = Bounds.around([(start.body_pose.x, start.body_pose.y), (goal.x, goal.y)],
                               self._options.search_margin)
        roots = tuple(step for step in (start.left, start.right) if self._state_is_free(step))
        if not roots:
            return _failure(PlanOutcome.INVALID_START, "no room for a first step: the body "
                            "over either start foot would collide", 0, started)
        if not may_reach(self._world, self._reachability_query(roots, goal, bounds)):
            return _failure(PlanOutcome.UNREACHABLE, "the goal is walled off: no collision-free "
                            f"corridor for the body on a {CELL_SIZE} m grid", 0, started)
        search = _Search(self, goal, bounds, started)
        return search.run(start, roots)

    def plan_from_within_margins(self, start: Stance, goal: Pose2D) -> tuple[PlanResult, str]:
        """:meth:`plan`; when the start stance collides (a walk stopped against the door
        frame leaves the robot inside the safety margins), plan once more with zero body and
        foot margins, so the robot can step away from where it already stands.

        Returns the result and, when the margins were dropped, why (else "").
        """
        result = self.plan(start, goal)
        if result.outcome is not PlanOutcome.INVALID_START or "collides" not in result.reason:
            return result, ""
        if self._options.body_margin == 0.0 and self._options.foot_margin == 0.0:
            return result, ""
        tight = FootstepPlanner(self._world, replace(self._options, body_margin=0.0, foot_margin=0.0))
        return tight.plan(start, goal), result.reason

    def _reject(self, start: Stance, goal: Pose2D) -> tuple[PlanOutcome, str] | None:
        """Why the request cannot be planned at all, or None."""
        if not start.is_finite():
            return PlanOutcome.INVALID_START, f"start stance is not finite: {start}"
        if not goal.is_finite():
            return PlanOutcome.INVALID_GOAL, f"goal pose is not finite: {goal}"
        start_collision = self._checker.stance_collision(start)
        if start_collision is not None:
            return PlanOutcome.INVALID_START, f"start stance collides: {start_collision}"
        goal_stance = Stance.nominal(goal, self._options.nominal_foot_separation)
        goal_collision = self._checker.stance_collision(goal_stance)
        if goal_collision is not None:
            return PlanOutcome.INVALID_GOAL, f"goal stance collides: {goal_collision}"
        return None

    def _at_goal(self, start: Stance, goal: Pose2D) -> bool:
        """The start is already the nominal stance at the goal (within the tolerances)."""
        nominal = Stance.nominal(start.body_pose, self._options.nominal_foot_separation)
        tolerance = self._options.goal_position_tolerance
        return (is_goal_centre(start.body_pose, goal, self._options)
                and start.left.pose.distance_to(nominal.left.pose) <= tolerance
                and start.right.pose.distance_to(nominal.right.pose) <= tolerance
                and start.left.pose.yaw_difference(start.right.pose)
                <= self._options.goal_yaw_tolerance)

    def _state_is_free(self, support: Footstep) -> bool:
        """The body over ``support`` (at its stance centre c(F)) is collision-free."""
        return not self._checker.body_collides(
            support.stance_centre(self._options.nominal_foot_separation))

    def _reachability_query(self, roots: tuple[Footstep, ...], goal: Pose2D,
                            bounds: Bounds) -> ReachabilityQuery:
        """The body-corridor question matching this search (see :mod:`reachability`)."""
        options = self._options
        separation = options.nominal_foot_separation
        grow = separation / 2.0 + CELL_SIZE
        centres = tuple((c.x, c.y) for c in (root.stance_centre(separation) for root in roots))
        return ReachabilityQuery(
            bounds=Bounds(bounds.x_min - grow, bounds.x_max + grow, bounds.y_min - grow,
                          bounds.y_max + grow),
            seeds=centres, goal=(goal.x, goal.y), goal_radius=options.goal_position_tolerance,
            body_radius=min(options.body_half_width, options.body_half_depth) + options.body_margin,
            hop=self._actions.max_body_hop)


def plan_footsteps(start: Stance, goal: Pose2D, world: World,
                   options: FootstepPlannerOptions | None = None) -> PlanResult:
    """One-shot :meth:`FootstepPlanner.plan`."""
    return FootstepPlanner(world, options).plan(start, goal)


def _failure(outcome: PlanOutcome, reason: str, expansions: int, started: float) -> PlanResult:
    """A failed :class:`PlanResult` timed from ``started``."""
    return PlanResult(outcome, reason, None, expansions, time.perf_counter() - started)


@dataclass(frozen=True)
class _ClosedSetGrid:
    """Integer keys of states: cell of the sole centre, yaw bin, foot.

    key = ((ix * rows + iy) * yaw_bins + iyaw) * 2 + (1 for a left foot).
    """

    x0: float
    y0: float
    rows: int
    resolution: float
    yaw_bins: int

    @classmethod
    def over(cls, bounds: Bounds, options: FootstepPlannerOptions) -> _ClosedSetGrid:
        rows = math.ceil((bounds.y_max - bounds.y_min) / options.grid_resolution) + 1
        yaw_bins = max(1, round(2.0 * math.pi / options.yaw_resolution))
        return cls(bounds.x_min, bounds.y_min, rows, options.grid_resolution, yaw_bins)

    def keys(self, x: np.ndarray, y: np.ndarray, yaw: np.ndarray, left: bool) -> list[int]:
        """Keys of several soles of the same foot."""
        column = np.floor((x - self.x0) / self.resolution).astype(np.int64)
        row = np.floor((y - self.y0) / self.resolution).astype(np.int64)
        bins = np.floor((yaw + math.pi) * (self.yaw_bins / (2.0 * math.pi)))
        yaw_bin = bins.astype(np.int64) % self.yaw_bins  # the bins wrap: no need to wrap yaw
        return (((column * self.rows + row) * self.yaw_bins + yaw_bin) * 2 + int(left)).tolist()


class _Search:
    """One A* run: node arrays, open heap, closed set (internal, single use)."""

    def __init__(self, planner: FootstepPlanner, goal: Pose2D, bounds: Bounds,
                 started: float) -> None:
        options = planner.options
        self._options = options
        self._tables = planner.actions.tables
        self._checker = FootprintChecker(planner.world, options)
        self._world = planner.world
        self._reach = planner.actions.body_reach
        self._goal = goal
        self._bounds = bounds
        self._grid = _ClosedSetGrid.over(bounds, options)
        self._heuristic = FootstepHeuristic(goal, options, planner.progress_table,
                                            planner.actions.max_turn)
        self._started = started
        self._deadline = started + options.max_planning_time
        self._half_separation = options.nominal_foot_separation / 2.0
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
        return self._heuristic.estimate_one(root.stance_centre(separation))

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

    def _snapping_steps(self, last: Footstep) -> tuple[Footstep, ...]:
        """Steps from the search's final stance (within the goal tolerance) onto the goal's
        nominal stance. Feet alternate, so the foot that did not move last goes first; when
        it cannot reach its target from there (a sideways shift towards it), it first steps
        in place and the other foot leads. None when no sequence stays within the step
        limits and clear of obstacles."""
        options = self._options
        target = Stance.nominal(self._goal, options.nominal_foot_separation)
        if target.foot(last.foot) == last and target.foot(last.foot.other) == \
                last.nominal_partner(options.nominal_foot_separation):
            return ()
        if self._checker.stance_collision(target) is not None:
            return ()
        in_place = last.nominal_partner(options.nominal_foot_separation)
        for sequence in ((target.foot(last.foot.other), target.foot(last.foot)),
                         (in_place, target.foot(last.foot), target.foot(last.foot.other))):
            if self._walkable(last, sequence):
                return sequence
        return ()

    def _walkable(self, support: Footstep, sequence: tuple[Footstep, ...]) -> bool:
        for placed in sequence:
            if not is_reachable_step(support, placed, self._options) or self._checker.footstep_collides(placed):
                return False
            support = placed
        return True

    def _closing_step(self, index: int) -> Footstep:
        x, y, yaw, is_left = self._nodes[index]
        support = Footstep(x, y, yaw, Foot.LEFT if is_left else Foot.RIGHT)
        return support.nominal_partner(self._options.nominal_foot_separation)

    def _expand(self, index: int) -> None:
        """Push every valid child of node ``index`` that improves its cell's best cost."""
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
        if self._near_obstacles(points[-1, 0], points[-1, 1]):
            valid &= self._free_children(points[2 * count:3 * count], yaw + table.midpoint[:, 2],
                                         (foot_x, foot_y, foot_yaw), (centre_x, centre_y))
        keys = self._grid.keys(foot_x, foot_y, foot_yaw, not is_left)
        estimates = self._heuristic.estimate(centre_x, centre_y, foot_yaw).tolist()
        self._push_children(index, np.flatnonzero(valid).tolist(), keys, estimates, table,
                            (foot_x.tolist(), foot_y.tolist(), foot_yaw.tolist()))

    def _push_children(self, parent: int, candidates: list[int], keys: list[int],
                       estimates: list[float], table: ActionTable,
                       poses: tuple[list[float], list[float], list[float]]) -> None:
        """Record and push the children that are new or cheaper than their cell's best.

        This is :meth:`_add` inlined over the children: it is the planner's
        innermost loop.
        """
        best, cost_so_far, step_costs = self._best, self._costs[parent], table.step_costs
        is_left = table.swing_foot is Foot.LEFT
        nodes, node_keys, parents, costs = self._nodes, self._keys, self._parents, self._costs
        heap, weight, push = self._open, self._options.heuristic_weight, heapq.heappush
        for child in candidates:
            key = keys[child]
            cost = cost_so_far + step_costs[child]
            if cost >= best.get(key, math.inf) - _COST_EPSILON:
                continue
            best[key] = cost
            estimate = estimates[child]
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

    def _free_children(self, midpoints: np.ndarray, midpoint_yaw: np.ndarray,
                       soles: tuple[np.ndarray, np.ndarray, np.ndarray],
                       centres: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
        """Children whose sole, double-stance body and single-support body are all free."""
        count = len(midpoints)
        bodies = (np.concatenate((midpoints[:, 0], centres[0])),
                  np.concatenate((midpoints[:, 1], centres[1])),
                  np.concatenate((midpoint_yaw, soles[2])))
        sole_hits, body_hits = self._checker.soles_and_bodies_collide(soles, bodies)
        return ~sole_hits & ~body_hits[:count] & ~body_hits[count:]

    def _success(self, start: Stance, index: int, expansions: int) -> PlanResult:
        steps = (*self._path(index), self._closing_step(index))
        snap = self._snapping_steps(steps[-1]) if self._options.snap_to_goal else ()
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
        return _failure(outcome, reason, expansions, self._started)
