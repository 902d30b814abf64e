"""Footstep planner benchmark: ``python -m door_evaluation.footsteps.benchmark [--repeats N] [--grid coarse]``.

Sweeps the full ranges (:mod:`~door_evaluation.footsteps.benchmark_cases`): every approach to the
stand pose (start 1.0-4.0 m from the door plane, +-0.6 m aside, +-0.6 rad turned; push and
pull, left and right hinge, doors 0.80-1.00 m) and every leg of every passage (push and
pull, same doors), planned as the node plans them: the robot profile's walking limits, the
node's default parameters. ``--shrink 0.7`` plans with the stride and turn limits 30 %
shorter (what the physical walker may achieve).

Each row is one family of searches: how many, how many succeeded, the median and the
largest planning time (each case's time is the median of its repeats) against the 50 ms
target (DESIGN: every footstep leg and the 4 m approach <= 50 ms), the same in CPU time
(what the wall time would be on a quiet machine: this one is shared, and the load average
is printed), and the largest number of expansions against the deterministic budget. The seed paper (WPI-CMU, DRC Finals)
gives no footstep planning time, only 10-40 s for the whole planning pipeline; there is
no peer planner in the project.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from dataclasses import dataclass, replace

from door_contract.parameters import validate_all
from door_evaluation.footsteps.benchmark_cases import COARSE, WIDTHS, PlanningCase, approach_cases, passage_cases
from door_robot.profile import load_profile
from footstep_planner.astar import FootstepPlanner
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.parameters import PLANNER_PARAMETERS
from footstep_planner.robot_limits import options_for_walking
from footstep_planner.world import World

__all__ = ["PAPER_FIGURE", "main"]

PAPER_FIGURE = "n/a (plan 10-40 s)"
PEER_FIGURE = "n/a"
TARGET_SECONDS = 0.050


@dataclass(frozen=True)
class Timing:
    """One case's result: the median wall time of its repeats and the search's figures."""

    case: PlanningCase
    seconds: float
    cpu_seconds: float
    expansions: int
    succeeded: bool


@dataclass(frozen=True)
class FamilyRow:
    """The figures of one family of cases."""

    family: str
    cases: int
    successes: int
    median_seconds: float
    max_seconds: float
    median_cpu_seconds: float
    max_cpu_seconds: float
    max_expansions: int
    slowest: str


def node_options(profile: str = "talos", shrink: float = 1.0) -> FootstepPlannerOptions:
    """The node's options with its default parameters; stride and turn scaled by ``shrink``."""
    defaults = validate_all(PLANNER_PARAMETERS, {})
    walking = load_profile(profile).walking
    walking = replace(walking, max_stride=walking.max_stride * shrink, max_turn=walking.max_turn * shrink)
    return options_for_walking(walking, defaults["heuristic_weight"], defaults["max_expansions"],
                               defaults["max_planning_time"])


def time_cases(cases: list[PlanningCase], repeats: int) -> list[Timing]:
    """Plan every case ``repeats`` times, with one planner per set of options (its tables are
    built once, as in the node)."""
    planners: dict[FootstepPlannerOptions, FootstepPlanner] = {}
    timings = []
    for case in cases:
        if case.options not in planners:
            planners[case.options] = FootstepPlanner(World(), case.options)
        planner = planners[case.options]
        planner.progress_table_within(case.leg.pruning.yaw_window)  # built once per window, not timed
        seconds, cpu_seconds, result = [], [], None
        for _ in range(repeats):
            started, started_cpu = time.perf_counter(), time.process_time()
            result = case.plan(planner)
            seconds.append(time.perf_counter() - started)
            cpu_seconds.append(time.process_time() - started_cpu)
        if result is None:
            raise ValueError(f"repeats must be at least 1, got {repeats}")
        timings.append(Timing(case, statistics.median(seconds), statistics.median(cpu_seconds),
                              result.expansions, result.succeeded))
    return timings


def family_rows(timings: list[Timing]) -> list[FamilyRow]:
    """One row per family, in the order the families first appear."""
    families: dict[str, list[Timing]] = {}
    for timing in timings:
        families.setdefault(timing.case.family, []).append(timing)
    rows = []
    for family, members in families.items():
        seconds, cpu = [m.seconds for m in members], [m.cpu_seconds for m in members]
        slowest = max(members, key=lambda m: m.seconds)
        rows.append(FamilyRow(family, len(members), sum(m.succeeded for m in members),
                              statistics.median(seconds), max(seconds), statistics.median(cpu), max(cpu),
                              max(m.expansions for m in members), slowest.case.label))
    return rows


def format_table(rows: list[FamilyRow], budget: int) -> str:
    """The rows as a fixed-width table, then the slowest case of each family."""
    header = (f"{'family':<52} {'paper':<19} {'peer':<5} {'cases':>5} {'ok':>5} {'median':>9} "
              f"{'max':>9} {'max/target':>10} {'cpu median':>10} {'cpu max':>9} {'expansions':>10}")
    lines = [header, "-" * len(header)]
    for row in rows:
        lines.append(f"{row.family:<52} {PAPER_FIGURE:<19} {PEER_FIGURE:<5} {row.cases:>5d} "
                     f"{row.successes:>5d} {_ms(row.median_seconds)} {_ms(row.max_seconds)} "
                     f"{row.max_seconds / TARGET_SECONDS:>10.2f} {_ms(row.median_cpu_seconds):>10} "
                     f"{_ms(row.max_cpu_seconds)} {row.max_expansions:>10d}")
    lines.append(f"target <= {TARGET_SECONDS * 1e3:.0f} ms per search; expansion budget {budget} "
                 "(deterministic); times are the median of each case's repeats; load average "
                 f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    lines += [f"slowest {row.family}: {row.slowest}" for row in rows]
    return "\n".join(lines)


def _ms(seconds: float) -> str:
    return f"{seconds * 1e3:>6.1f} ms"


def main(argv: list[str] | None = None) -> int:
    """Print the benchmark table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="runs per case")
    parser.add_argument("--grid", choices=("full", "coarse"), default="full",
                        help="coarse: the corners of the ranges only")
    parser.add_argument("--profile", default="talos", help="robot profile (params/robot_<name>.yaml)")
    parser.add_argument("--shrink", type=float, default=1.0, help="scale the stride and turn limits")
    arguments = parser.parse_args(argv)
    options = node_options(arguments.profile, arguments.shrink)
    grid = COARSE if arguments.grid == "coarse" else None
    widths = COARSE["widths"] if grid else WIDTHS
    cases = approach_cases(options, grid=grid) + passage_cases(options, widths=widths)
    started = time.perf_counter()
    timings = time_cases(cases, max(1, arguments.repeats))
    print(format_table(family_rows(timings), options.max_expansions))
    print(f"{len(cases)} searches x {arguments.repeats} in {time.perf_counter() - started:.1f} s "
          f"({arguments.profile}, stride {options.max_stride:.3f} m, turn {options.max_turn:.3f} rad, "
          f"heuristic weight {options.heuristic_weight:g})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
