r"""Constrained CHOMP ([Zucker 2013] Sec. II-B, after Zucker et al.'s CHOMP).

Each iteration minimises the linearised Lagrangian of [Zucker 2013] eq. (4),

.. math::

    \min_\delta\; \delta^T \nabla f(\xi) + \frac{1}{2\alpha} \delta^T M \delta
    \quad\text{s.t.}\quad h(\xi) + H \delta = 0,

whose solution is [Zucker 2013] eq. (5):

.. math::

    \delta = \alpha M^{-1} (H^T Q H M^{-1} - I) \nabla f(\xi) - M^{-1} H^T Q\, h(\xi),
    \qquad Q = (H M^{-1} H^T)^{-1}.

It is evaluated as :math:`y = M^{-1}\nabla f`, :math:`Z = M^{-1} H^T`,
:math:`S = H Z` (``k x k``, dense Cholesky -- the 181 x 181 solve that took
[Zucker 2013] most of its 40 s), multipliers :math:`\lambda = S^{-1}(h/\alpha - H y)`
and :math:`\delta = -\alpha (y + Z\lambda)` -- algebraically identical to
eq. (5), and never forming :math:`M^{-1}`.  The metric ``M`` is [Zucker 2013]'s
``A`` (plus the constant posture Hessian when a posture cost is present),
factorised **once** per problem with banded Cholesky per DOF block
(:mod:`door_trajopt.banded`); least-squares (``Q3``) costs add their
Gauss-Newton term ``w J^T J`` through a Woodbury update of that factor.

Extensions over the seed (which has neither inequalities nor limits):

* joint limits and inequality constraints ``g <= 0`` join ``H`` as active
  rows of a working set (added when a step would cross them, released when
  their multiplier turns negative); iterates are finally clipped to the box;
* steps are accepted on the exact l1 merit (:mod:`door_trajopt.evaluation`,
  penalty ``1.5 max |lambda|``) with Armijo backtracking, after trying a
  cheap second-order correction :math:`-M^{-1} H^T S^{-1} h(\xi + \delta)`
  that reuses the factor of ``S``.

The run stops, as in the seed, when the objective stops decreasing while
``max |h| <= constraint_tolerance``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt
import scipy.sparse as sp
from scipy.linalg import LinAlgError, cho_factor, cho_solve

from door_trajopt.banded import KroneckerBandedCholesky, LowRankUpdatedMetric, MetricSolver
from door_trajopt.evaluation import (
    BackendSolver,
    PointModel,
    PointValues,
    RunSummary,
    build_result,
)
from door_trajopt.problem import FloatArray, TrajectoryProblem
from door_trajopt.result import OptimizationResult
from door_trajopt.validation import FieldRange, at_least, check_ranges

__all__ = ["ActiveSystem", "ChompOptions", "ChompSolver", "ConstrainedStep", "IntArray", "MetricImages", "SparseRows",
           "WorkingSet", "robust_cholesky", "solve_chomp", "stacked_rows", "unit_columns"]

IntArray = npt.NDArray[np.int64]
REGULARISATIONS = (0.0, 1e-12, 1e-9, 1e-6)
"""Relative diagonal shifts tried when ``S = H M^{-1} H^T`` is (near) singular."""


@dataclass(frozen=True)
class ChompOptions:
    """Options of :class:`ChompSolver` ([Zucker 2013] Sec. II-B).

    * ``step_size`` -- ``alpha`` of eq. (4)-(5), dimensionless, ``(0, 1]``;
      ``1`` is the full Newton step of the quadratic part.
    * ``max_iterations`` -- iteration cap, ``>= 1``.
    * ``constraint_tolerance`` -- feasibility threshold on ``max |h_i|`` and
      ``max g_i`` in the constraints' units (m, rad), ``(0, 1]``.
    * ``cost_tolerance`` -- relative objective decrease below which the
      objective has "stopped decreasing", ``[0, 1)``.
    * ``max_backtracks`` -- step halvings per iteration, ``>= 0``.
    * ``active_set_iterations`` -- working-set updates per iteration, ``>= 1``.
    * ``armijo`` -- sufficient-decrease fraction of the merit, ``(0, 0.5)``.
    * ``second_order_correction`` -- try the projection back onto ``h = 0``.
    """

    step_size: float = 1.0
    max_iterations: int = 300
    constraint_tolerance: float = 1e-8
    cost_tolerance: float = 1e-10
    max_backtracks: int = 12
    active_set_iterations: int = 10
    armijo: float = 1e-4
    second_order_correction: bool = True

    def __post_init__(self) -> None:
        check_ranges(self, _CHOMP_RANGES, integers=("max_iterations", "max_backtracks", "active_set_iterations"))


_CHOMP_RANGES = {
    "step_size": FieldRange(0.0, 1.0, "", low_open=True),
    "max_iterations": at_least(1),
    "constraint_tolerance": FieldRange(0.0, 1.0, "", low_open=True),
    "cost_tolerance": FieldRange(0.0, 1.0, "", high_open=True),
    "max_backtracks": at_least(0),
    "active_set_iterations": at_least(1),
    "armijo": FieldRange(0.0, 0.5, "", low_open=True, high_open=True),
}
"""The interval of every numeric :class:`ChompOptions` field."""


@dataclass(frozen=True)
class WorkingSet:
    """Inequality rows and joint-limit variables treated as equalities this step."""

    inequality_rows: IntArray
    upper: IntArray
    lower: IntArray

    def merged(self, other: WorkingSet) -> WorkingSet:
        """Union of two working sets."""
        return WorkingSet(
            np.union1d(self.inequality_rows, other.inequality_rows),
            np.union1d(self.upper, other.upper),
            np.union1d(self.lower, other.lower),
        )

    def without(self, inequality: IntArray, upper: IntArray, lower: IntArray) -> WorkingSet:
        """Working set with the given members released."""
        return WorkingSet(
            np.setdiff1d(self.inequality_rows, inequality),
            np.setdiff1d(self.upper, upper),
            np.setdiff1d(self.lower, lower),
        )

    @property
    def is_empty(self) -> bool:
        """Whether nothing is in the set."""
        return not (self.inequality_rows.size or self.upper.size or self.lower.size)


@dataclass(frozen=True)
class ActiveSystem:
    """Rows ``H_w`` and values ``h_w`` of equalities plus the working set."""

    jacobian: sp.csr_matrix
    values: FloatArray
    working: WorkingSet
    n_equality: int


@dataclass(frozen=True)
class MetricImages:
    """``M^{-1}`` of the gradient and of the rows an active system may hold, at one iterate.

    Every working-set pass of an iteration (3.5 on average for the sideways ready_to_walk)
    needs ``y = M^{-1} grad f`` and ``Z = M^{-1} H_w^T``, and the passes differ only in a few
    inequality and joint-limit rows: each image is solved once per iterate and kept (the
    equality rows' at once, an inequality row's or a limit's the first time it is in the
    working set). A limit row is ``+-e_i``, its image ``+-M^{-1} e_i``.
    """

    metric: MetricSolver
    model: PointModel
    descent: FloatArray
    equality: FloatArray
    inequality: dict[int, FloatArray] = field(default_factory=dict)
    unit: dict[int, FloatArray] = field(default_factory=dict)

    @classmethod
    def at(cls, model: PointModel, metric: MetricSolver) -> MetricImages:
        return cls(metric, model, metric.solve(model.gradient), metric.solve(model.equality_jacobian.T.toarray()))

    def basis(self, working: WorkingSet) -> FloatArray:
        """``Z`` (n x k_w): the columns in the order of :meth:`ChompSolver._active_system`'s rows."""
        n_variables = self.descent.size
        self._solve_missing(self.inequality, working.inequality_rows,
                            lambda rows: stacked_rows([SparseRows.of(self.model.inequality_jacobian, rows)],
                                                      n_variables).T.toarray())
        self._solve_missing(self.unit, np.union1d(working.upper, working.lower),
                            lambda rows: unit_columns(rows, n_variables))
        columns = [self.equality,
                   *(self.inequality[int(row)][:, None] for row in working.inequality_rows),
                   *(self.unit[int(index)][:, None] for index in working.upper),
                   *(-self.unit[int(index)][:, None] for index in working.lower)]
        return np.hstack(columns)

    def _solve_missing(self, images: dict[int, FloatArray], rows: IntArray,
                       transposed_rows: Callable[[IntArray], FloatArray]) -> None:
        missing = np.array([row for row in rows if int(row) not in images], dtype=np.int64)
        if missing.size:
            solved = self.metric.solve(transposed_rows(missing))
            images.update({int(row): solved[:, column] for column, row in enumerate(missing)})


