"""The peer benchmark's problems: the project's constraints mean what the shared scorer
measures, both backends find the same optimum, and the benchmark runs without tesseract."""

import numpy as np
import pytest

from door_evaluation.trajopt import benchmark_peers
from door_evaluation.trajopt.peer_problems import (
    ARC_POSES,
    door_arc_problem,
    peer_problems,
    reach_problem,
    score,
    trajectory_problem,
)
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_trajopt.chomp import ChompOptions, ChompSolver
from door_trajopt.evaluation import ProblemEvaluator
from door_trajopt.sqp import SqpOptions, SqpSolver


@pytest.fixture(scope="module")
def kinematics():
    return RobotKinematics(load_profile("talos"))


def test_the_arm_problems_have_the_issues_sizes_and_no_torso(kinematics):
    reach, arc = peer_problems(kinematics)
    assert reach.chain.size == 7 and not any("torso" in name for name in reach.chain.joint_names)
    assert reach.n_waypoints == arc.n_waypoints == 100
    assert reach.equality_rows == 6 and arc.equality_rows == 6 * ARC_POSES == 240
    assert trajectory_problem(arc).n_variables == 99 * 7


def test_the_projects_pose_rows_are_what_the_scorer_measures(kinematics):
    """At a perturbed trajectory the worst position rows equal the scorer's position error,
    and the velocity smoothness (½ w Σ||Δq||², w = 2) is the scorer's cost, TrajOpt's Σ||Δq||²."""
    peer = door_arc_problem(kinematics)
    problem = trajectory_problem(peer)
    rng = np.random.default_rng(3)
    trajectory = peer.stationary_guess() + np.vstack([np.zeros((1, 7)), rng.normal(0.0, 0.05, (99, 7))])
    evaluator = ProblemEvaluator.for_problem(problem)
    values = evaluator.values(problem.free_vector(trajectory))
    rows = values.equality.reshape(-1, 6)
    measured = score(peer, trajectory)
    assert np.max(np.linalg.norm(rows[:, :3], axis=1)) == pytest.approx(measured.position_error, rel=1e-9)
    assert np.max(np.linalg.norm(rows[:, 3:], axis=1)) == pytest.approx(measured.rotation_error, rel=1e-6)
    assert values.cost == pytest.approx(measured.cost, rel=1e-12)
    assert measured.start_error == 0.0


def test_both_backends_reach_the_same_optimum_from_the_stationary_guess(kinematics):
    """CHOMP once put every limit its first long step crossed into its working set (405 rows)."""
    peer = reach_problem(kinematics)
    problem, guess = trajectory_problem(peer), peer.stationary_guess()
    sqp = SqpSolver(problem, SqpOptions(constraint_tolerance=1e-6, cost_tolerance=1e-8)).solve(guess)
    chomp = ChompSolver(problem, ChompOptions(constraint_tolerance=1e-6, cost_tolerance=1e-8)).solve(guess)
    scores = [score(peer, result.trajectory) for result in (sqp, chomp)]
    assert all(s.position_error < 1e-5 and s.rotation_error < 1e-5 and s.limit_violation == 0.0 for s in scores)
    assert scores[0].cost == pytest.approx(scores[1].cost, rel=1e-4)
    assert chomp.iterations < 20


def test_without_tesseract_the_benchmark_says_how_to_install_it(monkeypatch, capsys):
    monkeypatch.setattr(benchmark_peers, "tesseract_available", lambda: False)
    monkeypatch.setattr(benchmark_peers, "run", lambda repeats, with_peer: [] if not with_peer else None)
    assert benchmark_peers.main(["--repeats", "1"]) == 0
    printed = capsys.readouterr().out
    assert "pip install tesseract-robotics" in printed and "skipping the peer" in printed
