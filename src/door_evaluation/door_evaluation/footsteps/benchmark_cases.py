"""The footstep benchmark's cases: approaches from anywhere in the full ranges, and every
leg of every push and pull passage.

The scene is the simulation's: the door plane is x = 0 with the doorway centred on
y = 0, the robot starts at x = -distance facing +x turned by a yaw, shifted laterally
(issue #13's Monte-Carlo ranges: distance 1.0-4.0 m, lateral +-0.6 m, yaw +-0.6 rad,
width 0.80-1.00 m, push/pull x left/right hinge). Requests are built exactly as the node
builds them (:mod:`~footstep_planner.requests`), with the node's default parameters.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

from door_contract.vocabulary import DoorOpening, HingeSide, WalkGoal
from footstep_planner.astar import FootstepPlanner
from footstep_planner.door import DoorGeometry
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.legs import Leg
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import PlanResult
from footstep_planner.requests import GoalSettings, options_for_problem, walk_problem
from footstep_planner.world import World

__all__ = ["COARSE", "WIDTHS", "DoorCase", "PlanningCase", "approach_cases", "doors", "passage_cases"]

DISTANCES = (1.0, 2.0, 3.0, 4.0)
LATERALS = (-0.6, -0.3, 0.0, 0.3, 0.6)
YAWS = (-0.6, -0.3, 0.0, 0.3, 0.6)
APPROACH_WIDTHS = (0.80, 0.90, 1.00)
"""The approach barely depends on the width (the stand pose moves with the handle)."""
WIDTHS = (0.80, 0.85, 0.90, 0.95, 1.00)
COARSE = {"distances": (1.0, 4.0), "laterals": (-0.6, 0.6), "yaws": (-0.6, 0.6), "widths": (0.80, 1.00)}
"""A corner-only grid, for a quick run (tests)."""


@dataclass(frozen=True)
class DoorCase:
    """One door of the sweep."""

    opening: DoorOpening
    hinge: HingeSide
    width: float

    def geometry(self) -> DoorGeometry:
        """The door in the wall x = 0, doorway centred on y = 0, normal towards -x; the
        detector measures leaf = clear opening, as the node assumes."""
        hinge_y = self.width / 2.0 if self.hinge is HingeSide.LEFT else -self.width / 2.0
        return DoorGeometry(0.0, hinge_y, math.pi, self.hinge, self.opening, leaf_width=self.width,
                            clear_opening=self.width, handle_offset=0.07)

    @property
    def label(self) -> str:
        return f"{self.opening.value} {self.hinge.value} {self.width:.2f} m"


@dataclass(frozen=True)
class PlanningCase:
    """One search to time: a leg of a request, from where the previous leg ended."""

    family: str
    label: str
    world: World
    options: FootstepPlannerOptions
    start: Stance
    leg: Leg

    def plan(self, planner: FootstepPlanner) -> PlanResult:
        """This case's search with ``planner`` (built once per options, moved to this world)."""
        return planner.with_world(self.world).plan(self.start, self.leg.goal, self.leg.pruning)


def doors(widths: tuple[float, ...] = WIDTHS) -> Iterator[DoorCase]:
    """Every opening, hinge side and width."""
    for opening, hinge, width in itertools.product(DoorOpening, HingeSide, widths):
        yield DoorCase(opening, hinge, width)


def approach_cases(options: FootstepPlannerOptions, settings: GoalSettings = GoalSettings(),
                   grid: Mapping[str, tuple[float, ...]] | None = None) -> list[PlanningCase]:
    """Walks to the stand pose from every start of the grid, for every door."""
    grid = grid or {}
    cases = []
    for door in doors(grid.get("widths", APPROACH_WIDTHS)):
        geometry = door.geometry()
        for distance, lateral, yaw in itertools.product(grid.get("distances", DISTANCES),
                                                        grid.get("laterals", LATERALS), grid.get("yaws", YAWS)):
            start = Stance.nominal(Pose2D(-distance, lateral, yaw), options.nominal_foot_separation)
            problem = walk_problem(WalkGoal.STAND, geometry, start, options, settings)
            label = f"{door.label}, start {distance:.2f} m, {lateral:+.2f} m, {yaw:+.2f} rad"
            cases.append(PlanningCase(f"approach ({door.opening.value})", label, problem.world,
                                      options_for_problem(problem, WalkGoal.STAND, options), start,
                                      problem.legs[0]))
    return cases


def passage_cases(options: FootstepPlannerOptions, settings: GoalSettings = GoalSettings(),
                  widths: tuple[float, ...] = WIDTHS) -> list[PlanningCase]:
    """Every leg of the passage through every door, from the stand pose (where opening the
    door left the robot); each leg starts where the previous one's plan ended."""
    cases = []
    for door in doors(widths):
        geometry = door.geometry().with_angle(0.35 if door.opening is DoorOpening.PULL else 0.0)
        stand = walk_problem(WalkGoal.STAND, geometry, Stance.nominal(Pose2D(-3.0, 0.0, 0.0), 0.2),
                             options, settings).legs[0].goal
        start = Stance.nominal(stand, options.nominal_foot_separation)
        problem = walk_problem(WalkGoal.THROUGH, geometry, start, options, settings)
        leg_options = options_for_problem(problem, WalkGoal.THROUGH, options)
        leg_planner = FootstepPlanner(problem.world, leg_options)
        for leg in problem.legs:
            family = f"{door.opening.value} passage: {leg.name}"
            cases.append(PlanningCase(family, door.label, problem.world, leg_options, start, leg))
            result = leg_planner.plan(start, leg.goal, leg.pruning)
            if not result.succeeded or result.plan is None:
                break
            start = result.plan.final_stance
    return cases
