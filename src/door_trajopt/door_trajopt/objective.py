r"""The total cost ``f(xi)`` of a :class:`TrajectoryProblem` on the free vector.

.. math::

    f(\xi) = \underbrace{\tfrac12 \xi^T A \xi + \xi^T b + c}_{\text{[Zucker 2013] (2), [Banerjee 2015] } Q_1}
      + \underbrace{\tfrac12 \sum_t (q_t - q_{nom})^T P (q_t - q_{nom})}_{Q_2}
      + \underbrace{\sum_r \tfrac12 w_r \lVert r(\xi) \rVert^2}_{Q_3}

The first two terms are quadratic with the constant, Kronecker-banded Hessian
``M = A_1 (x) W + I (x) P`` (:mod:`door_trajopt.banded`); the residual terms
are modelled by Gauss-Newton, ``w_r J_r^T J_r``.  Only free waypoints enter the
posture and residual sums' derivatives; fixed waypoints only add constants.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from door_trajopt.banded import KroneckerBandedCholesky
from door_trajopt.constraints import checked_values, free_jacobian, free_pattern
from door_trajopt.problem import FloatArray, ResidualCost, TrajectoryProblem
from door_trajopt.smoothness import SmoothnessMetric

__all__ = ["Objective", "ResidualModel"]


@dataclass(frozen=True)
class ResidualModel:
    """A residual cost linearised at one trajectory: ``r`` and ``J`` (free columns)."""

    weight: float
    residual: FloatArray
    jacobian: sp.csr_matrix


@dataclass(frozen=True)
class Objective:
    """Value, gradient and Hessian pieces of ``f`` for one problem."""

    problem: TrajectoryProblem
    smoothness: SmoothnessMetric
    posture_weights: FloatArray
    posture_nominal: FloatArray

    @classmethod
    def for_problem(cls, problem: TrajectoryProblem) -> Objective:
        """Assemble the smoothness metric and posture weights of ``problem``."""
        if problem.posture is None:
            weights, nominal = np.zeros(problem.n_dof), np.zeros(problem.n_dof)
        else:
            weights, nominal = problem.posture.weights, problem.posture.nominal
        return cls(problem, SmoothnessMetric.for_problem(problem), weights, nominal)

    @property
    def residual_costs(self) -> tuple[ResidualCost, ...]:
        """The problem's least-squares (``Q3``) terms."""
        return self.problem.residual_costs

    def posture_value(self, trajectory: FloatArray) -> float:
        """``1/2 sum_t (q_t - q_nom)^T P (q_t - q_nom)`` over all waypoints."""
        deviation = trajectory - self.posture_nominal
        return 0.5 * float(np.sum(self.posture_weights * deviation**2))

    def residual_value(self, cost: ResidualCost, trajectory: FloatArray) -> float:
        """``1/2 w ||r||^2`` for one residual cost."""
        residual = checked_values(cost.residual(trajectory), cost.size, cost.name)
        return 0.5 * cost.weight * float(residual @ residual)

    def value(self, free: FloatArray) -> float:
        """``f(xi)``."""
        trajectory = self.problem.full_trajectory(free)
        total = self.smoothness.value(free) + self.posture_value(trajectory)
        return total + sum(self.residual_value(c, trajectory) for c in self.residual_costs)

    def quadratic_gradient(self, free: FloatArray) -> FloatArray:
        """Gradient of the smoothness + posture terms, ``M xi + b - p``."""
        waypoints = free.reshape(-1, self.problem.n_dof)
        posture = (waypoints - self.posture_nominal) * self.posture_weights
        return self.smoothness.gradient(free) + posture.reshape(-1)

    def residual_models(self, free: FloatArray) -> tuple[ResidualModel, ...]:
        """Residuals and free-column Jacobians of every ``Q3`` term."""
        trajectory = self.problem.full_trajectory(free)
        columns = self.problem.free_columns
        return tuple(
            ResidualModel(
                c.weight,
                checked_values(c.residual(trajectory), c.size, c.name),
                free_jacobian(c.jacobian(trajectory), c.size, columns, c.name),
            )
            for c in self.residual_costs
        )

    def gradient(self, free: FloatArray) -> FloatArray:
        """``grad f(xi)`` including ``w J^T r`` of the residual terms."""
        gradient = self.quadratic_gradient(free)
        for model in self.residual_models(free):
            gradient = gradient + model.weight * (model.jacobian.T @ model.residual)
        return gradient

    def quadratic_hessian(self) -> sp.csr_matrix:
        """Constant ``M = A_1 (x) W + I (x) P`` (sparse, SPD)."""
        posture = np.tile(self.posture_weights, self.smoothness.n_free)
        return (self.smoothness.hessian() + sp.diags(posture)).tocsr()

    def metric_factor(self) -> KroneckerBandedCholesky:
        """Banded Cholesky factors of ``M`` (computed once per problem)."""
        return KroneckerBandedCholesky.factorize(
            self.smoothness.single_dof_banded(), self.smoothness.weights, self.posture_weights
        )

    def residual_pattern(self) -> sp.csr_matrix:
        """Structural pattern of the stacked residual Jacobians (free columns)."""
        total = self.problem.n_waypoints * self.problem.n_dof
        columns = self.problem.free_columns
        parts = [free_pattern(c.pattern, c.size, total, columns) for c in self.residual_costs]
        if not parts:
            return sp.csr_matrix((0, self.problem.n_variables), dtype=bool)
        return sp.vstack(parts, format="csr")
