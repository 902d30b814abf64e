"""Constraint blocks built from per-waypoint functions (block-diagonal Jacobians).

A waypoint function maps one waypoint q_t (m,) to (value (r,), jacobian (r, m) — computed
only when asked for, since solvers evaluate values far more often); applied
at the waypoints ``at`` it becomes a :class:`~door_trajopt.problem.Constraint` with a
fixed structural pattern (r rows per waypoint, its own m columns), which the SQP backend
needs to set OSQP up once.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import scipy.sparse as sp

from door_trajopt.problem import Constraint, ConstraintKind, TrajectoryFunction, TrajectoryJacobian, TrajoptError

__all__ = ["WaypointFunction", "WaypointValue", "fixed_dof", "waypoint_constraint"]

WaypointValue = tuple[np.ndarray, np.ndarray | None]
"""What a waypoint function returns: (value, jacobian or None when not needed)."""
WaypointFunction = Callable[[np.ndarray, bool], WaypointValue]
"""f(q_t, need_jacobian) → (value, jacobian or None when not needed)."""


def _block_indices(at: Sequence[int], rows: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """Row and column index of every entry of the stacked (rows × m) blocks, block by block."""
    block_rows = np.repeat(np.arange(rows), m)
    block_cols = np.tile(np.arange(m), rows)
    row_index = np.concatenate([b * rows + block_rows for b in range(len(at))])
    col_index = np.concatenate([t * m + block_cols for t in at])
    return row_index, col_index


def _block_pattern(at: Sequence[int], rows: int, m: int, n: int) -> sp.csr_matrix:
    row_index, col_index = _block_indices(at, rows, m)
    return sp.csr_matrix((np.ones(row_index.size, dtype=bool), (row_index, col_index)),
                         shape=(rows * len(at), n * m))


def _jacobian_at(function: WaypointFunction, waypoint: np.ndarray) -> np.ndarray:
    """The waypoint function's Jacobian at ``waypoint`` (it must give one when asked)."""
    jacobian = function(waypoint, True)[1]
    if jacobian is None:
        raise TrajoptError("a waypoint function returned no Jacobian when asked for one")
    return jacobian


def _callbacks(function: WaypointFunction, at: Sequence[int], rows: int, m: int,
               n: int) -> tuple[TrajectoryFunction, TrajectoryJacobian, TrajectoryFunction | None]:
    """Value, Jacobian and Jacobian-data callbacks. The data are the blocks' entries block by
    block, row-major: with increasing waypoints that is the CSR order of the pattern."""
    at = tuple(at)
    row_index, col_index = _block_indices(at, rows, m)
    shape = (rows * len(at), n * m)

    def value(trajectory: np.ndarray) -> np.ndarray:
        return np.concatenate([function(trajectory[t], False)[0] for t in at])

    def data(trajectory: np.ndarray) -> np.ndarray:
        return np.concatenate([_jacobian_at(function, trajectory[t]).ravel() for t in at])

    def jacobian(trajectory: np.ndarray) -> sp.csr_matrix:
        return sp.csr_matrix((data(trajectory), (row_index, col_index)), shape=shape)

    return value, jacobian, (data if list(at) == sorted(set(at)) else None)


def waypoint_constraint(name: str, kind: ConstraintKind, function: WaypointFunction, rows: int,
                        at: Sequence[int], m: int, n: int) -> Constraint:
    value, jacobian, data = _callbacks(function, at, rows, m, n)
    return Constraint(name, kind, rows * len(at), value, jacobian, _block_pattern(at, rows, m, n), data)


def fixed_dof(name: str, dof: int, values: dict[int, float], m: int, n: int) -> Constraint:
    """q_t[dof] = values[t] for each waypoint t in ``values`` (linear equality rows)."""
    times = tuple(sorted(values))
    targets = np.array([values[t] for t in times])
    rows = sp.csr_matrix((np.ones(len(times)), ([*range(len(times))], [t * m + dof for t in times])),
                         shape=(len(times), n * m))

    def value(trajectory: np.ndarray) -> np.ndarray:
        deviation: np.ndarray = trajectory[list(times), dof] - targets
        return deviation

    ones = np.ones(len(times))
    return Constraint(name, ConstraintKind.EQUALITY, len(times), value, lambda _: rows, rows.astype(bool),
                      lambda _: ones)