@dataclass(frozen=True)
class ConstrainedStep:
    """Solution of the eq. (4) subproblem: ``delta``, ``lambda`` and reusable factors."""

    step: FloatArray
    multipliers: FloatArray
    schur_factor: tuple[FloatArray, bool] | None
    system: ActiveSystem
    images: MetricImages


def robust_cholesky(schur: FloatArray) -> tuple[FloatArray, bool]:
    """Cholesky of ``S``; shifts the diagonal if ``H`` is rank deficient."""
    scale = max(float(np.mean(np.diag(schur))), np.finfo(float).tiny)
    for shift in REGULARISATIONS:
        try:
            factor: tuple[FloatArray, bool] = cho_factor(schur + shift * scale * np.eye(schur.shape[0]))
            return factor
        except LinAlgError:
            continue
    factor = cho_factor(schur + scale * np.eye(schur.shape[0]))
    return factor


@dataclass(frozen=True)
class SparseRows:
    """Rows to stack into a CSR matrix: their entries (``data``, column ``indices``) row after
    row, and each row's entry count.

    An active system is the equality rows, some inequality rows and some limit rows; built
    as one CSR matrix from these arrays it costs one scipy constructor, where slicing the
    inequality Jacobian, a matrix per limit kind and ``sp.vstack`` cost five (a quarter of a
    sideways ready_to_walk's CHOMP iterations, scipy's format checks mostly).
    """

    data: FloatArray
    indices: IntArray
    lengths: IntArray

    @classmethod
    def of(cls, matrix: sp.csr_matrix, rows: IntArray | None = None) -> SparseRows:
        """Rows ``rows`` (all when ``None``) of a CSR matrix, in that order."""
        if rows is None:
            return cls(matrix.data, matrix.indices.astype(np.int64), np.diff(matrix.indptr).astype(np.int64))
        starts = matrix.indptr[rows].astype(np.int64)
        lengths = matrix.indptr[rows + 1].astype(np.int64) - starts
        first = np.cumsum(lengths) - lengths  # where each row's entries start in the result
        entries = np.repeat(starts - first, lengths) + np.arange(int(lengths.sum()))
        return cls(matrix.data[entries], matrix.indices[entries].astype(np.int64), lengths)

    @classmethod
    def units(cls, indices: IntArray, sign: float) -> SparseRows:
        """Rows ``sign * e_i^T`` for joint-limit variables ``indices``."""
        return cls(np.full(indices.size, sign), np.asarray(indices, dtype=np.int64),
                   np.ones(indices.size, dtype=np.int64))


