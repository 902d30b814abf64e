r"""Banded Cholesky solves with the Kronecker-structured CHOMP metric.

The constant part of the Hessian used as CHOMP's Riemannian metric is

.. math::

    M = A_1 \otimes W + I_n \otimes P,

(smoothness ``A = A_1 (x) W`` of [Zucker 2013] eq. (2) plus the diagonal posture
weights ``P``, [Banerjee 2015] ``Q2``).  In the row-major layout ``xi[t*m + j]`` its
DOF-``j`` block is ``M_j = w_j A_1 + p_j I``: banded, SPD, independent of the
other DOF.  Hence ``M^{-1} r`` reshapes ``r`` to ``n x m`` and solves every
column with the banded Cholesky factor of its DOF -- ``O(n m)`` as the seed
notes after eq. (3), never forming ``M^{-1}``.  DOF with identical
``(w_j, p_j)`` share one factor, so the usual ``A_1 (x) I_m`` case is a
single factorisation and one multi-right-hand-side solve.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
import scipy.sparse as sp
from scipy.linalg import cho_factor, cho_solve, cho_solve_banded, cholesky_banded

from door_trajopt.problem import FloatArray

__all__ = ["DofGroup", "KroneckerBandedCholesky", "LowRankUpdatedMetric", "MetricSolver"]


class MetricSolver(Protocol):
    """Anything that applies the inverse of CHOMP's metric to vectors/matrices."""

    def solve(self, rhs: FloatArray) -> FloatArray:
        """Return ``metric^{-1} rhs``."""
        ...


@dataclass(frozen=True)
class DofGroup:
    """DOF indices sharing one banded Cholesky factor (upper storage)."""

    dofs: tuple[int, ...]
    factor: FloatArray


@dataclass(frozen=True)
class KroneckerBandedCholesky:
    """Factorised ``M = A_1 (x) W + I (x) P``; factor once, solve many times."""

    n_free: int
    n_dof: int
    groups: tuple[DofGroup, ...]

    @classmethod
    def factorize(
        cls, single_dof_banded: FloatArray, weights: FloatArray, diagonal: FloatArray
    ) -> KroneckerBandedCholesky:
        """Factor ``M_j = w_j A_1 + p_j I`` for every distinct ``(w_j, p_j)``.

        ``single_dof_banded`` is ``A_1`` in LAPACK upper banded storage.
        """
        pairs = np.column_stack([weights, diagonal])
        unique_pairs, labels = np.unique(pairs, axis=0, return_inverse=True)
        groups = []
        for label, (weight, extra) in enumerate(unique_pairs):
            banded = weight * single_dof_banded
            banded[-1] += extra
            dofs = tuple(int(j) for j in np.flatnonzero(labels.reshape(-1) == label))
            groups.append(DofGroup(dofs, cholesky_banded(banded, lower=False)))
        return cls(int(single_dof_banded.shape[1]), int(weights.size), tuple(groups))

    def solve(self, rhs: FloatArray) -> FloatArray:
        """``M^{-1} rhs`` for ``rhs`` of shape ``(n*m,)`` or ``(n*m, k)``.

        Each DOF block of a right-hand side column is solved only if it is
        non-zero: the columns of ``H^T`` touch few DOF (a joint-value row
        touches one), which halves the work for [Zucker 2013]'s ``H``.
        """
        columns = 1 if rhs.ndim == 1 else rhs.shape[1]
        blocks = rhs.reshape(self.n_free, self.n_dof, columns)
        solution = np.zeros_like(blocks)
        for group in self.groups:
            index = list(group.dofs)
            stacked = blocks[:, index, :].reshape(self.n_free, -1)
            active = np.flatnonzero(np.any(stacked != 0.0, axis=0))
            if active.size == 0:
                continue
            solved = np.zeros_like(stacked)
            solved[:, active] = cho_solve_banded(
                (group.factor, False), stacked[:, active], check_finite=False
            )
            solution[:, index, :] = solved.reshape(self.n_free, len(index), columns)
        return solution.reshape(rhs.shape)


@dataclass(frozen=True)
class LowRankUpdatedMetric:
    r"""``(M + J^T J)^{-1}`` by the Woodbury identity, reusing ``M``'s banded factor.

    With ``U = M^{-1} J^T`` and the small capacitance ``C = I + J U``,

    .. math::

        (M + J^T J)^{-1} r = M^{-1} r - U C^{-1} J M^{-1} r .

    CHOMP uses it to add the Gauss-Newton term ``w J_r^T J_r`` of the
    least-squares (``Q3``) costs to its metric without refactorising ``M``;
    ``J`` here already carries the ``sqrt(w)`` factors.
    """

    base: KroneckerBandedCholesky
    jacobian: sp.csr_matrix
    basis: FloatArray
    capacitance: tuple[FloatArray, bool]

    @classmethod
    def build(cls, base: KroneckerBandedCholesky, jacobian: sp.csr_matrix) -> LowRankUpdatedMetric:
        """Precompute ``U`` and the Cholesky factor of ``C``."""
        basis = base.solve(jacobian.T.toarray())
        capacitance = np.eye(jacobian.shape[0]) + np.asarray(jacobian @ basis)
        return cls(base, jacobian, basis, cho_factor(capacitance))

    def solve(self, rhs: FloatArray) -> FloatArray:
        """``(M + J^T J)^{-1} rhs`` for one or several right-hand sides."""
        first = self.base.solve(rhs)
        solution: FloatArray = first - self.basis @ cho_solve(self.capacitance, self.jacobian @ first)
        return solution
