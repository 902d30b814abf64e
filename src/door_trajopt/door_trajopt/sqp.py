r"""TrajOpt-style sequential quadratic programming with OSQP ([Banerjee 2015] Sec. IV).

[Banerjee 2015] plans with a modified TrajOpt: cost eq. (4) (joint displacement
``Q1``, posture ``Q2``, Cartesian pose error ``Q3``) subject to joint limits,
joint/Cartesian posture equalities and half-plane inequalities, eq. (3).
TrajOpt (Schulman et al.) solves it by SQP on the exact l1 penalty

.. math::

    \phi_\mu(\xi) = f(\xi) + \mu \big(\textstyle\sum |h_i| + \sum \max(g_i, 0)\big):

1. **Convexify** at ``xi``: ``f`` by its gradient and the Hessian ``P``
   (constant smoothness/posture part plus Gauss-Newton ``w J^T J`` of the
   ``Q3`` residuals), constraints by their Jacobians ``H``, ``G``.
2. **QP** (:mod:`door_trajopt.qp_layout`) with slacks for the l1 terms
   (``L1_PENALTY``, TrajOpt) or, the default ``HARD``, the linearised
   constraints as hard rows -- a QP without slack variables, with an elastic
   (l1, slack) re-solve when the linearisation is infeasible inside the box -- and a
   box trust region ``|d_i| <= Delta`` intersected with the joint limits.
   OSQP is set up once per solver and layout with the structural sparsity and
   only ``update``-d afterwards; it warm-starts from the previous solution.
3. **Accept** on the ratio ``rho = (phi(xi) - phi(xi + d)) / (phi(xi) - m(d))``
   of true to model merit decrease: grow ``Delta`` on good steps, shrink it
   on bad ones.
4. **Second-order correction** (Nocedal & Wright Sec. 18.3): when a step
   is rejected, re-solve the QP with the constraint values at the trial
   point, ``h(xi + d) - H d`` replacing ``h(xi)``, which pulls the step back
   onto the curved constraint manifold.  Without it the l1 merit rejects the
   tangential steps along the door arc (the Maratos effect), the trust
   region collapses and plain SQP stalls well above the optimum.  The
   correction is repeated from the corrected step (``max_corrections``)
   while it lowers the merit and the step is not yet acceptable: one left the
   closed chain's error third order in the step, 3.7e-4 m/rad after a
   0.06 rad step of the facing push, which the penalty (40) made a rejection;
   the trust region then cycled 0.016 -> 0.031 -> 0.062 -> rejected for 33
   iterations. With a second one the push takes 10 (116 instead of 150 for
   the benchmark's 13 motions, -16 % over the sideways sweep's doors).
5. **Penalty**: ``mu_0`` from a least-squares multiplier estimate, raised
   to ``penalty_margin * max |lambda_QP|`` whenever the QP meets its
   linearised constraints (a penalty far above the multipliers -- TrajOpt's
   fixed 10 on a problem with small costs -- makes the merit reject every
   tangential step just as the Maratos effect does); when the model cannot
   improve any more but constraints are violated, ``mu`` is multiplied by
   ``penalty_increase``; past ``max_penalty`` the run ends ``INFEASIBLE``.

A run whose trust region collapses before the model converged is reported
with a ``stalled: ...`` message instead of passing silently as converged.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, replace
from types import SimpleNamespace

import numpy as np
import osqp
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from door_trajopt.evaluation import (
    BackendSolver,
    PointModel,
    PointValues,
    RunSummary,
    build_result,
)
from door_trajopt.lagrangian_curvature import BlockCurvature, block_pattern
from door_trajopt.problem import FloatArray, TrajectoryProblem, TrajoptError
from door_trajopt.qp_layout import QpLayout
from door_trajopt.result import OptimizationResult
from door_trajopt.validation import FieldRange, at_least, check_ranges

__all__ = ["ConstraintHandling", "ConstraintShift", "ConvexModel", "QpStep", "SqpOptions", "SqpSolver", "SqpState",
           "StepOutcome", "raise_field", "solve_sqp"]

SOLVED_STATUSES = (
    osqp.SolverStatus.OSQP_SOLVED,
    osqp.SolverStatus.OSQP_SOLVED_INACCURATE,
    osqp.SolverStatus.OSQP_MAX_ITER_REACHED,
)
STAGE_PROGRESS = 1e-3
"""Relative decrease of the linearised violation below which the run is infeasible."""
PINNED_LIMIT_MARGIN = 1e-6
"""Widening (rad, m) of the joint limits of pinned variables in the QP box."""
OSQP_RHO_INTERVAL = 50
"""ADMM iterations between OSQP's step-size (rho) adaptations (what its timing rule picked here)."""
INFEASIBLE_STATUSES = (
    osqp.SolverStatus.OSQP_PRIMAL_INFEASIBLE,
    osqp.SolverStatus.OSQP_PRIMAL_INFEASIBLE_INACCURATE,
)


