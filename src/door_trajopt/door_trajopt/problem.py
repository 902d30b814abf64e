"""Backend-agnostic description of a trajectory-optimisation problem.

Both backends (:mod:`door_trajopt.chomp`, after the HUBO+ constrained CHOMP of
[Zucker 2013], and :mod:`door_trajopt.sqp`, after the WPI-CMU TrajOpt set-up of
[Banerjee 2015]) consume the same :class:`TrajectoryProblem`.

Trajectory layout
-----------------
A trajectory is an ``(n, m)`` array: ``n`` waypoints ``q_0 .. q_{n-1}`` of
``m`` degrees of freedom (robot joints *and* door joints such as the hinge and
handle angles, [Zucker 2013] Sec. III).  Wherever a flat vector ``xi`` is used it is
the **row-major** flattening ``xi[t*m + j] = q_t[j]`` (``trajectory.reshape(-1)``),
so waypoint ``t`` occupies the contiguous slice ``xi[t*m:(t+1)*m]``.

Waypoint 0 is always fixed to :attr:`TrajectoryProblem.start`; waypoint
``n-1`` is fixed to :attr:`TrajectoryProblem.end` when it is given ([Zucker 2013]
fixes both endpoints ``q(0)`` and ``q(n+1)``; [Banerjee 2015]'s motions fix only the
start and constrain the end).  The remaining *free* waypoints are contiguous.

Costs ([Banerjee 2015] eq. (4), [Zucker 2013] eq. (2))
-------------------------------------------
``f(xi) = smoothness + posture + sum(residual costs)`` with

* smoothness: the finite-difference metric of :mod:`door_trajopt.smoothness`
  weighted per DOF (the ``Q1`` term of [Banerjee 2015], the ``A`` of [Zucker 2013]);
* posture: ``1/2 sum_t (q_t - q_nom)^T diag(w) (q_t - q_nom)`` (``Q2``);
* residual costs: ``1/2 w ||r(xi)||^2`` for a residual ``r`` with Jacobian,
  e.g. a Cartesian pose error ``d_Delta`` (``Q3``, [Banerjee 2015] eq. (5)).

Constraints
-----------
Equality constraints ``h(xi) = 0`` and inequality constraints ``g(xi) <= 0``,
each a named block of rows with value and Jacobian callbacks.  Jacobians are
taken with respect to the *full* flattened trajectory (``n*m`` columns, the
fixed waypoints' columns are ignored by the backends) and may be dense arrays
or scipy sparse matrices.  A structural sparsity ``pattern`` lets the SQP
backend set up OSQP once with a fixed sparsity (every non-zero the callback
may ever return must lie inside it).  Joint limits are kept apart as a box.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Protocol, TypeAlias

import numpy as np
import numpy.typing as npt
import scipy.sparse as sp

__all__ = ["START_TOLERANCE", "Constraint", "ConstraintKind", "Derivative", "FloatArray", "JacobianValue",
           "JointLimits", "PostureCost", "ResidualCost", "SmoothnessSpec", "TrajectoryFunction", "TrajectoryJacobian",
           "TrajectoryProblem", "TrajoptError", "as_float_vector"]

FloatArray: TypeAlias = npt.NDArray[np.float64]
JacobianValue: TypeAlias = "FloatArray | sp.spmatrix | sp.sparray"

START_TOLERANCE = 1e-6
"""Largest allowed mismatch (rad or m) between a guess and a fixed waypoint."""


class TrajoptError(Exception):
    """Invalid problem description or invalid solver options: the package's one base error.

    Not a :class:`ValueError`, so a bug's ``ValueError`` is never taken for a refused
    problem. The bad input of a request is the subclass
    :class:`~door_trajopt.motions.DoorStateOutOfRange`, which the node reports as REJECTED;
    any other error of a plan is a FAILURE ("internal error")."""


class ConstraintKind(enum.Enum):
    """Whether a constraint block means ``h(xi) = 0`` or ``g(xi) <= 0``."""

    EQUALITY = "equality"
    INEQUALITY = "inequality"


class TrajectoryFunction(Protocol):
    """Value callback: full ``(n, m)`` trajectory -> ``(k,)`` vector."""

    def __call__(self, trajectory: FloatArray) -> FloatArray:
        """Evaluate the function on a read-only ``(n, m)`` trajectory."""
        ...


class TrajectoryJacobian(Protocol):
    """Jacobian callback: full ``(n, m)`` trajectory -> ``(k, n*m)`` matrix.

    Columns follow the row-major flattening of the trajectory.  A dense
    ``ndarray`` or any scipy sparse matrix/array is accepted.
    """

    def __call__(self, trajectory: FloatArray) -> JacobianValue:
        """Evaluate the Jacobian on a read-only ``(n, m)`` trajectory."""
        ...


def as_float_vector(values: npt.ArrayLike, size: int, what: str) -> FloatArray:
    """Return ``values`` as a read-only float vector of length ``size``."""
    vector = np.array(values, dtype=np.float64).reshape(-1)
    if vector.shape != (size,):
        raise TrajoptError(f"{what} must have {size} entries, got {vector.size}")
    vector.setflags(write=False)
    return vector


def _validated_pattern(
    pattern: sp.spmatrix | sp.sparray | None, rows: int, what: str
) -> sp.csr_matrix | None:
    """Check a structural Jacobian pattern and return it as boolean CSR."""
    if pattern is None:
        return None
    matrix = sp.csr_matrix(pattern, dtype=bool)
    if matrix.shape[0] != rows:
        raise TrajoptError(f"{what}: pattern has {matrix.shape[0]} rows, expected {rows}")
    matrix.eliminate_zeros()
    return matrix


@dataclass(frozen=True)
class Constraint:
    """A named block of ``size`` equality or inequality rows.

    ``value(trajectory)`` returns ``h`` (or ``g``) with shape ``(size,)`` and
    ``jacobian(trajectory)`` its ``(size, n*m)`` derivative.  ``pattern`` is
    the structural non-zero pattern of the Jacobian (``None``: dense).
    ``jacobian_data`` (optional, with a pattern) returns the Jacobian's values
    in the order of the pattern's CSR entries, so that the backends can
    assemble the stacked Jacobian without building a sparse matrix per block.
    """

    name: str
    kind: ConstraintKind
    size: int
    value: TrajectoryFunction
    jacobian: TrajectoryJacobian
    pattern: sp.csr_matrix | None = None
    jacobian_data: TrajectoryFunction | None = None

    def __post_init__(self) -> None:
        if not self.name:
            raise TrajoptError("Constraint.name must be a non-empty string")
        if self.size < 1:
            raise TrajoptError(f"Constraint {self.name!r}: size must be >= 1, got {self.size}")
        checked = _validated_pattern(self.pattern, self.size, f"Constraint {self.name!r}")
        object.__setattr__(self, "pattern", checked)
        if self.jacobian_data is not None and checked is None:
            raise TrajoptError(f"Constraint {self.name!r}: jacobian_data needs a pattern")


@dataclass(frozen=True)
class ResidualCost:
    """Least-squares cost ``1/2 * weight * ||r(xi)||^2`` ([Banerjee 2015] ``Q3``).

    ``residual`` returns ``r`` (e.g. the masked pose error ``d_Delta`` of
    [Banerjee 2015] eq. (5) stacked over waypoints) and ``jacobian`` its derivative.
    The backends use the Gauss-Newton Hessian ``weight * J^T J``.
    """

    name: str
    size: int
    residual: TrajectoryFunction
    jacobian: TrajectoryJacobian
    weight: float = 1.0
    pattern: sp.csr_matrix | None = None

    def __post_init__(self) -> None:
        if self.size < 1:
            raise TrajoptError(f"ResidualCost {self.name!r}: size must be >= 1")
        if not (np.isfinite(self.weight) and self.weight >= 0.0):
            raise TrajoptError(f"ResidualCost {self.name!r}: weight must be finite and >= 0")
        checked = _validated_pattern(self.pattern, self.size, f"ResidualCost {self.name!r}")
        object.__setattr__(self, "pattern", checked)


@dataclass(frozen=True)
class JointLimits:
    """Per-DOF box ``lower <= q_t <= upper`` (rad or m; ``+-inf`` allowed)."""

    lower: FloatArray
    upper: FloatArray

    def __post_init__(self) -> None:
        lower = np.array(self.lower, dtype=np.float64).reshape(-1)
        upper = np.array(self.upper, dtype=np.float64).reshape(-1)
        if lower.shape != upper.shape:
            raise TrajoptError("JointLimits.lower and .upper must have the same length")
        if np.isnan(lower).any() or np.isnan(upper).any() or np.any(lower > upper):
            raise TrajoptError("JointLimits need lower <= upper and no NaN")
        object.__setattr__(self, "lower", as_float_vector(lower, lower.size, "lower"))
        object.__setattr__(self, "upper", as_float_vector(upper, upper.size, "upper"))

    @classmethod
    def unbounded(cls, n_dof: int) -> JointLimits:
        """Limits of ``+-inf`` for ``n_dof`` DOF."""
        return cls(np.full(n_dof, -np.inf), np.full(n_dof, np.inf))

    @property
    def n_dof(self) -> int:
        """Number of degrees of freedom."""
        return int(self.lower.size)


@dataclass(frozen=True)
class PostureCost:
    """``1/2 sum_t (q_t - nominal)^T diag(weights) (q_t - nominal)`` (``Q2``)."""

    nominal: FloatArray
    weights: FloatArray

    def __post_init__(self) -> None:
        nominal = np.array(self.nominal, dtype=np.float64).reshape(-1)
        object.__setattr__(self, "nominal", as_float_vector(nominal, nominal.size, "nominal"))
        weights = as_float_vector(self.weights, nominal.size, "PostureCost.weights")
        if not np.all(np.isfinite(weights) & (weights >= 0.0)):
            raise TrajoptError("PostureCost.weights must be finite and >= 0")
        object.__setattr__(self, "weights", weights)


class Derivative(enum.Enum):
    """Which finite difference the smoothness metric penalises ([Zucker 2013] eq. (1))."""

    VELOCITY = 1
    """First differences ``q_t - q_{t-1}``: [Banerjee 2015]'s joint displacement ``Q1``."""
    ACCELERATION = 2
    """Second differences ``q_{t-1} - 2 q_t + q_{t+1}``: [Zucker 2013] Sec. II-A."""


