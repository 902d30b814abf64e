r"""Zero- and first-order evaluation of a problem at an iterate, shared by both backends.

Also defines the exact :math:`\ell_1` merit function used for step acceptance
(TrajOpt's penalty formulation, Schulman et al.; [Banerjee 2015] Sec. IV adopts it):

.. math::

    \phi_\mu(\xi) = f(\xi) + \mu \Big( \sum_i |h_i(\xi)| + \sum_i \max(g_i(\xi), 0) \Big).

Joint limits are never part of the merit: both backends keep every iterate
inside the joint-limit box. :class:`BackendSolver` is what the two solvers share around their loops
(options, evaluator, the guarded ``solve``).
"""

from __future__ import annotations

import abc
import time
from dataclasses import dataclass
from typing import Generic, TypeVar

import numpy as np
import numpy.typing as npt
import scipy.sparse as sp

from door_trajopt.constraints import ConstraintStack, NonFiniteValueError, Violation, worst_violation
from door_trajopt.objective import Objective
from door_trajopt.problem import ConstraintKind, FloatArray, TrajectoryProblem
from door_trajopt.result import OptimizationResult, Outcome, invalid_guess_reason, invalid_input_result

__all__ = ["BackendSolver", "PointModel", "PointValues", "ProblemEvaluator", "RunSummary", "build_result"]

OptionsT = TypeVar("OptionsT")


@dataclass(frozen=True)
class PointValues:
    """Cost and constraint values at one free vector ``xi``."""

    free: FloatArray
    cost: float
    equality: FloatArray
    inequality: FloatArray

    def infeasibility(self) -> float:
        """``sum |h_i| + sum max(g_i, 0)`` (the penalised part of the merit)."""
        return float(np.sum(np.abs(self.equality)) + np.sum(np.maximum(self.inequality, 0.0)))

    def merit(self, penalty: float) -> float:
        """Exact penalty merit ``phi_mu`` (module docstring)."""
        return self.cost + penalty * self.infeasibility()


@dataclass(frozen=True)
class PointModel:
    """First-order information at a point: ``grad f``, ``H`` and ``G`` (free columns)."""

    values: PointValues
    gradient: FloatArray
    equality_jacobian: sp.csr_matrix
    inequality_jacobian: sp.csr_matrix


@dataclass(frozen=True)
class ProblemEvaluator:
    """Objective and stacked constraints of one problem."""

    problem: TrajectoryProblem
    objective: Objective
    equalities: ConstraintStack
    inequalities: ConstraintStack

    @classmethod
    def for_problem(cls, problem: TrajectoryProblem) -> ProblemEvaluator:
        """Prepare the objective and both constraint stacks."""
        return cls(
            problem,
            Objective.for_problem(problem),
            ConstraintStack.of_kind(problem, ConstraintKind.EQUALITY),
            ConstraintStack.of_kind(problem, ConstraintKind.INEQUALITY),
        )

    def values(self, free: FloatArray) -> PointValues:
        """Evaluate cost, ``h`` and ``g`` at ``free``."""
        trajectory = self.problem.full_trajectory(free)
        trajectory.setflags(write=False)
        return PointValues(
            free=free,
            cost=self.objective.value(free),
            equality=self.equalities.values(trajectory),
            inequality=self.inequalities.values(trajectory),
        )

    def model(self, values: PointValues) -> PointModel:
        """Add the gradient and the constraint Jacobians at ``values.free``."""
        trajectory = self.problem.full_trajectory(values.free)
        trajectory.setflags(write=False)
        return PointModel(
            values=values,
            gradient=self.objective.gradient(values.free),
            equality_jacobian=self.equalities.jacobian(trajectory),
            inequality_jacobian=self.inequalities.jacobian(trajectory),
        )

    def violation(self, values: PointValues) -> Violation:
        """Worst violation (joint limits included) and its constraint name."""
        pairs = ((self.equalities, values.equality), (self.inequalities, values.inequality))
        return worst_violation(self.problem, values.free, pairs)

    def clip_to_limits(self, free: FloatArray) -> FloatArray:
        """Project a free vector onto the joint-limit box."""
        waypoints = free.reshape(self.problem.n_free, self.problem.n_dof)
        clipped = np.clip(waypoints, self.problem.limits.lower, self.problem.limits.upper)
        return clipped.reshape(-1)

    def pinned_variables(self) -> npt.NDArray[np.int64]:
        """Free variables fixed by a structurally single-entry equality row.

        Such a row (e.g. [Zucker 2013]'s "hinge fixed" rows) already pins the variable;
        also treating its joint limit as active would make the active rows
        linearly dependent (singular ``H M^{-1} H^T`` in CHOMP, a degenerate QP
        that OSQP cannot polish), so the backends leave these limits to the
        row and the final clip.
        """
        pattern = self.equalities.pattern()
        single = np.flatnonzero(np.diff(pattern.indptr) == 1)
        return np.unique(pattern.indices[pattern.indptr[single]]).astype(np.int64)

    def lower_bounds(self) -> FloatArray:
        """Joint lower limits tiled over the free waypoints."""
        return np.tile(self.problem.limits.lower, self.problem.n_free)

    def upper_bounds(self) -> FloatArray:
        """Joint upper limits tiled over the free waypoints."""
        return np.tile(self.problem.limits.upper, self.problem.n_free)