class ConstraintHandling(enum.Enum):
    """How linearised constraints enter the QP."""

    L1_PENALTY = "l1_penalty"
    """TrajOpt: slack variables, penalty ``mu`` per unit violation."""
    HARD = "hard"
    """Linear constraints inside the trust region (elastic fallback)."""


@dataclass(frozen=True)
class SqpOptions:
    """Options of :class:`SqpSolver` (TrajOpt-style, [Banerjee 2015] Sec. IV).

    Units: trust radii in the DOF units (rad, m) per variable; tolerances in
    the constraints' units; ratios dimensionless.

    * ``constraint_handling`` -- :class:`ConstraintHandling`.
    * ``max_iterations`` -- QP solves (excluding corrections), ``>= 1``.
    * ``constraint_tolerance`` -- feasibility on ``max |h|, max g``, ``(0, 1]``.
    * ``cost_tolerance`` -- relative merit improvement deemed zero, ``[0, 1)``.
    * ``initial_trust_radius`` ``(0, 100]``, ``min_trust_radius`` ``(0, initial]``,
      ``max_trust_radius`` ``[initial, 1000]``.
    * ``trust_shrink`` ``(0, 1)``, ``trust_expand`` ``[1, 10]``.
    * ``acceptance_ratio`` -- minimum ``rho`` to accept, ``(0, 0.5)``.
    * ``initial_penalty`` -- ``mu_0``, ``(0, 1e12]``, or ``None``: ``penalty_margin``
      times the least-squares multiplier estimate at the guess (TrajOpt's
      fixed default of 10 is far too large when costs are small, which makes
      the merit reject every tangential step: the "stall above the optimum").
    * ``penalty_margin`` -- keep ``mu >= margin * ||lambda||_inf`` from the QP
      multipliers whenever the linearised constraints are met, ``[1, 100]``.
    * ``min_penalty`` ``(0, 1]``, ``penalty_increase`` ``(1, 1000]``,
      ``max_penalty`` ``[1, 1e15]``.
    * ``second_order_correction`` -- enable step 4 of the module docstring.
    * ``max_corrections`` -- second-order corrections at most per rejected step, ``>= 1``.
    * ``slack_curvature`` -- ``epsilon`` of :mod:`door_trajopt.qp_layout`, cost per
      squared constraint unit, ``[0, 1e6]``.
    * ``qp_tolerance`` -- OSQP ``eps_abs``/``eps_rel``, ``[1e-14, 1e-2]``; looser
      QP solutions (1e-4) make the trust region collapse on the door arc.
    * ``qp_refine_tolerance`` -- OSQP accuracy of a warm-started re-solve when
      polishing failed (degenerate active set), ``[1e-14, 1e-2]``.
    * ``qp_max_iterations`` -- OSQP iteration cap, ``>= 25``.
    * ``constraint_curvature`` -- add the block-diagonal quasi-Newton curvature of
      the constraints (:mod:`door_trajopt.lagrangian_curvature`) to the QP's
      Hessian; only for problems whose constraints each touch one waypoint.
    * ``initial_curvature`` -- its blocks' start ``B_t = initial * I``, ``(0, 1e3]``.
    """

    constraint_handling: ConstraintHandling = ConstraintHandling.HARD
    max_iterations: int = 300
    constraint_tolerance: float = 1e-8
    cost_tolerance: float = 1e-10
    initial_trust_radius: float = 1.0
    min_trust_radius: float = 1e-8
    max_trust_radius: float = 10.0
    trust_shrink: float = 0.25
    trust_expand: float = 2.0
    acceptance_ratio: float = 0.1
    initial_penalty: float | None = None
    penalty_margin: float = 2.0
    min_penalty: float = 1e-6
    penalty_increase: float = 10.0
    max_penalty: float = 1e9
    second_order_correction: bool = True
    max_corrections: int = 2
    slack_curvature: float = 100.0
    qp_tolerance: float = 1e-6
    qp_refine_tolerance: float = 1e-9
    qp_max_iterations: int = 20000
    constraint_curvature: bool = False
    initial_curvature: float = 1e-2

    def __post_init__(self) -> None:
        if not isinstance(self.constraint_handling, ConstraintHandling):
            raise_field(type(self).__name__, "constraint_handling", "a ConstraintHandling member")
        check_ranges(self, self._ranges(), integers=("max_iterations", "qp_max_iterations", "max_corrections"))

    def _ranges(self) -> dict[str, FieldRange]:
        """Every numeric field's interval, in the order checked (the trust radii's depend on
        ``initial_trust_radius``; ``initial_penalty`` has one only when given)."""
        r = FieldRange
        penalty = {} if self.initial_penalty is None else {"initial_penalty": r(0.0, 1e12, "", low_open=True)}
        return {
            "max_iterations": at_least(1),
            "constraint_tolerance": r(0.0, 1.0, "", low_open=True),
            "cost_tolerance": r(0.0, 1.0, "", high_open=True),
            "initial_trust_radius": r(0.0, 100.0, "", low_open=True),
            "min_trust_radius": r(0.0, self.initial_trust_radius, "", low_open=True),
            "max_trust_radius": r(self.initial_trust_radius, 1000.0, ""),
            "trust_shrink": r(0.0, 1.0, "", low_open=True, high_open=True),
            "trust_expand": r(1.0, 10.0, ""),
            "acceptance_ratio": r(0.0, 0.5, "", low_open=True, high_open=True),
            **penalty,
            "penalty_margin": r(1.0, 100.0, ""),
            "min_penalty": r(0.0, 1.0, "", low_open=True),
            "penalty_increase": r(1.0, 1000.0, "", low_open=True),
            "max_penalty": r(1.0, 1e15, ""),
            "max_corrections": at_least(1),
            "slack_curvature": r(0.0, 1e6, ""),
            "qp_tolerance": r(1e-14, 1e-2, ""),
            "qp_refine_tolerance": r(1e-14, 1e-2, ""),
            "qp_max_iterations": at_least(25),
            "initial_curvature": r(0.0, 1e3, "", low_open=True),
        }