@dataclass(frozen=True)
class SmoothnessSpec:
    """Finite-difference smoothness metric (see :mod:`door_trajopt.smoothness`).

    ``weights`` (length ``m``, ``None``: ones) scale each DOF's term, i.e.
    ``Q1 = diag(weights)``.  ``at_rest`` adds ghost waypoints ``q_{-1} = q_0``
    and ``q_n = q_{n-1}`` so accelerations at both ends are penalised too (the
    robot starts and stops at rest); without it the metric is [Zucker 2013]'s
    interior-only ``K``, which is positive definite only with a fixed end.
    """

    derivative: Derivative = Derivative.ACCELERATION
    at_rest: bool = True
    weights: FloatArray | None = None


@dataclass(frozen=True)
class TrajectoryProblem:
    """Everything a backend needs; see the module docstring for conventions.

    ``smoothness`` selects the finite-difference metric and its per-DOF
    weights (the ``A`` of [Zucker 2013] eq. (2), the ``Q1`` of [Banerjee 2015] eq. (4)).
    """

    n_waypoints: int
    start: FloatArray
    limits: JointLimits
    end: FloatArray | None = None
    smoothness: SmoothnessSpec = field(default_factory=SmoothnessSpec)
    posture: PostureCost | None = None
    residual_costs: tuple[ResidualCost, ...] = ()
    constraints: tuple[Constraint, ...] = ()
    dof_names: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        start = np.array(self.start, dtype=np.float64).reshape(-1)
        n_dof = start.size
        object.__setattr__(self, "start", as_float_vector(start, n_dof, "start"))
        self._check_sizes(n_dof)
        if self.end is not None:
            object.__setattr__(self, "end", as_float_vector(self.end, n_dof, "end"))
        object.__setattr__(self, "smoothness", self._checked_smoothness(n_dof))
        object.__setattr__(self, "residual_costs", tuple(self.residual_costs))
        object.__setattr__(self, "constraints", tuple(self.constraints))
        self._check_fixed_waypoints()
        self._check_names()

    def _check_sizes(self, n_dof: int) -> None:
        minimum = 3 if self.end is not None else 2
        if self.n_waypoints < minimum:
            raise TrajoptError(f"n_waypoints must be >= {minimum}, got {self.n_waypoints}")
        if self.limits.n_dof != n_dof:
            raise TrajoptError(f"limits have {self.limits.n_dof} DOF, start has {n_dof}")
        if self.posture is not None and self.posture.nominal.size != n_dof:
            raise TrajoptError("posture.nominal must have one entry per DOF")
        if self.dof_names and len(self.dof_names) != n_dof:
            raise TrajoptError("dof_names must be empty or have one name per DOF")

    def _checked_smoothness(self, n_dof: int) -> SmoothnessSpec:
        spec = self.smoothness
        raw = np.ones(n_dof) if spec.weights is None else spec.weights
        weights = as_float_vector(raw, n_dof, "smoothness.weights")
        if not np.all(np.isfinite(weights) & (weights > 0.0)):
            raise TrajoptError("smoothness.weights must be finite and > 0 (A must stay SPD)")
        needs_end = spec.derivative is Derivative.ACCELERATION and not spec.at_rest
        if needs_end and self.end is None:
            raise TrajoptError(
                "smoothness.at_rest=False with accelerations needs a fixed end waypoint "
                "(otherwise A = K^T K is singular, [Zucker 2013] Sec. II-A)"
            )
        return SmoothnessSpec(spec.derivative, spec.at_rest, weights)

    @property
    def smoothness_weights(self) -> FloatArray:
        """Per-DOF smoothness weights ``diag(Q1)`` (validated, length ``m``)."""
        assert self.smoothness.weights is not None
        return self.smoothness.weights

    def _check_fixed_waypoints(self) -> None:
        for label, q in (("start", self.start), ("end", self.end)):
            if q is None:
                continue
            if not np.all(np.isfinite(q)):
                raise TrajoptError(f"{label} waypoint must be finite")
            if np.any(q < self.limits.lower) or np.any(q > self.limits.upper):
                raise TrajoptError(f"{label} waypoint violates the joint limits")

    def _check_names(self) -> None:
        names = [c.name for c in self.constraints]
        if len(set(names)) != len(names):
            raise TrajoptError(f"constraint names must be unique, got {names}")

    @property
    def n_dof(self) -> int:
        """``m``: degrees of freedom per waypoint."""
        return int(self.start.size)

    @property
    def first_free(self) -> int:
        """Index of the first free waypoint (always 1)."""
        return 1

    @property
    def end_fixed(self) -> bool:
        """Whether the last waypoint is fixed to :attr:`end`."""
        return self.end is not None

    @property
    def n_free(self) -> int:
        """Number of free (optimised) waypoints."""
        return self.n_waypoints - 1 - int(self.end_fixed)

    @property
    def n_variables(self) -> int:
        """Length of the free vector ``xi`` (``n_free * m``)."""
        return self.n_free * self.n_dof

    @property
    def free_columns(self) -> slice:
        """Columns of the full flattened trajectory that are optimised."""
        return slice(self.first_free * self.n_dof, (self.first_free + self.n_free) * self.n_dof)

    def constraints_of(self, kind: ConstraintKind) -> tuple[Constraint, ...]:
        """Return the constraint blocks of one kind, in declaration order."""
        return tuple(c for c in self.constraints if c.kind is kind)

    def full_trajectory(self, free: FloatArray) -> FloatArray:
        """Assemble the ``(n, m)`` trajectory from the free flat vector."""
        trajectory = np.empty((self.n_waypoints, self.n_dof))
        trajectory[0] = self.start
        trajectory[1 : 1 + self.n_free] = free.reshape(self.n_free, self.n_dof)
        if self.end is not None:
            trajectory[-1] = self.end
        return trajectory

    def free_vector(self, trajectory: FloatArray) -> FloatArray:
        """Row-major flat vector of the free waypoints of a full trajectory."""
        return np.array(trajectory[1 : 1 + self.n_free], dtype=np.float64).reshape(-1)

    def linear_interpolation(self, goal: FloatArray) -> FloatArray:
        """Straight line in configuration space from ``start`` to ``goal``.

        The default initial guess of both papers ([Banerjee 2015] Sec. IV, the
        key-pose interpolation of [Zucker 2013] Sec. III with two key poses).
        """
        goal_vector = as_float_vector(goal, self.n_dof, "goal")
        ratio = np.linspace(0.0, 1.0, self.n_waypoints)[:, None]
        return (1.0 - ratio) * self.start[None, :] + ratio * goal_vector[None, :]
