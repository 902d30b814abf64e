r"""Quasi-Newton curvature of the constraints for the SQP model, one block per waypoint.

TrajOpt (and :mod:`door_trajopt.sqp` before this) models the problem by the Hessian of the
cost alone. The step of an SQP method, though, is Newton's on the Lagrangian
``L = f + lambda^T c``; without ``sum_i lambda_i nabla^2 c_i`` the QP does not see how the
pose constraints curve (a TCP orientation error is a rotation), predicts decreases the
true merit does not give, and the trust region shrinks and rejects its way along the door
arc -- a third of the door motions' QPs were such rejected trials.

Every constraint of a door motion is a function of **one** waypoint
(:mod:`door_trajopt.waypoint_constraints`), so that curvature is block diagonal, one
``m x m`` block ``B_t`` per free waypoint (a partitioned quasi-Newton model, Griewank &
Toint), and the QP's Hessian keeps its banded structure. After an accepted step each block
gets the BFGS update with ``s_t`` the step of waypoint ``t`` and ``y_t`` the change of its
constraints' part of the Lagrangian gradient, ``y = (J_new - J_old)^T lambda`` at the QP's
multipliers,

.. math::

    B \leftarrow B - \frac{B s s^T B}{s^T B s} + \frac{y y^T}{s^T y},

skipped where ``s^T y <= 1e-8 s^T B s`` (negative curvature along ``s``: the update would
lose positive definiteness; Nocedal & Wright Sec. 18.3). The blocks start at
``initial * I``. (Powell's damping instead of the skip made the door motions' iteration
counts jump with ``initial``: 9 to 53 for a push.) Measured on the door motions (10
waypoints, closed chain at every one): a push in 12 SQP iterations instead of 22, a turn
in 10 instead of 23; from the peer benchmark's stationary guesses over 100 waypoints it
needs more iterations than the cost Hessian alone, so it is an option, which the motion
library turns on.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from door_trajopt.problem import FloatArray

__all__ = ["BlockCurvature", "block_pattern"]

SMALLEST_STEP = 1e-12
"""Blocks whose step is shorter than this (rad, m) are left as they are."""


def block_pattern(n_blocks: int, size: int) -> sp.csr_matrix:
    """Boolean pattern of ``n_blocks`` dense ``size x size`` diagonal blocks."""
    return sp.block_diag([np.ones((size, size), dtype=bool)] * n_blocks, format="csr").astype(bool)


@dataclass
class BlockCurvature:
    """The blocks ``B_t`` (``n_blocks x size x size``) and their updates."""

    blocks: FloatArray

    @classmethod
    def start(cls, n_blocks: int, size: int, initial: float) -> BlockCurvature:
        return cls(np.tile(initial * np.eye(size), (n_blocks, 1, 1)))

    def update(self, step: FloatArray, gradient_change: FloatArray) -> None:
        """BFGS of every block with positive curvature (module docstring), vectorised."""
        n_blocks, size, _ = self.blocks.shape
        s = step.reshape(n_blocks, size)
        y = gradient_change.reshape(n_blocks, size)
        bs = np.einsum("tij,tj->ti", self.blocks, s)
        sbs = np.einsum("ti,ti->t", s, bs)
        sy = np.einsum("ti,ti->t", s, y)
        index = np.flatnonzero((np.linalg.norm(s, axis=1) > SMALLEST_STEP) & (sbs > 0.0) & (sy > 1e-8 * sbs))
        if index.size:
            self.blocks[index] += (np.einsum("ti,tj->tij", y[index], y[index]) / sy[index, None, None]
                                   - np.einsum("ti,tj->tij", bs[index], bs[index]) / sbs[index, None, None])

    def matrix(self) -> sp.csr_matrix:
        """The block-diagonal matrix (free variables, row-major waypoint layout).

        Built straight from the blocks' data: row ``t*size + i`` holds block ``t``'s row
        ``i`` in columns ``t*size .. t*size + size - 1`` (``sp.block_diag`` of the list
        took 0.7 ms per SQP iteration).
        """
        n_blocks, size, _ = self.blocks.shape
        rows = n_blocks * size
        columns = (np.arange(rows) // size * size)[:, None] + np.arange(size)[None, :]
        return sp.csr_matrix((self.blocks.reshape(-1), columns.reshape(-1), np.arange(rows + 1) * size),
                             shape=(rows, rows))