def raise_field(owner: str, field_name: str, expected: str) -> None:
    """Raise :class:`TrajoptError` for a field of the wrong kind."""
    raise TrajoptError(f"{owner}.{field_name} must be {expected}")


@dataclass(frozen=True)
class ConstraintShift:
    """Constant terms of the linearised constraints (``h``, ``g`` or SOC values)."""

    equality: FloatArray
    inequality: FloatArray


@dataclass(frozen=True)
class ConvexModel:
    """The convexified problem at ``xi``: gradient, Hessian and linearisations."""

    point: PointModel
    hessian: sp.csr_matrix

    @property
    def values(self) -> PointValues:
        """Zero-order values at the linearisation point."""
        return self.point.values

    def shift(self) -> ConstraintShift:
        """Return the constraint constants ``h(xi)``, ``g(xi)`` of the plain QP."""
        return ConstraintShift(self.values.equality, self.values.inequality)

    def linearised_violation(self, step: FloatArray, shift: ConstraintShift) -> float:
        """``|h + H d|_1 + |(g + G d)_+|_1``."""
        equality = shift.equality + self.point.equality_jacobian @ step
        inequality = shift.inequality + self.point.inequality_jacobian @ step
        return float(np.sum(np.abs(equality)) + np.sum(np.maximum(inequality, 0.0)))

    def model_merit(self, step: FloatArray, penalty: float, shift: ConstraintShift) -> float:
        """``m(d) = f + g^T d + 1/2 d^T P d + mu (|h + H d|_1 + |(g + G d)_+|_1)``."""
        quadratic = float(self.point.gradient @ step + 0.5 * step @ (self.hessian @ step))
        return self.values.cost + quadratic + penalty * self.linearised_violation(step, shift)


