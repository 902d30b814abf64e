"""Benchmark of the backends on the [Zucker 2013]-sized door opening problem.

Run ``python -m door_evaluation.trajopt.benchmark_backends`` (``--help`` for options).
[Zucker 2013] (HUBO+, Sec. III-A) reports ~40 s for its constrained CHOMP with
``n = 104``, ``m = 9``, ``k = 181`` on a 2.5 GHz Core 2 Duo, dominated by the
dense ``181 x 181`` solve for ``Q``.  This prints, for constrained CHOMP, the
TrajOpt-style SQP (both constraint handlings) and scipy's SLSQP as a naive
dense baseline: wall time, cost, max violation, iterations and the ratio
paper time / our warm time.  Fast backends are timed as the median of
several warm runs (the solver object, hence ``A``'s factor / the OSQP set-up,
is built once, as a planner would) and cold (build + first solve); SLSQP is
run once.  Timings depend on the machine
load; set ``OPENBLAS_NUM_THREADS=1`` on a shared machine.
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Protocol

from scipy.optimize import Bounds, minimize

from door_evaluation.trajopt.toy_problems import BenchmarkCase, seed000_sized_case
from door_trajopt.chomp import ChompSolver
from door_trajopt.evaluation import PointValues, ProblemEvaluator, RunSummary, build_result
from door_trajopt.problem import FloatArray, TrajectoryProblem
from door_trajopt.result import OptimizationResult
from door_trajopt.sqp import ConstraintHandling, SqpOptions, SqpSolver

__all__ = ["main"]


class Solver(Protocol):
    """A backend object built once per problem (``ChompSolver``, ``SqpSolver``)."""

    def solve(self, initial_guess: FloatArray) -> OptimizationResult:
        """Optimise from an ``(n, m)`` guess."""
        ...


PAPER_OPTIMISATION_TIME_S = 40.0
"""[Zucker 2013] Sec. III-A: "Trajectory optimization takes approximately 40 s"."""

FEASIBILITY_TOLERANCE = 1e-6
"""Constraint threshold (rad, m) used to classify the SLSQP baseline."""


@dataclass(frozen=True)
class BenchmarkRow:
    """One backend's measured figures."""

    backend: str
    result: OptimizationResult
    seconds: float
    cold_seconds: float

    @property
    def paper_ratio(self) -> float:
        """Paper time divided by ours (> 1: faster than [Zucker 2013])."""
        return PAPER_OPTIMISATION_TIME_S / self.seconds


def timed_solver(
    build: Callable[[], Solver], guess: FloatArray, repeats: int
) -> tuple[OptimizationResult, float, float]:
    """Return the result, median warm solve time and cold (build + first solve) time."""
    started = time.perf_counter()
    solver = build()
    result = solver.solve(guess)
    cold = time.perf_counter() - started
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        result = solver.solve(guess)
        times.append(time.perf_counter() - started)
    return result, statistics.median(times), cold


def run_chomp(case: BenchmarkCase, repeats: int) -> BenchmarkRow:
    """Time constrained CHOMP ([Zucker 2013] eq. (5))."""
    result, warm, cold = timed_solver(
        lambda: ChompSolver(case.problem), case.initial_guess, repeats
    )
    return BenchmarkRow("constrained CHOMP", result, warm, cold)


def run_sqp(case: BenchmarkCase, repeats: int, handling: ConstraintHandling) -> BenchmarkRow:
    """Time the TrajOpt-style SQP with OSQP."""
    options = SqpOptions(constraint_handling=handling)
    result, warm, cold = timed_solver(
        lambda: SqpSolver(case.problem, options), case.initial_guess, repeats
    )
    return BenchmarkRow(f"SQP/OSQP ({handling.value})", result, warm, cold)