def unit_columns(indices: IntArray, n_variables: int) -> FloatArray:
    """The columns ``e_i`` (n_variables x len(indices)) of the identity, without building it."""
    columns = np.zeros((n_variables, indices.size))
    columns[indices, np.arange(indices.size)] = 1.0
    return columns


def stacked_rows(parts: list[SparseRows], n_columns: int) -> sp.csr_matrix:
    """One CSR matrix of ``parts``' rows, top to bottom."""
    lengths = np.concatenate([part.lengths for part in parts])
    indptr = np.concatenate([[0], np.cumsum(lengths)])
    return sp.csr_matrix((np.concatenate([part.data for part in parts]),
                          np.concatenate([part.indices for part in parts]), indptr), shape=(lengths.size, n_columns))



class ChompSolver(BackendSolver[ChompOptions]):
    """Constrained CHOMP for one problem; ``M`` is factorised in the constructor."""

    def __init__(self, problem: TrajectoryProblem, options: ChompOptions | None = None) -> None:
        super().__init__(problem, options if options is not None else ChompOptions())
        self._metric: KroneckerBandedCholesky = self._evaluator.objective.metric_factor()

    def _run(self, guess: FloatArray, started: float) -> OptimizationResult:
        evaluator, options = self._evaluator, self._options
        values = evaluator.values(evaluator.clip_to_limits(evaluator.problem.free_vector(guess)))
        penalty, iteration, converged, note = 0.0, 0, False, ""
        while iteration < options.max_iterations and not converged:
            iteration += 1
            model = evaluator.model(values)
            step = self._working_set_step(model, self._iteration_metric(values))
            penalty = self._raised_penalty(penalty, step)
            accepted = self._line_search(model, step, penalty)
            if accepted is None and not (pushed := self._pushed_through(model, step.step)).is_empty:
                step = self._constrained_step(self._active_system(model, step.system.working.merged(pushed)),
                                              step.images)
                penalty = self._raised_penalty(penalty, step)
                accepted = self._line_search(model, step, penalty)
            if accepted is None:
                converged, note = True, self._stall_note(model, step, penalty)
            else:
                converged = self._stopped_decreasing(values, accepted)
                values = accepted
        summary = RunSummary(values, converged, iteration, started, note)
        return build_result(evaluator, summary, options.constraint_tolerance)

    @staticmethod
    def _raised_penalty(penalty: float, step: ConstrainedStep) -> float:
        """The l1 merit's penalty, never lowered: at least 1.5 max |lambda| of ``step``."""
        return max(penalty, 1.5 * float(np.max(np.abs(step.multipliers), initial=0.0)))

    def _stall_note(self, model: PointModel, step: ConstrainedStep, penalty: float) -> str:
        """Empty at a stationary point, else why the line search gave up."""
        if self._merit_slope(model, step, penalty) >= 0.0:
            return ""
        return "stalled: no merit decrease along the constrained CHOMP step"

    def _stopped_decreasing(self, previous: PointValues, current: PointValues) -> bool:
        """[Zucker 2013]'s rule: objective no longer decreasing and ``h`` feasible."""
        decrease = previous.cost - current.cost
        threshold = self._options.cost_tolerance * max(1.0, abs(current.cost))
        feasible = self._evaluator.violation(current).amount <= self._options.constraint_tolerance
        return feasible and decrease <= threshold

    # --- working set --------------------------------------------------------

    def _initial_working_set(self, model: PointModel) -> WorkingSet:
        at_upper, at_lower = self._on_limits(model.values.free)
        return WorkingSet(
            np.flatnonzero(model.values.inequality >= -self._options.constraint_tolerance),
            self._limit_candidates(at_upper),
            self._limit_candidates(at_lower),
        )

    def _on_limits(self, free: FloatArray) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
        """Masks of the variables on (within the constraint tolerance of) their upper and lower limits."""
        tolerance = self._options.constraint_tolerance
        return free >= self._upper - tolerance, free <= self._lower + tolerance

    def _limit_candidates(self, mask: npt.NDArray[np.bool_]) -> IntArray:
        """Variables flagged by ``mask``, except those pinned by an equality row."""
        return np.setdiff1d(np.flatnonzero(mask), self._pinned)

    def _active_system(self, model: PointModel, working: WorkingSet) -> ActiveSystem:
        parts = [SparseRows.of(model.equality_jacobian),
                 SparseRows.of(model.inequality_jacobian, working.inequality_rows),
                 SparseRows.units(working.upper, 1.0), SparseRows.units(working.lower, -1.0)]
        jacobian = stacked_rows(parts, model.values.free.size)
        values = self._active_values(model.values, working)
        return ActiveSystem(jacobian, values, working, model.values.equality.size)

    def _active_values(self, values: PointValues, working: WorkingSet) -> FloatArray:
        """``h_w``: equalities, working inequalities and working joint limits."""
        free = values.free
        return np.concatenate(
            [
                values.equality,
                values.inequality[working.inequality_rows],
                free[working.upper] - self._upper[working.upper],
                self._lower[working.lower] - free[working.lower],
            ]
        )

    def _iteration_metric(self, values: PointValues) -> MetricSolver:
        """``M``, plus the Gauss-Newton term of ``Q3`` residuals via Woodbury."""
        residuals = self._evaluator.objective.residual_models(values.free)
        if not residuals:
            return self._metric
        scaled = [np.sqrt(r.weight) * r.jacobian for r in residuals]
        return LowRankUpdatedMetric.build(self._metric, sp.vstack(scaled, format="csr"))

    def _working_set_step(self, model: PointModel, metric: MetricSolver) -> ConstrainedStep:
        """Solve eq. (5) and update the working set until it is consistent."""
        images = MetricImages.at(model, metric)
        working = self._initial_working_set(model)
        step = self._constrained_step(self._active_system(model, working), images)
        for _ in range(self._options.active_set_iterations - 1):
            updated = self._updated_working_set(model, step)
            if updated is None:
                break
            step = self._constrained_step(self._active_system(model, updated), images)
        return step

    def _updated_working_set(self, model: PointModel, step: ConstrainedStep) -> WorkingSet | None:
        """Release rows with negative multipliers, else add blocking ones."""
        working = step.system.working
        released = self._released(step)
        if released is not None:
            return working.without(*released)
        blocking = self._blocking(model, step.step)
        if blocking.is_empty:
            return None
        return working.merged(blocking)

    def _released(self, step: ConstrainedStep) -> tuple[IntArray, IntArray, IntArray] | None:
        working = step.system.working
        sizes = np.cumsum(
            [step.system.n_equality, working.inequality_rows.size, working.upper.size]
        )
        inequality, upper, lower = np.split(step.multipliers[sizes[0] :], sizes[1:] - sizes[0])
        release = (
            working.inequality_rows[inequality < 0.0],
            working.upper[upper < 0.0],
            working.lower[lower < 0.0],
        )
        return release if any(part.size for part in release) else None

    def _blocking(self, model: PointModel, delta: FloatArray) -> WorkingSet:
        """Inequality rows the step would violate (linearised).

        Joint limits the step would cross are *not* added: the trial point is clipped to
        the box, and a variable left on its limit joins the working set at the next
        iteration (:meth:`_initial_working_set`). Added here, a long first step from a
        far guess put hundreds of limits into ``S`` at once (405 rows on the peer
        benchmark's reach, a dense Cholesky each active-set pass: 3-7x slower than plain
        CHOMP), and limits contradicting the linearised poses made ``S`` nearly singular
        (multipliers of 1e8, a step of 7,000 rad that no line search could use).
        """
        tolerance = self._options.constraint_tolerance
        linearised = model.values.inequality + model.inequality_jacobian @ delta
        empty = np.zeros(0, dtype=np.int64)
        return WorkingSet(np.flatnonzero(linearised > tolerance), empty, empty)

    def _pushed_through(self, model: PointModel, delta: FloatArray) -> WorkingSet:
        """The joint limits a step would push a variable out through that already lies on them.

        Such a variable is clipped at any step length, the rest of the step then no longer
        keeps the equalities, and no backtracking decreases the merit: the sideways push's
        ``ready_to_walk`` stalled so at 68 of 78 doors, on a limit the working set had
        released for its negative multiplier. Used only when the line search found no
        decrease: added at every working-set pass, release and re-adding alternated (4.5x
        the solves), and added after every settled pass they slowed the handle's turn 20x.
        """
        at_upper, at_lower = self._on_limits(model.values.free)
        empty = np.zeros(0, dtype=np.int64)
        return WorkingSet(empty, self._limit_candidates(at_upper & (delta > 0.0)),
                          self._limit_candidates(at_lower & (delta < 0.0)))

    # --- eq. (5) ------------------------------------------------------------

    def _constrained_step(self, system: ActiveSystem, images: MetricImages) -> ConstrainedStep:
        """``delta = -alpha M^{-1} (grad f + H^T lambda)``, i.e. [Zucker 2013] eq. (5)."""
        alpha = self._options.step_size
        descent = images.descent
        if system.values.size == 0:
            return ConstrainedStep(-alpha * descent, np.zeros(0), None, system, images)
        basis = images.basis(system.working)
        factor = robust_cholesky(np.asarray(system.jacobian @ basis))
        rhs = system.values / alpha - system.jacobian @ descent
        multipliers = cho_solve(factor, rhs)
        step = -alpha * (descent + basis @ multipliers)
        return ConstrainedStep(step, multipliers, factor, system, images)

    # --- globalisation --------------------------------------------------------

    def _line_search(
        self, model: PointModel, step: ConstrainedStep, penalty: float
    ) -> PointValues | None:
        """Backtracking on the l1 merit, after a second-order correction attempt."""
        current = model.values
        slope = self._merit_slope(model, step, penalty)
        if slope >= 0.0:
            return None
        reference = current.merit(penalty)
        scale = 1.0
        for attempt in range(self._options.max_backtracks + 1):
            trial = self._trial(current.free + scale * step.step)
            if trial.merit(penalty) <= reference + self._options.armijo * scale * slope:
                return trial
            if attempt == 0 and self._options.second_order_correction:
                corrected = self._corrected_trial(step, trial)
                if corrected.merit(penalty) <= reference + self._options.armijo * slope:
                    return corrected
            scale *= 0.5
        return None

    @staticmethod
    def _merit_slope(model: PointModel, step: ConstrainedStep, penalty: float) -> float:
        """Directional derivative bound ``grad f^T delta - mu (|h|_1 + |g_+|_1)``."""
        return float(model.gradient @ step.step) - penalty * model.values.infeasibility()

    def _trial(self, free: FloatArray) -> PointValues:
        return self._evaluator.values(self._evaluator.clip_to_limits(free))

    def _corrected_trial(self, step: ConstrainedStep, trial: PointValues) -> PointValues:
        active_values = self._active_values(trial, step.system.working)
        return self._trial(trial.free + self._correction(step, active_values))

    def _correction(self, step: ConstrainedStep, active_values: FloatArray) -> FloatArray:
        """Second-order correction ``-M^{-1} H^T S^{-1} h_w(xi + delta)`` (min ``M``-norm)."""
        if step.schur_factor is None:
            return np.zeros_like(step.step)
        weights = cho_solve(step.schur_factor, active_values)
        return -step.images.metric.solve(step.system.jacobian.T @ weights)


def solve_chomp(
    problem: TrajectoryProblem, initial_guess: FloatArray, options: ChompOptions | None = None
) -> OptimizationResult:
    """One-shot constrained CHOMP; build a :class:`ChompSolver` to reuse ``M``'s factor."""
    return ChompSolver(problem, options).solve(initial_guess)
