"""Peer benchmark: the project's SQP and CHOMP beside tesseract's TrajOpt, on the same problems.

    python -m door_evaluation.trajopt.benchmark_peers [--repeats 3]

Two 7-DOF TALOS arm problems (:mod:`door_evaluation.trajopt.peer_problems`: T = 100, smoothness cost,
joint limits, a 6-D reach goal; a door arc of 240 pose equalities), one stationary initial
guess, one Pinocchio scorer for every solution. Each solver is timed from problem set-up
to solution (TrajOpt constructs its problem, ours build their solver), the minimum of
``--repeats`` runs. Ratios are ours / TrajOpt: time (< 1: faster) and cost (< 1: cheaper).

TrajOpt is an optional extra (``tesseract-robotics``, not in requirements.txt); without it
the benchmark says how to install it and prints the project's rows alone.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from door_evaluation.trajopt.peer_problems import PeerProblem, Score, peer_problems, score, trajectory_problem
from door_evaluation.trajopt.tesseract_peer import INSTALL_COMMAND, TrajOptPeer, tesseract_available
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_trajopt.chomp import ChompOptions, ChompSolver
from door_trajopt.sqp import ConstraintHandling, SqpOptions, SqpSolver

__all__ = ["main", "run"]

TOLERANCE = 1e-5  # m / rad: every solver's constraint tolerance (the motion library's)
MAX_ITERATIONS = 300
PAPER_SECONDS = 10.1  # [Banerjee 2015] Sec. V: one TrajOpt plan of the pull door
TRAJOPT = "tesseract TrajOpt (OSQP)"


@dataclass(frozen=True)
class Row:
    problem: str
    solver: str
    seconds: float
    score: Score

    @property
    def feasible(self) -> bool:
        return max(self.score.position_error, self.score.rotation_error, self.score.limit_violation) <= 10 * TOLERANCE


def _project_solvers(peer: PeerProblem) -> dict[str, Callable[[], np.ndarray]]:
    problem, guess = trajectory_problem(peer), peer.stationary_guess()

    def sqp(handling: ConstraintHandling) -> Callable[[], np.ndarray]:
        options = SqpOptions(constraint_handling=handling, max_iterations=MAX_ITERATIONS,
                             constraint_tolerance=TOLERANCE, cost_tolerance=1e-6)
        return lambda: SqpSolver(problem, options).solve(guess).trajectory

    chomp_options = ChompOptions(max_iterations=MAX_ITERATIONS, constraint_tolerance=TOLERANCE, cost_tolerance=1e-6)
    return {"project SQP (hard)": sqp(ConstraintHandling.HARD),
            "project SQP (l1 penalty)": sqp(ConstraintHandling.L1_PENALTY),
            "project CHOMP": lambda: ChompSolver(problem, chomp_options).solve(guess).trajectory}


def _timed(run: Callable[[], np.ndarray], repeats: int) -> tuple[float, np.ndarray]:
    """The fastest of ``repeats`` runs (at least one) and the last run's trajectory."""
    started = time.perf_counter()
    trajectory = run()
    best = time.perf_counter() - started
    for _ in range(repeats - 1):
        started = time.perf_counter()
        trajectory = run()
        best = min(best, time.perf_counter() - started)
    return best, trajectory


def _trajopt(peer: PeerProblem, repeats: int) -> Row:
    runs = [TrajOptPeer(peer, TOLERANCE, MAX_ITERATIONS).solve() for _ in range(repeats)]
    fastest = min(runs, key=lambda run: run.seconds)
    return Row(peer.name, TRAJOPT, fastest.seconds, score(peer, fastest.trajectory))


def run(repeats: int, with_peer: bool) -> list[Row]:
    rows = []
    for peer in peer_problems(RobotKinematics(load_profile("talos"))):
        if with_peer:
            rows.append(_trajopt(peer, repeats))
        for name, solver in _project_solvers(peer).items():
            seconds, trajectory = _timed(solver, repeats)
            rows.append(Row(peer.name, name, seconds, score(peer, trajectory)))
    return rows


def format_rows(rows: list[Row]) -> str:
    lines = ["| problem | solver | time | time / TrajOpt | cost | cost / TrajOpt | position error | rotation error "
             "| feasible |", "|---|---|---|---|---|---|---|---|---|"]
    peers = {row.problem: row for row in rows if row.solver == TRAJOPT}
    for row in rows:
        peer = peers.get(row.problem)
        time_ratio = f"{row.seconds / peer.seconds:.2f}×" if peer else "—"
        cost_ratio = f"{row.score.cost / peer.score.cost:.3f}" if peer else "—"
        lines.append(f"| {row.problem} | {row.solver} | {row.seconds * 1e3:.0f} ms | {time_ratio} | "
                     f"{row.score.cost:.5f} | {cost_ratio} | {row.score.position_error:.1e} m | "
                     f"{row.score.rotation_error:.1e} rad | {'yes' if row.feasible else 'NO'} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="runs per solver; the fastest is reported")
    args = parser.parse_args(argv)
    with_peer = tesseract_available()
    if not with_peer:
        print(f"tesseract's TrajOpt is not installed (an optional extra): {INSTALL_COMMAND}\n"
              "skipping the peer; the project's solvers alone:")
    print(format_rows(run(args.repeats, with_peer)))
    print(f"paper figure: {PAPER_SECONDS} s for one TrajOpt plan ([Banerjee 2015] Sec. V); constraint tolerance "
          f"{TOLERANCE:g} for every solver, feasible = every pose and limit within {10 * TOLERANCE:g}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
