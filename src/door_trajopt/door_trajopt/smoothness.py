r"""CHOMP finite-difference smoothness objective ([Zucker 2013] Sec. II-A).

[Zucker 2013] eq. (1) writes smoothness as a sum of squared finite differences of
every DOF ``j`` over the waypoints.  With a finite-differencing matrix ``K``
(velocities in the seed's printed example, **accelerations** in its door
experiments) and the free waypoints stacked in ``xi``, eq. (2) reads

.. math::

    f(\xi) = \tfrac12 \xi^T A \xi + \xi^T b + c,
    \qquad A = K^T K, \quad b = K^T e, \quad c = \tfrac12 e^T e,

where ``e`` carries the contribution of the fixed endpoints.  ``A`` is
symmetric positive definite and banded, so eq. (3), ``xi* = -A^{-1} b``,
costs ``O(m n)`` with a banded Cholesky factor.

Here ``K_1`` is built for **one** DOF over all ``n`` waypoints and split into
its free-waypoint columns ``K`` and fixed-waypoint columns ``K_fix``; with
per-DOF weights ``W = diag(w)`` ([Banerjee 2015]'s ``Q1``) and the row-major layout
``xi[t*m + j]`` of :mod:`door_trajopt.problem`:

.. math::

    A = (K^T K) \otimes W, \qquad
    E = K_{fix} Q_{fix} \;(\text{rows} \times m), \qquad
    b = \mathrm{vec}_{row}(K^T E W), \qquad
    c = \tfrac12 \sum_j w_j \lVert E_{:,j} \rVert^2 .

The per-DOF value is ``1/2 w_j ||K x_j + E_j||^2``; ``A_1 = K^T K`` is kept in
LAPACK upper banded storage for :func:`scipy.linalg.cholesky_banded`.

Rows of ``K_1`` for accelerations are ``q_{t-1} - 2 q_t + q_{t+1}`` at the
interior waypoints; with ``at_rest`` the ghost waypoints ``q_{-1} = q_0`` and
``q_n = q_{n-1}`` add the rows ``q_1 - q_0`` and ``q_{n-2} - q_{n-1}`` (zero
velocity at both ends), which keeps ``A`` positive definite with a free end.
For velocities the rows are ``q_t - q_{t-1}``.  The constant ``1/dt^2`` (or
``1/dt^4``) factor is omitted as in [Zucker 2013].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from door_trajopt.problem import Derivative, FloatArray, TrajectoryProblem

__all__ = ["SmoothnessMetric", "finite_difference_rows", "upper_banded"]


def finite_difference_rows(
    n_waypoints: int, derivative: Derivative, at_rest: bool
) -> sp.csr_matrix:
    """``K_1``: finite differences of one DOF over all ``n_waypoints``.

    Returns a ``(rows, n_waypoints)`` sparse matrix ([Zucker 2013] eq. (1)).
    """
    if derivative is Derivative.VELOCITY:
        return sp.diags([-1.0, 1.0], [0, 1], shape=(n_waypoints - 1, n_waypoints), format="csr")
    interior = sp.diags([1.0, -2.0, 1.0], [0, 1, 2], shape=(n_waypoints - 2, n_waypoints))
    if not at_rest:
        return interior.tocsr()
    first = sp.csr_matrix(([-1.0, 1.0], ([0, 0], [0, 1])), shape=(1, n_waypoints))
    last = sp.csr_matrix(
        ([1.0, -1.0], ([0, 0], [n_waypoints - 2, n_waypoints - 1])), shape=(1, n_waypoints)
    )
    return sp.vstack([first, interior, last], format="csr")


def upper_banded(matrix: sp.spmatrix, bandwidth: int) -> FloatArray:
    """LAPACK upper banded storage ``ab[u + i - j, j] = M[i, j]`` of a symmetric matrix."""
    size = matrix.shape[0]
    banded = np.zeros((bandwidth + 1, size))
    dense_diagonals = sp.dia_matrix(matrix)
    for offset, values in zip(dense_diagonals.offsets, dense_diagonals.data, strict=True):
        if 0 <= offset <= bandwidth:
            banded[bandwidth - offset, offset:] = values[offset:]
    return banded


@dataclass(frozen=True)
class SmoothnessMetric:
    """Constant quadratic ``f(xi) = 1/2 xi^T A xi + xi^T b + c`` of [Zucker 2013] eq. (2).

    Attributes are for the free waypoints only (``n_free`` rows of ``K``):
    ``k_free`` is ``K``, ``endpoint_term`` is ``E``, ``weights`` is ``diag(W)``.
    """

    k_free: sp.csr_matrix
    endpoint_term: FloatArray
    weights: FloatArray
    bandwidth: int

    @classmethod
    def for_problem(cls, problem: TrajectoryProblem) -> SmoothnessMetric:
        """Build ``K``, ``E`` and the weights from a problem's smoothness spec."""
        spec = problem.smoothness
        k_all = finite_difference_rows(problem.n_waypoints, spec.derivative, spec.at_rest)
        free = np.arange(1, 1 + problem.n_free)
        fixed = np.setdiff1d(np.arange(problem.n_waypoints), free)
        fixed_rows = [problem.start] if problem.end is None else [problem.start, problem.end]
        fixed_values = np.vstack(fixed_rows)
        endpoint_term = k_all[:, fixed] @ fixed_values
        return cls(
            k_free=k_all[:, free].tocsr(),
            endpoint_term=np.asarray(endpoint_term),
            weights=problem.smoothness_weights,
            bandwidth=spec.derivative.value,
        )

    @property
    def n_free(self) -> int:
        """Number of free waypoints."""
        return int(self.k_free.shape[1])

    @property
    def n_dof(self) -> int:
        """Number of DOF ``m``."""
        return int(self.weights.size)

    def single_dof_matrix(self) -> sp.csr_matrix:
        """``A_1 = K^T K`` for one DOF (``n_free x n_free``, banded)."""
        return (self.k_free.T @ self.k_free).tocsr()

    def single_dof_banded(self) -> FloatArray:
        """``A_1`` in upper banded storage (bandwidth = derivative order)."""
        return upper_banded(self.single_dof_matrix(), self.bandwidth)

    def hessian(self) -> sp.csr_matrix:
        """Return ``A = A_1 (x) W`` for the row-major free vector (sparse, SPD)."""
        return sp.kron(self.single_dof_matrix(), sp.diags(self.weights), format="csr")

    def linear_term(self) -> FloatArray:
        """``b = vec_row(K^T E W)``."""
        return np.asarray(self.k_free.T @ self.endpoint_term * self.weights).reshape(-1)

    def constant_term(self) -> float:
        """``c = 1/2 sum_j w_j ||E_j||^2``."""
        return 0.5 * float(np.sum(self.weights * np.sum(self.endpoint_term**2, axis=0)))

    def differences(self, free: FloatArray) -> FloatArray:
        """Finite differences ``K X + E`` (one column per DOF)."""
        waypoints = free.reshape(self.n_free, self.n_dof)
        return np.asarray(self.k_free @ waypoints) + self.endpoint_term

    def value(self, free: FloatArray) -> float:
        """``f(xi)`` of [Zucker 2013] eq. (2)."""
        residual = self.differences(free)
        return 0.5 * float(np.sum(self.weights * np.sum(residual**2, axis=0)))

    def gradient(self, free: FloatArray) -> FloatArray:
        """``grad f = A xi + b = vec_row(K^T (K X + E) W)``."""
        residual = self.differences(free) * self.weights
        return np.asarray(self.k_free.T @ residual).reshape(-1)

    def unconstrained_minimum(self) -> FloatArray:
        """``xi* = -A^{-1} b`` ([Zucker 2013] eq. (3)), via a sparse solve."""
        a_single = self.single_dof_matrix().tocsc()
        rhs = -np.asarray(self.k_free.T @ self.endpoint_term)
        return np.asarray(spla.spsolve(a_single, rhs)).reshape(-1)