def slsqp_baseline(
    problem: TrajectoryProblem, guess: FloatArray, max_iterations: int
) -> OptimizationResult:
    """Run scipy's ``minimize(method='SLSQP')`` on the same objective/constraints (dense)."""
    evaluator = ProblemEvaluator.for_problem(problem)
    started = time.perf_counter()
    constraints = [
        {
            "type": "eq",
            "fun": lambda x: evaluator.equalities.values(problem.full_trajectory(x)),
            "jac": lambda x: evaluator.equalities.jacobian(problem.full_trajectory(x)).toarray(),
        }
    ]
    if evaluator.inequalities.size:
        constraints.append(
            {
                "type": "ineq",
                "fun": lambda x: -evaluator.inequalities.values(problem.full_trajectory(x)),
                "jac": lambda x: (
                    -evaluator.inequalities.jacobian(problem.full_trajectory(x)).toarray()
                ),
            }
        )
    solution = minimize(
        evaluator.objective.value,
        evaluator.clip_to_limits(problem.free_vector(guess)),
        jac=evaluator.objective.gradient,
        method="SLSQP",
        bounds=Bounds(evaluator.lower_bounds(), evaluator.upper_bounds()),
        constraints=constraints,
        options={"maxiter": max_iterations, "ftol": 1e-9},
    )
    values: PointValues = evaluator.values(evaluator.clip_to_limits(solution.x))
    summary = RunSummary(
        values, bool(solution.status != 9), int(solution.nit), started, solution.message
    )
    return build_result(evaluator, summary, FEASIBILITY_TOLERANCE)


def run_slsqp(case: BenchmarkCase, max_iterations: int) -> BenchmarkRow:
    """Time the naive dense baseline (run once)."""
    result = slsqp_baseline(case.problem, case.initial_guess, max_iterations)
    return BenchmarkRow("scipy SLSQP (naive)", result, result.solve_time_s, result.solve_time_s)


def format_rows(rows: Sequence[BenchmarkRow], reference_cost: float) -> str:
    """Format the figures as a fixed-width table."""
    header = (
        f"{'backend':<26}{'warm [ms]':>11}{'cold [ms]':>11}{'paper/warm':>12}{'cost':>12}"
        f"{'cost/ref-1':>12}{'max viol.':>11}{'iters':>7}  outcome"
    )
    lines = [header, "-" * len(header)]
    for row in rows:
        result = row.result
        gap = result.cost / reference_cost - 1.0
        lines.append(
            f"{row.backend:<26}{row.seconds * 1e3:>11.1f}{row.cold_seconds * 1e3:>11.1f}"
            f"{row.paper_ratio:>12.1f}{result.cost:>12.8f}{gap:>12.1e}"
            f"{result.max_violation:>11.1e}{result.iterations:>7}  {result.outcome.value}"
        )
    return "\n".join(lines)


def describe(case: BenchmarkCase) -> str:
    """Problem size line ([Zucker 2013]: n = 104, m = 9, k = 181)."""
    problem = case.problem
    rows = sum(c.size for c in problem.constraints)
    names = ", ".join(f"{c.name}={c.size}" for c in problem.constraints)
    return (
        f"problem {case.name}: n = {problem.n_free} free waypoints, m = {problem.n_dof} DOF, "
        f"k = {rows} constraints ({names})"
    )


def parse_arguments(argv: Sequence[str] | None) -> argparse.Namespace:
    """Command-line options."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7, help="timed runs per fast backend")
    parser.add_argument("--slsqp-max-iterations", type=int, default=1000)
    parser.add_argument(
        "--skip-slsqp", action="store_true", help="SLSQP needs minutes (~0.27 s per iteration)"
    )
    return parser.parse_args(argv)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the benchmark and print the table."""
    arguments = parse_arguments(argv)
    case = seed000_sized_case()
    print(describe(case))
    rows = [
        run_chomp(case, arguments.repeats),
        run_sqp(case, arguments.repeats, ConstraintHandling.HARD),
        run_sqp(case, arguments.repeats, ConstraintHandling.L1_PENALTY),
    ]
    if not arguments.skip_slsqp:
        print("running scipy SLSQP (dense, several minutes) ...", flush=True)
        rows.append(run_slsqp(case, arguments.slsqp_max_iterations))
    print(format_rows(rows, reference_cost=rows[0].result.cost))
    print(f"paper figure: {PAPER_OPTIMISATION_TIME_S:.0f} s ([Zucker 2013] Sec. III-A, 2010 Core 2 Duo)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