@dataclass(frozen=True)
class QpStep:
    """A QP solution: the step, the largest multiplier and the slack in use."""

    step: FloatArray
    max_multiplier: float
    slack: float
    multipliers: FloatArray | None = None  # of the H and G rows (OSQP's y)

    @classmethod
    def zero(cls, size: int) -> QpStep:
        """Return the null step used when OSQP fails."""
        return cls(np.zeros(size), 0.0, float("inf"))


@dataclass(frozen=True)
class SqpState:
    """Loop state: current point, trust radius, penalty, QP count, stop note."""

    values: PointValues
    trust_radius: float
    penalty: float
    iterations: int
    note: str = ""


@dataclass(frozen=True)
class StepOutcome:
    """What one trust-region trial produced."""

    state: SqpState
    accepted: bool
    predicted: float
    actual: float
    box_limited: bool
    multipliers: FloatArray | None = None


class SqpSolver(BackendSolver[SqpOptions]):
    """TrajOpt-style SQP for one problem; the OSQP workspace persists across solves."""

    def __init__(self, problem: TrajectoryProblem, options: SqpOptions | None = None) -> None:
        super().__init__(problem, options if options is not None else SqpOptions())
        self._quadratic_hessian = self._evaluator.objective.quadratic_hessian()
        self._curvature: BlockCurvature | None = None
        patterns = (
            self._evaluator.equalities.pattern(),
            self._evaluator.inequalities.pattern(),
            self._hessian_pattern(),
        )
        # slack layout for the l1 mode and elastic re-solves; HARD solves without slacks
        self._layouts = {slacks: QpLayout.build(*patterns, slacks=slacks) for slacks in (True, False)}
        self._qps: dict[bool, osqp.OSQP] = {}
        self._loaded: dict[bool, ConvexModel] = {}  # the model whose P and A each workspace holds

    def _hessian_pattern(self) -> sp.csr_matrix:
        residual = self._evaluator.objective.residual_pattern().astype(np.float64)
        gauss_newton = residual.T @ residual
        pattern = abs(self._quadratic_hessian) + abs(gauss_newton)
        if self._options.constraint_curvature:
            problem = self._evaluator.problem
            pattern = pattern + block_pattern(problem.n_free, problem.n_dof).astype(np.float64)
        return pattern.astype(bool).tocsr()

    # --- the loop (BackendSolver.solve checks the guess, then calls it) -----

    def _run(self, guess: FloatArray, started: float) -> OptimizationResult:
        evaluator, options = self._evaluator, self._options
        free = evaluator.clip_to_limits(evaluator.problem.free_vector(guess))
        if options.constraint_curvature:  # every solve starts from the same model
            problem = evaluator.problem
            self._curvature = BlockCurvature.start(problem.n_free, problem.n_dof, options.initial_curvature)
        values = evaluator.values(free)
        penalty = self._initial_penalty(self._convexify(values))
        state = SqpState(values, options.initial_trust_radius, penalty, 0)
        converged = False
        while state.iterations < options.max_iterations and not converged:
            state, converged = self._penalty_iteration(state)
        summary = RunSummary(state.values, converged, state.iterations, started, state.note)
        return build_result(evaluator, summary, options.constraint_tolerance)

    # --- penalty ----------------------------------------------------------------

    def _initial_penalty(self, model: ConvexModel) -> float:
        """``mu_0``: given, or ``margin`` times the multipliers of the first model.

        Estimate: the multipliers of ``min g^T d + 1/2 d^T P d`` s.t. the
        violated/active rows ``h + H d = 0``, i.e. ``S lambda = h - H P^{-1} g``
        with ``S = H P^{-1} H^T`` (the CHOMP formula, [Zucker 2013] eq. (5)).  Unlike
        a gradient-only estimate it is not zero when the guess already minimises
        the cost (a straight-line guess of a pure smoothness cost).
        """
        options = self._options
        if options.initial_penalty is not None:
            return options.initial_penalty
        point = model.point
        active = point.values.inequality >= 0.0
        jacobian = sp.vstack(
            [point.equality_jacobian, point.inequality_jacobian[active]], format="csc"
        )
        if jacobian.shape[0] == 0:
            return options.min_penalty
        values = np.concatenate([point.values.equality, point.values.inequality[active]])
        factor = spla.splu(sp.csc_matrix(model.hessian))
        basis = factor.solve(jacobian.T.toarray())
        schur = np.asarray(jacobian @ basis)
        rhs = values - jacobian @ factor.solve(point.gradient)
        multipliers = np.linalg.lstsq(schur, rhs, rcond=None)[0]
        estimate = options.penalty_margin * float(np.max(np.abs(multipliers)))
        return float(np.clip(estimate, options.min_penalty, options.max_penalty))

    def _steered_penalty(self, penalty: float, qp_step: QpStep) -> float:
        """Keep ``mu >= margin ||lambda||`` when the QP met its linearised constraints."""
        if qp_step.slack > self._options.constraint_tolerance:
            return penalty
        wanted = self._options.penalty_margin * qp_step.max_multiplier
        return float(min(max(penalty, wanted), self._options.max_penalty))

    # --- outer loop: convexify, trust region, penalty -------------------------

    def _penalty_iteration(self, state: SqpState) -> tuple[SqpState, bool]:
        """Trust-region steps at fixed ``mu``; then raise ``mu`` or finish."""
        state, stalled = self._trust_region_loop(state)
        if not stalled:
            return state, False
        if self._feasible(state.values) or self._infeasibility_stationary(state):
            return state, True
        bigger = min(state.penalty * self._options.penalty_increase, self._options.max_penalty)
        radius = max(state.trust_radius, self._options.initial_trust_radius)
        return replace(state, penalty=bigger, trust_radius=radius, note=""), False

    def _infeasibility_stationary(self, state: SqpState) -> bool:
        """Give up: ``mu`` at its cap, or no step can reduce the linearised violation.

        The test solves one feasibility QP (penalty ``max_penalty``, trust
        radius at least the initial one, elastic slacks).  If even its step
        leaves ``|h + H d|_1 + |(g + G d)_+|_1`` at the current violation, the
        point is a stationary point of the violation itself -- the constraints
        contradict each other or the limits -- and raising ``mu`` further
        would only burn iterations.  Otherwise ``mu`` was merely too small.
        """
        options = self._options
        if state.penalty >= options.max_penalty:
            return True
        model = self._convexify(state.values)
        radius = max(state.trust_radius, options.initial_trust_radius)
        probe = replace(state, penalty=options.max_penalty, trust_radius=radius)
        step = self._solve_qp(model, probe, model.shift(), elastic=True).step
        linearised = model.linearised_violation(step, model.shift())
        current = state.values.infeasibility()
        return linearised >= (1.0 - STAGE_PROGRESS) * current

    def _trust_region_loop(self, state: SqpState) -> tuple[SqpState, bool]:
        """Iterate until the model predicts no improvement (``True``) or the cap."""
        options = self._options
        model = self._convexify(state.values)
        while state.iterations < options.max_iterations:
            outcome = self._try_step(model, state)
            state = outcome.state
            floor = self._improvement_floor(state)
            if outcome.predicted <= floor:
                genuine = not outcome.box_limited and outcome.predicted >= -floor
                return (state if genuine else self._collapsed(state)), True
            if outcome.accepted:
                if self._converged_step(outcome, state):
                    return state, True
                model = self._convexify(state.values, model, outcome.multipliers)
            elif state.trust_radius < options.min_trust_radius:
                return self._collapsed(state), True
        return state, False

    @staticmethod
    def _collapsed(state: SqpState) -> SqpState:
        """Stop note: the box (or QP inaccuracy), not optimality, ended the run.

        This is TrajOpt's stall: the merit rejects steps, the box shrinks until
        no predicted decrease is left, and the point looks converged.
        """
        radius = state.trust_radius
        note = f"stalled: trust region collapsed to {radius:.1e} before the model converged"
        return replace(state, note=note)

    def _improvement_floor(self, state: SqpState) -> float:
        merit = state.values.merit(state.penalty)
        return self._options.cost_tolerance * max(1.0, abs(merit))

    def _converged_step(self, outcome: StepOutcome, state: SqpState) -> bool:
        small = outcome.actual <= self._improvement_floor(state)
        return small and self._feasible(state.values)

    def _feasible(self, values: PointValues) -> bool:
        return self._evaluator.violation(values).amount <= self._options.constraint_tolerance

    def _convexify(self, values: PointValues, previous: ConvexModel | None = None,
                   multipliers: FloatArray | None = None) -> ConvexModel:
        """The model at ``values``; with ``constraint_curvature``, after updating the blocks
        from the step ``previous`` → ``values`` at the QP's ``multipliers``."""
        point = self._evaluator.model(values)
        hessian = self._quadratic_hessian
        if self._curvature is not None:
            if previous is not None and multipliers is not None:
                self._update_curvature(self._curvature, previous.point, point, multipliers)
            hessian = hessian + self._curvature.matrix()
        residuals = self._evaluator.objective.residual_models(values.free)
        if not residuals and self._curvature is None:  # the constant Hessian: P needs no update
            return ConvexModel(point, self._quadratic_hessian)
        for residual in residuals:
            hessian = hessian + residual.weight * (residual.jacobian.T @ residual.jacobian)
        return ConvexModel(point, sp.csr_matrix(hessian))

    @staticmethod
    def _update_curvature(curvature: BlockCurvature, old: PointModel, new: PointModel,
                          multipliers: FloatArray) -> None:
        """``y = (J_new − J_old)ᵀ λ`` over the equality and inequality rows."""
        k_eq = old.equality_jacobian.shape[0]
        change = (new.equality_jacobian - old.equality_jacobian).T @ multipliers[:k_eq] + \
            (new.inequality_jacobian - old.inequality_jacobian).T @ multipliers[k_eq:]
        curvature.update(new.values.free - old.values.free, np.asarray(change).reshape(-1))

    # --- one trust-region trial ---------------------------------------------

    def _try_step(self, model: ConvexModel, state: SqpState) -> StepOutcome:
        """Solve the QP, test the ratio, try a second-order correction, adapt Delta."""
        options = self._options
        qp_step = self._solve_qp(model, state, model.shift())
        state = replace(
            state,
            iterations=state.iterations + 1,
            penalty=self._steered_penalty(state.penalty, qp_step),
        )
        reference = model.values.merit(state.penalty)
        predicted = reference - model.model_merit(qp_step.step, state.penalty, model.shift())
        box_limited = float(np.max(np.abs(qp_step.step), initial=0.0)) >= 0.99 * state.trust_radius
        if predicted <= self._improvement_floor(state):
            return StepOutcome(state, False, predicted, 0.0, box_limited, qp_step.multipliers)
        trial = self._trial(model, qp_step.step)
        if reference - trial.merit(state.penalty) < options.acceptance_ratio * predicted:
            trial = self._corrected_trial(model, state, qp_step.step, trial, predicted)
        actual = reference - trial.merit(state.penalty)
        accepted = actual >= options.acceptance_ratio * predicted
        radius = self._next_radius(state.trust_radius, actual / predicted, qp_step.step)
        values = trial if accepted else model.values
        state = replace(state, values=values, trust_radius=radius)
        return StepOutcome(state, accepted, predicted, actual, box_limited, qp_step.multipliers)

    def _trial(self, model: ConvexModel, step: FloatArray) -> PointValues:
        return self._evaluator.values(self._evaluator.clip_to_limits(model.values.free + step))

    def _next_radius(self, radius: float, ratio: float, step: FloatArray) -> float:
        """Shrink on rejection; expand (TrajOpt-style) on good steps at the boundary."""
        options = self._options
        if ratio < options.acceptance_ratio:
            return radius * options.trust_shrink
        at_boundary = float(np.max(np.abs(step), initial=0.0)) >= 0.5 * radius
        if ratio > 0.25 and at_boundary:
            return min(radius * options.trust_expand, options.max_trust_radius)
        return radius

    def _corrected_trial(
        self, model: ConvexModel, state: SqpState, step: FloatArray, trial: PointValues, predicted: float
    ) -> PointValues:
        """Second-order corrections: constants ``h(xi + d) - H d`` (and ``g``) at the last trial
        step ``d``, re-solved up to ``max_corrections`` times while the merit falls and the step
        is not yet acceptable (``predicted``: the model's decrease for ``step``)."""
        options = self._options
        if not options.second_order_correction:
            return trial
        point, reference = model.point, model.values.merit(state.penalty)
        for _ in range(options.max_corrections):
            shift = ConstraintShift(
                trial.equality - point.equality_jacobian @ step,
                trial.inequality - point.inequality_jacobian @ step,
            )
            corrected_step = self._solve_qp(model, state, shift).step
            corrected = self._trial(model, corrected_step)
            if corrected.merit(state.penalty) >= trial.merit(state.penalty):
                break
            step, trial = corrected_step, corrected
            if reference - trial.merit(state.penalty) >= options.acceptance_ratio * predicted:
                break
        return trial

    # --- OSQP -----------------------------------------------------------------

    def _solve_qp(
        self, model: ConvexModel, state: SqpState, shift: ConstraintShift, elastic: bool = False
    ) -> QpStep:
        """Update the persistent OSQP workspace and return the step ``d``.

        HARD mode solves the slack-free QP; only when its linearisation is infeasible
        inside the box is the elastic (slack) QP solved instead.
        """
        slacks = elastic or self._options.constraint_handling is ConstraintHandling.L1_PENALTY
        result = self._polished_solve(self._load(model, state, shift, slacks))
        if not slacks and result.info.status_val in INFEASIBLE_STATUSES:
            slacks = True
            result = self._polished_solve(self._load(model, state, shift, slacks))
        usable = result.info.status_val in SOLVED_STATUSES and np.all(np.isfinite(result.x))
        layout = self._layouts[slacks]
        if not usable:
            return QpStep.zero(layout.n_variables)
        return self._qp_step(result.x, result.y, layout)

    def _polished_solve(self, workspace: osqp.OSQP) -> SimpleNamespace:
        """Solve; if OSQP's polishing failed (degenerate active set), refine ADMM.

        Polishing makes the step exact; without it the ADMM solution is only
        ``qp_tolerance`` accurate, which is too coarse near the optimum (the
        SQP then crawls: a pinned joint sitting on its limit or a weakly
        active bound is enough).  The refinement re-solves, warm-started, at
        ``qp_refine_tolerance``.
        """
        result: SimpleNamespace = workspace.solve(raise_error=False)
        options = self._options
        polished = result.info.status_polish == 1
        if polished or result.info.status_val not in SOLVED_STATUSES:
            return result
        if options.qp_refine_tolerance >= options.qp_tolerance:
            return result
        refine = options.qp_refine_tolerance
        workspace.update_settings(eps_abs=refine, eps_rel=refine)
        refined: SimpleNamespace = workspace.solve(raise_error=False)
        workspace.update_settings(eps_abs=options.qp_tolerance, eps_rel=options.qp_tolerance)
        return refined

    @staticmethod
    def _qp_step(solution: FloatArray, duals: FloatArray, layout: QpLayout) -> QpStep:
        n_rows = layout.n_equality + layout.n_inequality
        multipliers = np.abs(duals[:n_rows])
        slack = np.sum(np.abs(solution[layout.n_variables :]))
        return QpStep(
            np.asarray(solution[: layout.n_variables]),
            float(np.max(multipliers, initial=0.0)),
            float(slack),
            np.array(duals[:n_rows]),
        )

    def _load(
        self, model: ConvexModel, state: SqpState, shift: ConstraintShift, slacks: bool
    ) -> osqp.OSQP:
        """Set OSQP up on first use of a layout; afterwards only ``update`` the values.

        ``P`` and ``A`` belong to the model: the second-order correction and the retries
        after a rejected step solve the same model again with new ``q``, ``l``, ``u``
        only. Those re-solves keep the matrices (and OSQP its KKT factorisation, which
        a matrix update redoes even for unchanged values): two thirds of a push's QPs.
        """
        layout, options = self._layouts[slacks], self._options
        point = model.point
        q = layout.linear_term(point.gradient, state.penalty)
        lower = self._lower_bounds(model, state, shift, layout)
        upper = self._upper_bounds(model, state, shift, layout)
        workspace = self._qps.get(slacks)
        if workspace is None:
            self._qps[slacks] = self._setup(model, q, lower, upper, layout)
            self._loaded[slacks] = model
            return self._qps[slacks]
        changes = {"q": q, "l": lower, "u": upper}
        if self._loaded.get(slacks) is not model:
            changes["Ax"] = layout.a_values(point.equality_jacobian, point.inequality_jacobian)
            if model.hessian is not self._quadratic_hessian:  # Gauss-Newton terms changed P
                changes["Px"] = layout.p_values(model.hessian, options.slack_curvature)
            self._loaded[slacks] = model
        workspace.update(**changes)
        return workspace

    def _setup(
        self, model: ConvexModel, q: FloatArray, lower: FloatArray, upper: FloatArray,
        layout: QpLayout,
    ) -> osqp.OSQP:
        options = self._options
        workspace = osqp.OSQP()
        workspace.setup(
            layout.p_matrix(model.hessian, options.slack_curvature),
            q,
            layout.a_matrix(model.point.equality_jacobian, model.point.inequality_jacobian),
            lower,
            upper,
            verbose=False,
            eps_abs=options.qp_tolerance,
            eps_rel=options.qp_tolerance,
            max_iter=options.qp_max_iterations,
            polishing=True,
            warm_starting=True,
            # OSQP's default (0) sets the interval from the measured set-up time, so its
            # iterates, and the SQP's, could depend on the CPU load; a fixed one cannot
            adaptive_rho_interval=OSQP_RHO_INTERVAL,
        )
        return workspace

    def _step_box(self, model: ConvexModel, state: SqpState) -> tuple[FloatArray, FloatArray]:
        """Trust box ``|d_i| <= Delta`` intersected with the joint limits.

        Variables pinned by an equality row get no trust box (their step is
        fixed by the linear row) and limits widened by ``PINNED_LIMIT_MARGIN``:
        a pin that sits exactly on a limit (hinge fixed at a closed-door stop)
        would otherwise make bound and row active together, a degenerate QP
        that OSQP cannot polish.  A pin beyond a limit is still stopped there.
        """
        free = model.values.free
        radius = state.trust_radius
        lower = np.maximum(-radius, self._lower - free)
        upper = np.minimum(radius, self._upper - free)
        pinned = self._pinned
        lower[pinned] = self._lower[pinned] - free[pinned] - PINNED_LIMIT_MARGIN
        upper[pinned] = self._upper[pinned] - free[pinned] + PINNED_LIMIT_MARGIN
        return lower, upper

    def _lower_bounds(
        self, model: ConvexModel, state: SqpState, shift: ConstraintShift, layout: QpLayout
    ) -> FloatArray:
        step_lower, _ = self._step_box(model, state)
        return np.concatenate(
            [
                -shift.equality,
                np.full(layout.n_inequality, -np.inf),
                step_lower,
                np.zeros(layout.n_slacks),
            ]
        )

    def _upper_bounds(
        self, model: ConvexModel, state: SqpState, shift: ConstraintShift, layout: QpLayout
    ) -> FloatArray:
        _, step_upper = self._step_box(model, state)
        return np.concatenate(
            [-shift.equality, -shift.inequality, step_upper, np.full(layout.n_slacks, np.inf)]
        )


def solve_sqp(
    problem: TrajectoryProblem, initial_guess: FloatArray, options: SqpOptions | None = None
) -> OptimizationResult:
    """One-shot SQP; build an :class:`SqpSolver` to reuse the OSQP set-up."""
    return SqpSolver(problem, options).solve(initial_guess)
