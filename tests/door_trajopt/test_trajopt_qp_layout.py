"""The fixed-sparsity OSQP layout reproduces the QP matrices of qp_layout's docstring."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from door_trajopt.qp_layout import QpLayout


def random_pattern(rows: int, cols: int, seed: int) -> sp.csr_matrix:
    return sp.random(rows, cols, density=0.3, random_state=seed, format="csr").astype(bool)


def test_constraint_matrix_matches_block_reference() -> None:
    n, k_eq, k_ineq = 6, 3, 2
    eq_pattern, ineq_pattern = random_pattern(k_eq, n, 1), random_pattern(k_ineq, n, 2)
    hessian = sp.diags([2.0, -1.0, -1.0], [0, 1, -1], shape=(n, n), format="csr")
    layout = QpLayout.build(eq_pattern, ineq_pattern, hessian)
    rng = np.random.default_rng(3)
    equality = sp.csr_matrix(eq_pattern.multiply(rng.normal(size=(k_eq, n))))
    inequality = sp.csr_matrix(ineq_pattern.multiply(rng.normal(size=(k_ineq, n))))
    identity = sp.identity
    zeros = sp.csr_matrix
    reference = sp.vstack(
        [
            sp.hstack([equality, -identity(k_eq), identity(k_eq), zeros((k_eq, k_ineq))]),
            sp.hstack([inequality, zeros((k_ineq, 2 * k_eq)), -identity(k_ineq)]),
            identity(layout.n_qp_variables),
        ]
    )
    built = layout.a_matrix(equality, inequality)
    np.testing.assert_allclose(built.toarray(), reference.toarray())
    # a later update with other values keeps the structure and only moves values
    scaled = layout.a_values(2.0 * equality, inequality)
    assert scaled.size == built.nnz


def test_hessian_values_follow_the_upper_triangle_pattern() -> None:
    n = 5
    hessian = sp.diags([4.0, 1.0, 1.0], [0, 1, -1], shape=(n, n), format="csr")
    empty = sp.csr_matrix((0, n), dtype=bool)
    layout = QpLayout.build(empty, empty, hessian)
    matrix = layout.p_matrix(hessian, slack_curvature=0.0)
    np.testing.assert_allclose(matrix.toarray(), sp.triu(hessian).toarray())
    np.testing.assert_allclose(layout.p_values(3.0 * hessian, 0.0), 3.0 * matrix.data)
