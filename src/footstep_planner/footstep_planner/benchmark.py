"""Footstep planner benchmark: ``python -m footstep_planner.benchmark [--repeats N]``.

Scenarios (TALOS defaults, DRC-sized door in a wall, robot facing the door):

1. *approach*: 4 m walk to the stand pose for opening a push door (target <= 50 ms);
2. *approach, offset*: the same with the start 1.2 m to the side (a harder search);
3. *door passage*: through a push door open at 90 degrees, from 1.5 m in front to
   1 m beyond the door plane.

Each runs with A* (w = 1) and weighted A* (w = 2); the table gives the median
planning time over the repeats, the expansions and the steps.  The seed paper
(WPI-CMU, DRC Finals) gives no footstep planning time, only 10-40 s for the
whole planning pipeline, so its column reads "n/a (plan 10-40 s)".
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from dataclasses import dataclass

from footstep_planner.astar import FootstepPlanner
from footstep_planner.door import DoorGeometry, DoorOpening, HingeSide
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.goals import stand_pose_for_opening, through_door_pose
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import PlanResult
from footstep_planner.world import World

PAPER_FIGURE = "n/a (plan 10-40 s)"
TARGET_SECONDS = 0.050
WEIGHTS = (1.0, 2.0)


@dataclass(frozen=True)
class Scenario:
    """A planning request in a world."""

    name: str
    world: World
    start: Stance
    goal: Pose2D


@dataclass(frozen=True)
class Measurement:
    """Median time and the search statistics of one scenario with one heuristic weight."""

    scenario: str
    weight: float
    median_seconds: float
    expansions: int
    steps: int
    outcome: str


def scenarios(options: FootstepPlannerOptions) -> tuple[Scenario, ...]:
    """The benchmark scenarios, door in the wall x = 5 facing a robot walking along +x."""
    door = DoorGeometry(5.0, 0.435, math.pi, HingeSide.LEFT, DoorOpening.PUSH)
    closed_world = World.from_door(door)
    stand = stand_pose_for_opening(door, options)
    open_door = door.with_angle(math.pi / 2.0)
    separation = options.nominal_foot_separation
    return (
        Scenario("approach 4 m", closed_world,
                 Stance.nominal(Pose2D(stand.x - 4.0, stand.y, 0.0), separation), stand),
        Scenario("approach 4 m, 1.2 m offset", closed_world,
                 Stance.nominal(Pose2D(stand.x - 3.8, stand.y - 1.2, 0.0), separation), stand),
        Scenario("door passage (open 90 deg)", World.from_door(open_door),
                 Stance.nominal(Pose2D(5.0 - 1.5, 0.0, 0.0), separation),
                 through_door_pose(open_door)),
    )


def measure(scenario: Scenario, planner: FootstepPlanner, repeats: int) -> Measurement:
    """Plan ``repeats`` times; keep the median wall time and the last result's statistics."""
    times, result = [], None
    for _ in range(repeats):
        started = time.perf_counter()
        result = planner.plan(scenario.start, scenario.goal)
        times.append(time.perf_counter() - started)
    assert isinstance(result, PlanResult)
    steps = len(result.plan.steps) if result.plan is not None else 0
    return Measurement(scenario.name, planner.options.heuristic_weight, statistics.median(times),
                       result.expansions, steps, result.outcome.value)


def setup_seconds(options: FootstepPlannerOptions) -> float:
    """Time to build a planner (action set and heuristic tables); reuse it with ``with_world``."""
    started = time.perf_counter()
    FootstepPlanner(World(), options)
    return time.perf_counter() - started


def format_table(rows: list[Measurement]) -> str:
    """The results as a fixed-width text table."""
    header = (f"{'scenario':<30} {'planner':<16} {'paper':<20} {'ours (median)':>14} "
              f"{'ratio paper/ours':>17} {'ours/target':>12} {'expansions':>11} {'steps':>6} "
              f"outcome")
    lines = [header, "-" * len(header)]
    for row in rows:
        planner = "A*" if row.weight == 1.0 else f"weighted A* w={row.weight:g}"
        lines.append(
            f"{row.scenario:<30} {planner:<16} {PAPER_FIGURE:<20} "
            f"{row.median_seconds * 1e3:>11.1f} ms {'n/a':>17} "
            f"{row.median_seconds / TARGET_SECONDS:>12.2f} {row.expansions:>11d} "
            f"{row.steps:>6d} {row.outcome}")
    return "\n".join(lines)


def run(repeats: int) -> list[Measurement]:
    """Every scenario with every weight."""
    rows = []
    for weight in WEIGHTS:
        options = FootstepPlannerOptions(heuristic_weight=weight)
        base = FootstepPlanner(World(), options)
        for scenario in scenarios(options):
            rows.append(measure(scenario, base.with_world(scenario.world), repeats))
    return rows


def main(argv: list[str] | None = None) -> int:
    """Print the benchmark table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7, help="runs per measurement")
    arguments = parser.parse_args(argv)
    rows = run(max(1, arguments.repeats))
    print(format_table(rows))
    print(f"planner set-up (action set + heuristic table, once per options): "
          f"{setup_seconds(FootstepPlannerOptions()) * 1e3:.1f} ms; "
          f"target for the 4 m approach: <= {TARGET_SECONDS * 1e3:.0f} ms")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
