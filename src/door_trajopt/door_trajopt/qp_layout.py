r"""Fixed-sparsity layout of the TrajOpt QP subproblem for OSQP.

Variables ``z = [d, s+, s-, t]``: the step ``d`` on the free trajectory,
equality slacks ``s+ - s- = h + H d`` and inequality slacks ``t >= g + G d``
(TrajOpt's exact l1 penalty, [Banerjee 2015] Sec. IV adopts TrajOpt).  The QP is

.. math::

    \min_z\; \tfrac12 d^T P d + \nabla f^T d + \mu\, \mathbf 1^T (s^+ + s^- + t)
    \quad\text{s.t.}\quad
    \begin{bmatrix} H & -I & I & 0 \\ G & 0 & 0 & -I \\ & I_z & & \end{bmatrix} z
    \in \begin{bmatrix} [-h, -h] \\ (-\infty, -g] \\ [\ell_z, u_z] \end{bmatrix}

where the identity block carries the trust box and joint limits on ``d``
and ``0 <= s+, s-, t`` (slacks pinned to 0 for hard constraints).  ``P`` is
the constant smoothness/posture Hessian plus Gauss-Newton ``w J^T J``, and
a small curvature ``epsilon`` on the slacks (``+ epsilon/2 ||s||^2``): it
keeps the penalty exact (a slack only becomes positive when a multiplier
would exceed ``mu``, exactly as without it) but removes the LP-like
degeneracy that makes ADMM need thousands of iterations.

With hard constraints the slacks are pinned to 0, so the HARD mode of
:mod:`door_trajopt.sqp` uses the layout **without** them (``slacks=False``:
``z = d``, rows ``[H; G; I]``): a third of the variables and half the rows
of the slack layout for the door motions (81 against 261 variables for a
push), which OSQP solves ~2× faster.  Only the elastic re-solve, when the
linearisation is infeasible inside the box, needs the slack layout.

OSQP requires the sparsity of ``P`` and ``A`` to stay fixed after
``setup``, so they are built from the *structural* patterns of the
Jacobians; each iteration the current values are gathered into those
patterns (:class:`SparsityPattern`) and permuted into CSC order for
``OSQP.update(Px=..., Ax=...)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import scipy.sparse as sp

from door_trajopt.problem import FloatArray, TrajoptError

__all__ = ["IntArray", "QpLayout", "SparsityPattern", "assemble_coo", "csc_permutation"]

IntArray = npt.NDArray[np.int64]


@dataclass(frozen=True)
class SparsityPattern:
    """Sorted linear keys of a structural pattern; gathers values into it.

    Keys are ``row * n_cols + col`` (row-major) or ``col * n_rows + row``
    (column-major, the CSC order OSQP wants for ``P``).
    """

    shape: tuple[int, int]
    keys: IntArray
    column_major: bool

    @classmethod
    def of(cls, pattern: sp.spmatrix, column_major: bool = False) -> SparsityPattern:
        """Pattern from the non-zeros of a (boolean) sparse matrix."""
        coo = sp.coo_matrix(pattern)
        keys = cls._keys(coo.row, coo.col, pattern.shape, column_major)
        return cls((int(pattern.shape[0]), int(pattern.shape[1])), np.unique(keys), column_major)

    @staticmethod
    def _keys(
        rows: IntArray, cols: IntArray, shape: tuple[int, int], column_major: bool
    ) -> IntArray:
        rows, cols = rows.astype(np.int64), cols.astype(np.int64)
        return cols * shape[0] + rows if column_major else rows * shape[1] + cols

    @property
    def nnz(self) -> int:
        """Number of structural non-zeros."""
        return int(self.keys.size)

    def rows_cols(self) -> tuple[IntArray, IntArray]:
        """Row and column index of every key, in key order."""
        if self.column_major:
            cols, rows = np.divmod(self.keys, self.shape[0])
        else:
            rows, cols = np.divmod(self.keys, self.shape[1])
        return rows, cols

    def gather(self, matrix: sp.spmatrix, what: str) -> FloatArray:
        """Values of ``matrix`` in key order; raises if a non-zero lies outside.

        A canonical row-major CSR matrix whose stored entries are exactly the pattern
        (the block Jacobians of :mod:`door_trajopt.waypoint_constraints` are) gives its
        data as it is; anything else is matched key by key.
        """
        if not self.column_major and sp.issparse(matrix) and matrix.format == "csr" \
                and matrix.nnz == self.nnz and matrix.has_canonical_format:
            rows = np.repeat(np.arange(matrix.shape[0], dtype=np.int64), np.diff(matrix.indptr))
            if np.array_equal(rows * self.shape[1] + matrix.indices, self.keys):
                return np.array(matrix.data, dtype=np.float64)
        coo = sp.coo_matrix(matrix)
        values = np.zeros(self.nnz)
        if coo.nnz == 0:
            return values
        keys = self._keys(coo.row, coo.col, self.shape, self.column_major)
        slots = np.minimum(np.searchsorted(self.keys, keys), self.nnz - 1)
        outside = (self.keys[slots] != keys) & (coo.data != 0.0)
        if outside.any():
            raise TrajoptError(f"{what}: non-zero outside the declared sparsity pattern")
        inside = self.keys[slots] == keys
        np.add.at(values, slots[inside], coo.data[inside])
        return values


@dataclass(frozen=True)
class QpLayout:
    """Index bookkeeping of the QP above for one problem."""

    n_variables: int
    n_equality: int
    n_inequality: int
    equality_pattern: SparsityPattern
    inequality_pattern: SparsityPattern
    hessian_pattern: SparsityPattern
    a_permutation: IntArray
    a_constant_values: FloatArray
    a_template: sp.csc_matrix
    slacks: bool = True

    @property
    def n_slacks(self) -> int:
        """``2 k_eq + k_ineq`` (0 without slacks)."""
        return 2 * self.n_equality + self.n_inequality if self.slacks else 0

    @property
    def n_qp_variables(self) -> int:
        """Length of ``z``."""
        return self.n_variables + self.n_slacks

    @property
    def n_rows(self) -> int:
        """Rows of the QP constraint matrix."""
        return self.n_equality + self.n_inequality + self.n_qp_variables

    @classmethod
    def build(
        cls, equality: sp.spmatrix, inequality: sp.spmatrix, hessian: sp.spmatrix,
        slacks: bool = True,
    ) -> QpLayout:
        """Layout from the structural patterns of ``H``, ``G`` and ``P`` (with or without slacks)."""
        eq_pattern, ineq_pattern = SparsityPattern.of(equality), SparsityPattern.of(inequality)
        upper = sp.triu(sp.csc_matrix(hessian, dtype=bool), format="csc")
        n_variables = int(hessian.shape[0])
        rows, cols, constants = assemble_coo(eq_pattern, ineq_pattern, n_variables, slacks)
        n_z = n_variables + (2 * eq_pattern.shape[0] + ineq_pattern.shape[0] if slacks else 0)
        n_rows = eq_pattern.shape[0] + ineq_pattern.shape[0] + n_z
        permutation, template = csc_permutation(rows, cols, (n_rows, n_z))
        return cls(
            n_variables=n_variables,
            n_equality=eq_pattern.shape[0],
            n_inequality=ineq_pattern.shape[0],
            equality_pattern=eq_pattern,
            inequality_pattern=ineq_pattern,
            hessian_pattern=SparsityPattern.of(upper, column_major=True),
            a_permutation=permutation,
            a_constant_values=constants,
            a_template=template,
            slacks=slacks,
        )

    def a_values(self, equality: sp.spmatrix, inequality: sp.spmatrix) -> FloatArray:
        """CSC data of the QP constraint matrix for the current ``H``, ``G``."""
        listed = np.concatenate(
            [
                self.equality_pattern.gather(equality, "equality Jacobian"),
                self.inequality_pattern.gather(inequality, "inequality Jacobian"),
                self.a_constant_values,
            ]
        )
        permuted: FloatArray = listed[self.a_permutation]
        return permuted

    def a_matrix(self, equality: sp.spmatrix, inequality: sp.spmatrix) -> sp.csc_matrix:
        """Build the QP constraint matrix with the fixed structure (for ``setup``)."""
        matrix = self.a_template.copy()
        matrix.data = self.a_values(equality, inequality)
        return matrix

    def p_values(self, hessian: sp.spmatrix, slack_curvature: float) -> FloatArray:
        """CSC data of the upper triangle of ``P``; slack diagonal ``slack_curvature``."""
        step_part = self.hessian_pattern.gather(sp.triu(hessian), "Hessian")
        return np.concatenate([step_part, np.full(self.n_slacks, slack_curvature)])

    def p_matrix(self, hessian: sp.spmatrix, slack_curvature: float) -> sp.csc_matrix:
        """Upper-triangular ``P`` over ``z`` with the fixed structure."""
        rows, cols = self.hessian_pattern.rows_cols()
        slacks = np.arange(self.n_variables, self.n_qp_variables)
        size = self.n_qp_variables
        coordinates = (np.concatenate([rows, slacks]), np.concatenate([cols, slacks]))
        values = self.p_values(hessian, slack_curvature)
        matrix = sp.csc_matrix((values, coordinates), shape=(size, size))
        matrix.sort_indices()
        return matrix

    def linear_term(self, gradient: FloatArray, penalty: float) -> FloatArray:
        """``q = [grad f, mu 1]``."""
        return np.concatenate([gradient, np.full(self.n_slacks, penalty)])


def assemble_coo(
    eq: SparsityPattern, ineq: SparsityPattern, n_variables: int, slacks: bool = True
) -> tuple[IntArray, IntArray, FloatArray]:
    """COO coordinates of the QP matrix: ``H``, ``G`` pattern slots then constants."""
    k_eq, k_ineq = eq.shape[0], ineq.shape[0]
    n_z = n_variables + (2 * k_eq + k_ineq if slacks else 0)
    eq_rows, eq_cols = eq.rows_cols()
    ineq_rows, ineq_cols = ineq.rows_cols()
    rows, cols, constants = [eq_rows, k_eq + ineq_rows], [eq_cols, ineq_cols], []
    if slacks:
        slack_pos = n_variables + np.arange(k_eq)
        slack_neg = n_variables + k_eq + np.arange(k_eq)
        slack_ineq = n_variables + 2 * k_eq + np.arange(k_ineq)
        rows += [np.arange(k_eq), np.arange(k_eq), k_eq + np.arange(k_ineq)]
        cols += [slack_pos, slack_neg, slack_ineq]
        constants += [-np.ones(k_eq), np.ones(k_eq), -np.ones(k_ineq)]
    identity = np.arange(n_z)
    constants.append(np.ones(n_z))
    rows.append(k_eq + k_ineq + identity)
    cols.append(identity)
    return np.concatenate(rows), np.concatenate(cols), np.concatenate(constants)


def csc_permutation(
    rows: IntArray, cols: IntArray, shape: tuple[int, int]
) -> tuple[IntArray, sp.csc_matrix]:
    """Map from listed COO order to CSC data order (and the CSC template)."""
    tags = np.arange(1, rows.size + 1, dtype=np.float64)
    template = sp.coo_matrix((tags, (rows, cols)), shape=shape).tocsc()
    template.sort_indices()
    if template.nnz != rows.size:
        raise TrajoptError("internal error: duplicate entries in the QP layout")
    return template.data.astype(np.int64) - 1, template
