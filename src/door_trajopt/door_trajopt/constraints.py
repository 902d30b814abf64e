"""Stacking named constraint blocks into ``h(xi)``/``g(xi)`` and their Jacobians.

The stacked Jacobian is restricted to the free waypoints' columns (``H`` of
[Zucker 2013] Sec. II-B is ``k x (n m)`` over the free trajectory only).  Values
are checked for NaN/inf so that a broken callback ends a solve with
``INVALID_INPUT`` naming the block instead of poisoning the linear algebra.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from door_trajopt.problem import (
    Constraint,
    ConstraintKind,
    FloatArray,
    JacobianValue,
    TrajectoryFunction,
    TrajectoryProblem,
    TrajoptError,
)

__all__ = ["ConstraintStack", "NonFiniteValueError", "Violation", "checked_values", "free_jacobian", "free_pattern",
           "joint_limit_violation", "worst_violation"]

JOINT_LIMITS_NAME = "joint_limits"
"""Name reported when the worst violation is a joint limit."""


class NonFiniteValueError(TrajoptError):
    """A callback returned NaN/inf; the message names the callback."""


def free_jacobian(jacobian: JacobianValue, rows: int, columns: slice, name: str) -> sp.csr_matrix:
    """Restrict a ``(rows, n*m)`` callback Jacobian to the free columns (CSR)."""
    matrix = sp.csr_matrix(jacobian, dtype=np.float64)
    if matrix.shape[0] != rows:
        raise TrajoptError(f"{name}: Jacobian has {matrix.shape[0]} rows, expected {rows}")
    restricted = matrix[:, columns]
    if not np.all(np.isfinite(restricted.data)):
        raise NonFiniteValueError(f"{name}: Jacobian contains NaN/inf")
    return restricted


def checked_values(values: FloatArray, size: int, name: str) -> FloatArray:
    """Flatten a callback value vector and check its length and finiteness."""
    vector = np.asarray(values, dtype=np.float64).reshape(-1)
    if vector.size != size:
        raise TrajoptError(f"{name}: value has {vector.size} entries, expected {size}")
    if not np.all(np.isfinite(vector)):
        raise NonFiniteValueError(f"{name}: value contains NaN/inf")
    return vector


def free_pattern(
    pattern: sp.csr_matrix | None, rows: int, total_columns: int, columns: slice
) -> sp.csr_matrix:
    """Structural pattern restricted to the free columns (dense when ``None``)."""
    if pattern is None:
        width = columns.stop - columns.start
        return sp.csr_matrix(np.ones((rows, width), dtype=bool))
    if pattern.shape[1] != total_columns:
        raise TrajoptError(f"pattern has {pattern.shape[1]} columns, expected {total_columns}")
    return sp.csr_matrix(pattern[:, columns], dtype=bool)


@dataclass(frozen=True)
class ConstraintStack:
    """All blocks of one :class:`ConstraintKind`, stacked in declaration order."""

    blocks: tuple[Constraint, ...]
    kind: ConstraintKind
    columns: slice
    total_columns: int

    @classmethod
    def of_kind(cls, problem: TrajectoryProblem, kind: ConstraintKind) -> ConstraintStack:
        """Stack the problem's blocks of ``kind``."""
        total = problem.n_waypoints * problem.n_dof
        return cls(problem.constraints_of(kind), kind, problem.free_columns, total)

    @property
    def size(self) -> int:
        """Total number of rows ``k``."""
        return int(sum(block.size for block in self.blocks))

    @property
    def n_variables(self) -> int:
        """Number of free variables (columns of the stacked Jacobian)."""
        count: int = self.columns.stop - self.columns.start
        return count

    def offsets(self) -> FloatArray:
        """Row offsets of the blocks (length ``len(blocks) + 1``)."""
        return np.concatenate([[0], np.cumsum([block.size for block in self.blocks])]).astype(int)

    def values(self, trajectory: FloatArray) -> FloatArray:
        """Stacked ``h`` (or ``g``) at a full ``(n, m)`` trajectory."""
        if not self.blocks:
            return np.zeros(0)
        parts = [checked_values(b.value(trajectory), b.size, b.name) for b in self.blocks]
        return np.concatenate(parts)

    @cached_property
    def _data_layout(self) -> tuple[sp.csr_matrix, tuple[tuple[TrajectoryFunction, np.ndarray], ...]] | None:
        """The stacked free-column pattern and, per block, its ``jacobian_data`` and which of
        its pattern's entries lie in free columns; ``None`` unless every block gives
        ``jacobian_data`` (a block with it always has a pattern)."""
        sources = []
        for block in self.blocks:
            if block.jacobian_data is None or block.pattern is None:
                return None
            columns = block.pattern.indices
            sources.append((block.jacobian_data, (columns >= self.columns.start) & (columns < self.columns.stop)))
        return (self.pattern(), tuple(sources)) if sources else None

    def jacobian(self, trajectory: FloatArray) -> sp.csr_matrix:
        """Stacked Jacobian w.r.t. the free variables (``k x N`` CSR).

        With every block's ``jacobian_data`` the values go straight into the stacked
        pattern's CSR structure (computed once), instead of a sparse matrix per block
        restricted to the free columns and stacked: that was a quarter of a door
        motion's SQP time.
        """
        layout = self._data_layout
        if layout is not None:
            return self._jacobian_from_data(trajectory, *layout)
        if not self.blocks:
            return sp.csr_matrix((0, self.n_variables))
        parts = [
            free_jacobian(b.jacobian(trajectory), b.size, self.columns, b.name) for b in self.blocks
        ]
        return sp.vstack(parts, format="csr")

    def _jacobian_from_data(self, trajectory: FloatArray, pattern: sp.csr_matrix,
                            sources: tuple[tuple[TrajectoryFunction, np.ndarray], ...]) -> sp.csr_matrix:
        parts = []
        for block, (jacobian_data, inside) in zip(self.blocks, sources, strict=True):
            data = np.asarray(jacobian_data(trajectory), dtype=np.float64).reshape(-1)
            if data.size != inside.size:
                raise TrajoptError(f"{block.name}: Jacobian data has {data.size} entries, expected {inside.size}")
            parts.append(data[inside])
        data = np.concatenate(parts)
        if not np.all(np.isfinite(data)):
            name = next(b.name for b, p in zip(self.blocks, parts, strict=True) if not np.all(np.isfinite(p)))
            raise NonFiniteValueError(f"{name}: Jacobian contains NaN/inf")
        return sp.csr_matrix((data, pattern.indices, pattern.indptr), shape=pattern.shape)

    def pattern(self) -> sp.csr_matrix:
        """Stacked structural pattern w.r.t. the free variables (boolean CSR)."""
        if not self.blocks:
            return sp.csr_matrix((0, self.n_variables), dtype=bool)
        parts = [
            free_pattern(b.pattern, b.size, self.total_columns, self.columns) for b in self.blocks
        ]
        return sp.vstack(parts, format="csr")

    def violations(self, values: FloatArray) -> FloatArray:
        """Per-row violation: ``|h_i|`` or ``max(g_i, 0)``."""
        if self.kind is ConstraintKind.EQUALITY:
            return np.abs(values)
        return np.maximum(values, 0.0)

    def block_name(self, row: int) -> str:
        """Name of the block that holds stacked row ``row``."""
        index = int(np.searchsorted(self.offsets(), row, side="right")) - 1
        return self.blocks[index].name


@dataclass(frozen=True)
class Violation:
    """Largest constraint violation and the name of the block holding it."""

    amount: float
    name: str | None


def joint_limit_violation(problem: TrajectoryProblem, free: FloatArray) -> float:
    """Largest excursion of the free waypoints outside the joint limits."""
    waypoints = free.reshape(problem.n_free, problem.n_dof)
    below = problem.limits.lower - waypoints
    above = waypoints - problem.limits.upper
    return float(max(0.0, np.max(below), np.max(above)))


def worst_violation(
    problem: TrajectoryProblem,
    free: FloatArray,
    stacked: tuple[tuple[ConstraintStack, FloatArray], ...],
) -> Violation:
    """Worst violation over joint limits and the given ``(stack, values)`` pairs."""
    best = Violation(joint_limit_violation(problem, free), JOINT_LIMITS_NAME)
    for stack, values in stacked:
        if values.size == 0:
            continue
        per_row = stack.violations(values)
        row = int(np.argmax(per_row))
        if per_row[row] > best.amount:
            best = Violation(float(per_row[row]), stack.block_name(row))
    return best if best.amount > 0.0 else Violation(0.0, None)
