"""Smoothness metric of [Zucker 2013] eq. (1)-(3): structure, values and banded solves."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from door_trajopt.banded import KroneckerBandedCholesky, LowRankUpdatedMetric
from door_trajopt.problem import (
    Derivative,
    JointLimits,
    SmoothnessSpec,
    TrajectoryProblem,
    TrajoptError,
)
from door_trajopt.smoothness import SmoothnessMetric

N_WAYPOINTS = 9
N_DOF = 3
WEIGHTS = np.array([1.0, 2.0, 0.5])


def make_problem(end_fixed: bool, spec: SmoothnessSpec) -> TrajectoryProblem:
    """Small problem with distinct per-DOF weights."""
    return TrajectoryProblem(
        n_waypoints=N_WAYPOINTS,
        start=np.array([0.1, -0.2, 0.3]),
        end=np.array([1.0, 0.5, -0.4]) if end_fixed else None,
        limits=JointLimits.unbounded(N_DOF),
        smoothness=SmoothnessSpec(spec.derivative, spec.at_rest, WEIGHTS),
    )


def explicit_sum_of_squares(problem: TrajectoryProblem, trajectory: np.ndarray) -> float:
    """[Zucker 2013] eq. (1) written out with loops, ghost waypoints for ``at_rest``."""
    spec = problem.smoothness
    padded = trajectory
    if spec.derivative is Derivative.ACCELERATION and spec.at_rest:
        padded = np.vstack([trajectory[:1], trajectory, trajectory[-1:]])
    total = 0.0
    for j in range(problem.n_dof):
        column = padded[:, j]
        differences = np.diff(column, n=spec.derivative.value)
        total += 0.5 * WEIGHTS[j] * float(np.sum(differences**2))
    return total


def dense_single_dof_k(problem: TrajectoryProblem) -> np.ndarray:
    """``K`` for one DOF (free columns) built from unit trajectories."""
    metric = SmoothnessMetric.for_problem(problem)
    return metric.k_free.toarray()


SPECS = [
    (False, SmoothnessSpec(Derivative.ACCELERATION, True)),
    (True, SmoothnessSpec(Derivative.ACCELERATION, True)),
    (True, SmoothnessSpec(Derivative.ACCELERATION, False)),
    (False, SmoothnessSpec(Derivative.VELOCITY, True)),
]


@pytest.mark.parametrize(("end_fixed", "spec"), SPECS)
def test_hessian_is_symmetric_positive_definite(end_fixed: bool, spec: SmoothnessSpec) -> None:
    hessian = SmoothnessMetric.for_problem(make_problem(end_fixed, spec)).hessian().toarray()
    np.testing.assert_allclose(hessian, hessian.T)
    assert np.linalg.eigvalsh(hessian).min() > 1e-6


@pytest.mark.parametrize(("end_fixed", "spec"), SPECS)
def test_hessian_is_banded_and_dof_decoupled(end_fixed: bool, spec: SmoothnessSpec) -> None:
    metric = SmoothnessMetric.for_problem(make_problem(end_fixed, spec))
    rows, cols = metric.hessian().nonzero()
    assert np.all(np.abs(rows - cols) <= metric.bandwidth * N_DOF)
    assert np.all(rows % N_DOF == cols % N_DOF)


@pytest.mark.parametrize(("end_fixed", "spec"), SPECS)
def test_kronecker_structure_matches_dense_reference(end_fixed: bool, spec: SmoothnessSpec) -> None:
    problem = make_problem(end_fixed, spec)
    k_dense = dense_single_dof_k(problem)
    reference = np.kron(k_dense.T @ k_dense, np.diag(WEIGHTS))
    np.testing.assert_allclose(SmoothnessMetric.for_problem(problem).hessian().toarray(), reference)


@pytest.mark.parametrize(("end_fixed", "spec"), SPECS)
def test_quadratic_form_equals_sum_of_squared_differences(
    end_fixed: bool, spec: SmoothnessSpec
) -> None:
    problem = make_problem(end_fixed, spec)
    metric = SmoothnessMetric.for_problem(problem)
    free = np.random.default_rng(3).normal(size=problem.n_variables)
    quadratic = (
        0.5 * free @ (metric.hessian() @ free)
        + free @ metric.linear_term()
        + metric.constant_term()
    )
    explicit = explicit_sum_of_squares(problem, problem.full_trajectory(free))
    assert metric.value(free) == pytest.approx(explicit, rel=1e-12)
    assert quadratic == pytest.approx(explicit, rel=1e-12)


def test_gradient_matches_finite_differences() -> None:
    problem = make_problem(False, SmoothnessSpec())
    metric = SmoothnessMetric.for_problem(problem)
    free = np.random.default_rng(4).normal(size=problem.n_variables)
    step = 1e-6
    numeric = [
        (metric.value(free + step * e) - metric.value(free - step * e)) / (2 * step)
        for e in np.eye(free.size)
    ]
    np.testing.assert_allclose(metric.gradient(free), numeric, atol=1e-7)


def test_unconstrained_minimum_is_straight_line_in_configuration_space() -> None:
    """[Zucker 2013] eq. (3): ``-A^{-1} b`` joins the fixed endpoints by a line."""
    problem = make_problem(True, SmoothnessSpec(Derivative.ACCELERATION, False))
    metric = SmoothnessMetric.for_problem(problem)
    trajectory = problem.full_trajectory(metric.unconstrained_minimum())
    assert problem.end is not None
    line = problem.linear_interpolation(problem.end)
    np.testing.assert_allclose(trajectory, line, atol=1e-12)


def test_banded_cholesky_solves_match_dense_solves() -> None:
    problem = make_problem(False, SmoothnessSpec())
    metric = SmoothnessMetric.for_problem(problem)
    posture = np.array([0.0, 0.3, 0.3])
    factor = KroneckerBandedCholesky.factorize(metric.single_dof_banded(), WEIGHTS, posture)
    dense = metric.hessian().toarray() + np.diag(np.tile(posture, metric.n_free))
    rng = np.random.default_rng(5)
    vector = rng.normal(size=problem.n_variables)
    matrix = sp.random(problem.n_variables, 4, density=0.3, random_state=6).toarray()
    np.testing.assert_allclose(factor.solve(vector), np.linalg.solve(dense, vector), rtol=1e-10)
    np.testing.assert_allclose(factor.solve(matrix), np.linalg.solve(dense, matrix), atol=1e-10)
    assert len(factor.groups) == 3


def test_identical_dof_share_one_factor() -> None:
    problem = make_problem(False, SmoothnessSpec())
    metric = SmoothnessMetric.for_problem(problem)
    factor = KroneckerBandedCholesky.factorize(metric.single_dof_banded(), np.ones(4), np.zeros(4))
    assert len(factor.groups) == 1


def test_free_end_without_rest_rows_is_rejected() -> None:
    with pytest.raises(TrajoptError, match="at_rest"):
        make_problem(False, SmoothnessSpec(Derivative.ACCELERATION, False))


def test_woodbury_metric_matches_dense_gauss_newton_metric() -> None:
    problem = make_problem(False, SmoothnessSpec())
    metric = SmoothnessMetric.for_problem(problem)
    base = KroneckerBandedCholesky.factorize(metric.single_dof_banded(), WEIGHTS, np.zeros(N_DOF))
    jacobian = sp.random(3, problem.n_variables, density=0.2, random_state=7, format="csr")
    updated = LowRankUpdatedMetric.build(base, jacobian)
    dense = metric.hessian().toarray() + (jacobian.T @ jacobian).toarray()
    rhs = np.random.default_rng(8).normal(size=(problem.n_variables, 2))
    np.testing.assert_allclose(updated.solve(rhs), np.linalg.solve(dense, rhs), atol=1e-9)
