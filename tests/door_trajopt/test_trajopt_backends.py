"""Both backends on the door-arc problem: feasibility, agreement, limits, failures."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse as sp

from door_evaluation.trajopt.toy_problems import (
    DOOR_ARC_CHAIN,
    DOOR_ARC_LIMITS,
    BenchmarkCase,
    door_arc_case,
    seed000_sized_case,
)
from door_trajopt.chomp import ChompOptions, ChompSolver, solve_chomp
from door_trajopt.evaluation import ProblemEvaluator
from door_trajopt.problem import (
    Constraint,
    ConstraintKind,
    JointLimits,
    PostureCost,
    ResidualCost,
    TrajectoryProblem,
)
from door_trajopt.result import OptimizationResult, Outcome
from door_trajopt.sqp import ConstraintHandling, SqpOptions, SqpSolver, solve_sqp

Backend = Callable[[TrajectoryProblem, np.ndarray], OptimizationResult]


def sqp_l1(problem: TrajectoryProblem, guess: np.ndarray) -> OptimizationResult:
    """TrajOpt's slack formulation instead of the default hard constraints."""
    return solve_sqp(problem, guess, SqpOptions(constraint_handling=ConstraintHandling.L1_PENALTY))


BACKENDS: dict[str, Backend] = {"chomp": solve_chomp, "sqp": solve_sqp, "sqp_l1": sqp_l1}


def with_upper_limit(dof: int, value: float) -> JointLimits:
    """Door-arc limits with one upper limit lowered."""
    upper = DOOR_ARC_LIMITS.upper.copy()
    upper[dof] = value
    return JointLimits(DOOR_ARC_LIMITS.lower, upper)


@pytest.fixture(scope="module")
def door_arc() -> BenchmarkCase:
    return door_arc_case()


@pytest.fixture(scope="module")
def solutions(door_arc: BenchmarkCase) -> dict[str, OptimizationResult]:
    return {
        name: solve(door_arc.problem, door_arc.initial_guess) for name, solve in BACKENDS.items()
    }


@pytest.mark.parametrize("backend", BACKENDS)
def test_door_arc_solution_is_feasible_and_smoother_than_guess(
    backend: str, door_arc: BenchmarkCase, solutions: dict[str, OptimizationResult]
) -> None:
    result = solutions[backend]
    evaluator = ProblemEvaluator.for_problem(door_arc.problem)
    guess_cost = evaluator.objective.value(door_arc.problem.free_vector(door_arc.initial_guess))
    assert result.outcome is Outcome.SUCCESS, result.message
    assert result.max_violation <= 1e-6
    assert result.violated_constraint is None
    assert result.cost < guess_cost
    np.testing.assert_allclose(result.trajectory[0], door_arc.problem.start)
    assert result.trajectory[-1, 3] == pytest.approx(np.deg2rad(40.0), abs=1e-6)


def test_result_reports_recomputed_values(
    door_arc: BenchmarkCase, solutions: dict[str, OptimizationResult]
) -> None:
    evaluator = ProblemEvaluator.for_problem(door_arc.problem)
    result = solutions["chomp"]
    values = evaluator.values(door_arc.problem.free_vector(result.trajectory))
    assert result.cost == pytest.approx(values.cost)
    assert np.max(np.abs(values.equality)) <= 1e-6
    assert not result.trajectory.flags.writeable


@pytest.mark.parametrize("backend", ["sqp", "sqp_l1"])
def test_sqp_reaches_the_chomp_optimum_within_one_percent(
    backend: str, solutions: dict[str, OptimizationResult]
) -> None:
    """The colleague's plain SQP stalled 25 % above the optimum; this one must not."""
    reference = solutions["chomp"].cost
    assert solutions[backend].cost == pytest.approx(reference, rel=0.01)
    np.testing.assert_allclose(
        solutions[backend].trajectory, solutions["chomp"].trajectory, atol=1e-3
    )


@pytest.mark.parametrize("backend", BACKENDS)
def test_joint_limits_hold_when_active(backend: str) -> None:
    case = door_arc_case(limits=with_upper_limit(0, 1.5))
    result = BACKENDS[backend](case.problem, case.initial_guess)
    assert result.outcome is Outcome.SUCCESS, result.message
    assert result.max_violation <= 1e-6
    assert np.all(result.trajectory <= case.problem.limits.upper + 1e-9)
    assert np.all(result.trajectory >= case.problem.limits.lower - 1e-9)
    assert result.trajectory[:, 0].max() == pytest.approx(1.5, abs=1e-6)