@dataclass(frozen=True)
class RunSummary:
    """What a backend loop hands over to build an :class:`OptimizationResult`."""

    values: PointValues
    converged: bool
    iterations: int
    started_at: float
    message: str = ""


def build_result(
    evaluator: ProblemEvaluator, summary: RunSummary, tolerance: float
) -> OptimizationResult:
    """Classify a finished run: SUCCESS, INFEASIBLE or ITERATION_LIMIT."""
    violation = evaluator.violation(summary.values)
    feasible = violation.amount <= tolerance
    if summary.converged:
        outcome = Outcome.SUCCESS if feasible else Outcome.INFEASIBLE
    else:
        outcome = Outcome.ITERATION_LIMIT
    return OptimizationResult(
        trajectory=evaluator.problem.full_trajectory(summary.values.free),
        outcome=outcome,
        cost=summary.values.cost,
        max_violation=violation.amount,
        violated_constraint=None if feasible else violation.name,
        iterations=summary.iterations,
        solve_time_s=time.perf_counter() - summary.started_at,
        message=summary.message,
    )


class BackendSolver(abc.ABC, Generic[OptionsT]):
    """What both backends (:class:`~door_trajopt.sqp.SqpSolver`,
    :class:`~door_trajopt.chomp.ChompSolver`) share: the validated options, the problem's
    evaluator with its joint-limit box and pinned variables, and a :meth:`solve` that checks
    the guess before the backend's own loop (:meth:`_run`) runs."""

    def __init__(self, problem: TrajectoryProblem, options: OptionsT) -> None:
        self._options = options
        self._evaluator = ProblemEvaluator.for_problem(problem)
        self._lower = self._evaluator.lower_bounds()
        self._upper = self._evaluator.upper_bounds()
        self._pinned = self._evaluator.pinned_variables()

    @property
    def options(self) -> OptionsT:
        """The validated options."""
        return self._options

    def solve(self, initial_guess: FloatArray) -> OptimizationResult:
        """Optimise from an ``(n, m)`` guess (projected onto the joint limits).

        Never raises for a bad guess or NaN/inf callback values: those give
        ``Outcome.INVALID_INPUT`` with the reason in ``message``.
        """
        started = time.perf_counter()
        reason = invalid_guess_reason(self._evaluator.problem, initial_guess)
        if reason is not None:
            return invalid_input_result(initial_guess, reason, time.perf_counter() - started)
        try:
            return self._run(np.asarray(initial_guess, dtype=np.float64), started)
        except NonFiniteValueError as error:
            return invalid_input_result(initial_guess, str(error), time.perf_counter() - started)

    @abc.abstractmethod
    def _run(self, guess: FloatArray, started: float) -> OptimizationResult:
        """The backend's loop from a checked guess; ``started`` is the ``perf_counter`` time."""
