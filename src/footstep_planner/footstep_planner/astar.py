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
requests at once.

Budgets.  ``max_expansions`` bounds every search deterministically: the same
request gives the same plan (or the same EXPANSION_LIMIT) on a quiet or a loaded
machine.  ``max_planning_time`` is only a safety net far above normal use.  A
repeated request (``attempt`` > 0) searches with a larger budget, a greedier
weight and a wider region (:mod:`~footstep_planner.attempts`).  A leg may also
prune the states it can never need (:mod:`~footstep_planner.pruning`: e.g.
sideways along the centre line of a narrow doorway), which makes it a
near-straight search.
"""

from __future__ import annotations

import copy
import math
import time
from dataclasses import replace

from door_contract.vocabulary import Foot
from footstep_planner.actions import ActionSet
from footstep_planner.attempts import options_for_attempt
from footstep_planner.footprint import FootprintChecker
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.geometry import Bounds
from footstep_planner.heuristic import is_goal_centre
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import FootstepPlan, InputProblem, PlanOutcome, PlanResult, failed
from footstep_planner.progress import ProgressTable
from footstep_planner.pruning import LegPruning
from footstep_planner.reachability import CELL_SIZE, ReachabilityQuery, may_reach
from footstep_planner.search import Search, SearchRequest
from footstep_planner.world import World

__all__ = ["FootstepPlanner", "plan_footsteps"]


class FootstepPlanner:
    """Plans footsteps in one world with one set of options (both fixed at construction)."""

    def __init__(self, world: World, options: FootstepPlannerOptions | None = None) -> None:
        self._world = world
        self._options = options if options is not None else FootstepPlannerOptions()
        self._actions = ActionSet.from_options(self._options)
        self._checker = FootprintChecker(world, self._options)
        self._progress = {math.pi: self._build_progress(math.pi)}

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
        return self._progress[math.pi]

    def progress_table_within(self, yaw_window: float) -> ProgressTable:
        """The progress bounds of searches that keep their headings within ``yaw_window``
        of the goal's (built on first use, tens of ms, then kept: legs reuse a few windows)."""
        table = self._progress.get(yaw_window)
        if table is None:
            table = self._progress[yaw_window] = self._build_progress(yaw_window)
        return table

    def _build_progress(self, yaw_window: float) -> ProgressTable:
        return ProgressTable.build(self._actions.step_effects, self._actions.max_turn,
                                   self._options.goal_yaw_tolerance, yaw_window)

    def plan(self, start: Stance, goal: Pose2D, pruning: LegPruning = LegPruning(),
             attempt: int = 0, first_foot: Foot | None = None) -> PlanResult:
        """Footsteps from the ``start`` stance to a nominal stance centred on ``goal``.

        Never raises on bad input: NaN/inf or colliding start and goal end in
        INVALID_START / INVALID_GOAL, hopeless goals in UNREACHABLE, and the
        search ends within ``max_expansions`` and ``max_planning_time``.
        ``pruning`` drops the states this leg never needs; ``attempt`` (0 = first
        try) selects the search settings of that repeat
        (:func:`~footstep_planner.attempts.options_for_attempt`; it raises
        :class:`FootstepPlannerError` when out of range). ``first_foot`` is the foot that must
        step first (None: whichever makes the cheaper plan).
        """
        started = time.perf_counter()
        search_options = options_for_attempt(self._options, attempt)
        rejection = self._reject(start, goal)
        if rejection is not None:
            outcome, problem, reason = rejection
            return failed(outcome, reason, 0, started, problem)
        if self._at_goal(start, goal):
            plan = FootstepPlan(start, goal, (self._squaring_step(start),), self._options.step_cost, 0,
                                time.perf_counter() - started)
            return PlanResult(PlanOutcome.SUCCESS, "already standing at the goal: one step squares the feet",
                              plan, 0, plan.planning_time)
        bounds = Bounds.around([(start.body_pose.x, start.body_pose.y), (goal.x, goal.y)],
                               search_options.search_margin)
        # the first step is taken from the other foot: that foot is the search's root
        supports = (start.left, start.right) if first_foot is None else (start.foot(first_foot.other),)
        roots = tuple(step for step in supports if self._state_is_free(step))
        if not roots:
            return failed(PlanOutcome.INVALID_START, "no room for a first step: the body "
                          "over either start foot would collide", 0, started, InputProblem.NO_FIRST_STEP)
        if not may_reach(self._world, self._reachability_query(roots, goal, bounds)):
            return failed(PlanOutcome.UNREACHABLE, "the goal is walled off: no collision-free "
                            f"corridor for the body on a {CELL_SIZE} m grid", 0, started)
        origin = (start.body_pose.x, start.body_pose.y)
        search = Search(self, SearchRequest(goal, bounds, search_options, pruning, origin), started)
        return search.run(start, roots)

    def plan_from_within_margins(self, start: Stance, goal: Pose2D, attempt: int = 0,
                                 pruning: LegPruning = LegPruning()) -> tuple[PlanResult, str]:
        """:meth:`plan`; when the start stance collides (a walk stopped against the door
        frame leaves the robot inside the safety margins), plan once more with zero body and
        foot margins, so the robot can step away from where it already stands.

        Returns the result and, when the margins were dropped, why (else "").
        """
        result = self.plan(start, goal, pruning, attempt=attempt)
        tight = self.without_margins()
        if result.input_problem is not InputProblem.START_COLLIDES or tight is None:
            return result, ""
        return tight.plan(start, goal, pruning, attempt=attempt), result.reason

    def without_margins(self) -> FootstepPlanner | None:
        """This planner with zero body and foot margins (None when it has none to drop): what
        plans the first steps of a robot that already stands inside the margins."""
        if self._options.body_margin == 0.0 and self._options.foot_margin == 0.0:
            return None
        return FootstepPlanner(self._world, replace(self._options, body_margin=0.0, foot_margin=0.0))

    def _reject(self, start: Stance, goal: Pose2D) -> tuple[PlanOutcome, InputProblem, str] | None:
        """Why the request cannot be planned at all, or None."""
        if not start.is_finite():
            return PlanOutcome.INVALID_START, InputProblem.START_NOT_FINITE, f"start stance is not finite: {start}"
        if not goal.is_finite():
            return PlanOutcome.INVALID_GOAL, InputProblem.GOAL_NOT_FINITE, f"goal pose is not finite: {goal}"
        start_collision = self._checker.stance_collision(start)
        if start_collision is not None:
            return PlanOutcome.INVALID_START, InputProblem.START_COLLIDES, f"start stance collides: {start_collision}"
        goal_stance = Stance.nominal(goal, self._options.nominal_foot_separation)
        goal_collision = self._checker.stance_collision(goal_stance)
        if goal_collision is not None:
            return PlanOutcome.INVALID_GOAL, InputProblem.GOAL_COLLIDES, f"goal stance collides: {goal_collision}"
        return None

    def _at_goal(self, start: Stance, goal: Pose2D) -> bool:
        """The start is already the nominal stance at the goal (within the tolerances)."""
        tolerance = self._options.goal_position_tolerance
        return (is_goal_centre(start.body_pose, goal, self._options)
                and max(self._off_nominal(start)) <= tolerance
                and start.left.pose.yaw_difference(start.right.pose)
                <= self._options.goal_yaw_tolerance)

    def _off_nominal(self, start: Stance) -> tuple[float, float]:
        """How far the left and the right sole stand from the nominal stance at the start's
        body pose (m)."""
        nominal = Stance.nominal(start.body_pose, self._options.nominal_foot_separation)
        return start.left.pose.distance_to(nominal.left.pose), start.right.pose.distance_to(nominal.right.pose)

    def _squaring_step(self, start: Stance) -> Footstep:
        """The one step of a robot already at its goal: the foot farther from the nominal stance
        placed beside the other (in place when that would collide). Never no step: a walk that
        was judged failed (a sole 7.9 cm off its plan, the base within the goal's tolerance) was
        repeated as an empty plan, which proposes nothing, and the FSM waited for a proposal
        until its planning timeout, three repeats in a row."""
        left_off, right_off = self._off_nominal(start)
        kept, moved = (start.right, start.left) if left_off > right_off else (start.left, start.right)
        squared = kept.nominal_partner(self._options.nominal_foot_separation)
        return moved if self._checker.footstep_collides(squared) else squared

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
            body_radius=min(options.body_half_width, options.body_half_depth - abs(options.body_offset))
            + options.body_margin,
            hop=self._actions.max_body_hop)


def plan_footsteps(start: Stance, goal: Pose2D, world: World,
                   options: FootstepPlannerOptions | None = None) -> PlanResult:
    """One-shot :meth:`FootstepPlanner.plan`."""
    return FootstepPlanner(world, options).plan(start, goal)