def test_backends_agree_with_active_joint_limit() -> None:
    case = door_arc_case(limits=with_upper_limit(0, 1.5))
    chomp = solve_chomp(case.problem, case.initial_guess)
    sqp = solve_sqp(case.problem, case.initial_guess)
    assert sqp.cost == pytest.approx(chomp.cost, rel=0.01)


@pytest.mark.parametrize("backend", BACKENDS)
def test_nan_in_guess_is_invalid_input(backend: str, door_arc: BenchmarkCase) -> None:
    guess = door_arc.initial_guess.copy()
    guess[5, 2] = np.nan
    result = BACKENDS[backend](door_arc.problem, guess)
    assert result.outcome is Outcome.INVALID_INPUT
    assert "waypoint 5" in result.message
    assert result.iterations == 0


@pytest.mark.parametrize("backend", BACKENDS)
def test_wrong_shape_or_moved_start_is_invalid_input(backend: str, door_arc: BenchmarkCase) -> None:
    moved = door_arc.initial_guess.copy()
    moved[0, 0] += 0.1
    assert BACKENDS[backend](door_arc.problem, moved).outcome is Outcome.INVALID_INPUT
    short = door_arc.initial_guess[:-1]
    assert BACKENDS[backend](door_arc.problem, short).outcome is Outcome.INVALID_INPUT


@pytest.mark.parametrize("backend", BACKENDS)
def test_callback_returning_nan_is_invalid_input(backend: str, door_arc: BenchmarkCase) -> None:
    broken = Constraint(
        name="broken_sensor",
        kind=ConstraintKind.EQUALITY,
        size=1,
        value=lambda trajectory: np.array([np.nan]),
        jacobian=lambda trajectory: np.zeros((1, trajectory.size)),
    )
    problem = replace(door_arc.problem, constraints=(*door_arc.problem.constraints, broken))
    result = BACKENDS[backend](problem, door_arc.initial_guess)
    assert result.outcome is Outcome.INVALID_INPUT
    assert "broken_sensor" in result.message


@pytest.mark.parametrize("backend", BACKENDS)
def test_contradicting_constraints_are_infeasible_and_named(backend: str) -> None:
    """The hinge may not pass 0.5 rad but ``door_opening`` wants 40 deg."""
    case = door_arc_case(limits=with_upper_limit(3, 0.5))
    result = BACKENDS[backend](case.problem, case.initial_guess)
    assert result.outcome is Outcome.INFEASIBLE
    assert result.violated_constraint == "door_opening"
    assert result.max_violation == pytest.approx(np.deg2rad(40.0) - 0.5, abs=1e-6)
    assert np.all(result.trajectory[:, 3] <= 0.5 + 1e-12)


@pytest.mark.parametrize("backend", BACKENDS)
def test_inequality_constraint_is_respected(backend: str) -> None:
    """``g <= 0``: keep the wrist angle above 0.2 rad at every waypoint."""
    case = door_arc_case()
    n, m = case.problem.n_waypoints, case.problem.n_dof
    rows = np.arange(1, n)

    def value(trajectory: np.ndarray) -> np.ndarray:
        return 0.2 - trajectory[rows, 2]

    def jacobian(trajectory: np.ndarray) -> np.ndarray:
        matrix = np.zeros((rows.size, n * m))
        matrix[np.arange(rows.size), rows * m + 2] = -1.0
        return matrix

    wrist = Constraint("wrist_above", ConstraintKind.INEQUALITY, rows.size, value, jacobian)
    problem = replace(case.problem, constraints=(*case.problem.constraints, wrist))
    result = BACKENDS[backend](problem, case.initial_guess)
    assert result.outcome is Outcome.SUCCESS, result.message
    assert result.trajectory[1:, 2].min() >= 0.2 - 1e-6
    assert result.trajectory[1:, 2].min() == pytest.approx(0.2, abs=1e-5)


def test_posture_cost_pulls_towards_nominal(solutions: dict[str, OptimizationResult]) -> None:
    nominal = solutions["chomp"].trajectory[-1] + np.array([0.0, 0.0, 0.3, 0.0])
    posture = PostureCost(nominal, np.array([0.0, 0.0, 0.05, 0.0]))
    case = door_arc_case(posture=posture)
    chomp = solve_chomp(case.problem, case.initial_guess)
    sqp = solve_sqp(case.problem, case.initial_guess)
    assert chomp.outcome is Outcome.SUCCESS and sqp.outcome is Outcome.SUCCESS
    assert sqp.cost == pytest.approx(chomp.cost, rel=0.01)
    assert chomp.trajectory[:, 2].mean() > solutions["chomp"].trajectory[:, 2].mean()


def test_solvers_are_reusable_across_guesses(door_arc: BenchmarkCase) -> None:
    """Factorisation / OSQP set-up happen once; a second guess still converges."""
    other = door_arc.initial_guess.copy()
    other[1:-1, :3] += 0.05 * np.sin(np.linspace(0, np.pi, other.shape[0] - 2))[:, None]
    chomp = ChompSolver(door_arc.problem)
    sqp = SqpSolver(door_arc.problem)
    results = [
        solver.solve(guess) for solver in (chomp, sqp) for guess in (door_arc.initial_guess, other)
    ]
    assert all(r.outcome is Outcome.SUCCESS for r in results)
    costs = [r.cost for r in results]
    assert max(costs) == pytest.approx(min(costs), rel=0.01)


def test_iteration_cap_is_reported() -> None:
    case = door_arc_case()
    result = ChompSolver(case.problem, ChompOptions(max_iterations=2)).solve(case.initial_guess)
    assert result.outcome is Outcome.ITERATION_LIMIT
    assert result.iterations == 2
    result = SqpSolver(case.problem, SqpOptions(max_iterations=2)).solve(case.initial_guess)
    assert result.outcome is Outcome.ITERATION_LIMIT


def elbow_target_cost(case: BenchmarkCase, target: np.ndarray, weight: float) -> ResidualCost:
    """``Q3``-style Cartesian error of the elbow point at the last waypoint."""
    n, m = case.problem.n_waypoints, case.problem.n_dof
    length = DOOR_ARC_CHAIN.link_lengths[0]

    def residual(trajectory: np.ndarray) -> np.ndarray:
        angle = trajectory[-1, 0]
        return length * np.array([np.cos(angle), np.sin(angle)]) - target

    def jacobian(trajectory: np.ndarray) -> np.ndarray:
        angle = trajectory[-1, 0]
        matrix = np.zeros((2, n * m))
        matrix[:, (n - 1) * m] = length * np.array([-np.sin(angle), np.cos(angle)])
        return matrix

    pattern = sp.csr_matrix(jacobian(case.initial_guess) != 0.0)
    return ResidualCost("elbow_target", 2, residual, jacobian, weight, pattern)


def test_residual_pose_cost_is_minimised_consistently(
    solutions: dict[str, OptimizationResult],
) -> None:
    case = door_arc_case()
    target = 0.45 * np.array([np.cos(1.2), np.sin(1.2)])
    cost = elbow_target_cost(case, target, weight=0.05)
    problem = replace(case.problem, residual_costs=(cost,))
    chomp = solve_chomp(problem, case.initial_guess)
    sqp = solve_sqp(problem, case.initial_guess)
    assert chomp.outcome is Outcome.SUCCESS and sqp.outcome is Outcome.SUCCESS
    assert sqp.cost == pytest.approx(chomp.cost, rel=0.01)
    before = np.linalg.norm(cost.residual(solutions["chomp"].trajectory))
    assert np.linalg.norm(cost.residual(chomp.trajectory)) < before


def test_trajopt_like_plain_sqp_stalls_and_says_so(
    door_arc: BenchmarkCase, solutions: dict[str, OptimizationResult]
) -> None:
    """The colleague's stall: fixed mu = 10, 0.1 rad box, no second-order correction.

    Every tangential step along the door arc raises ``mu |h|`` more than it
    lowers the cost, the trust region collapses and the run ends far above
    the optimum.  The result must say so instead of posing as converged.
    """
    plain = SqpOptions(
        constraint_handling=ConstraintHandling.L1_PENALTY,
        initial_penalty=10.0,
        initial_trust_radius=0.1,
        second_order_correction=False,
    )
    result = solve_sqp(door_arc.problem, door_arc.initial_guess, plain)
    assert result.cost > 1.25 * solutions["chomp"].cost
    assert "trust region collapsed" in result.message


def test_seed000_sized_problem_with_pins_on_joint_limits() -> None:
    """n = 104, m = 9, k = 181; the hinge is pinned at 0 = its lower limit.

    A pin on a limit makes the active rows dependent; both backends must
    still agree on the optimum and keep every limit.
    """
    case = seed000_sized_case()
    lower = case.problem.limits.lower.copy()
    lower[7:] = 0.0
    problem = replace(case.problem, limits=JointLimits(lower, case.problem.limits.upper))
    chomp = solve_chomp(problem, case.initial_guess)
    sqp = solve_sqp(problem, case.initial_guess)
    for result in (chomp, sqp):
        assert result.outcome is Outcome.SUCCESS, result.message
        assert result.max_violation <= 1e-6
        assert np.all(result.trajectory >= lower - 1e-9)
    assert sqp.cost == pytest.approx(chomp.cost, rel=0.01)
