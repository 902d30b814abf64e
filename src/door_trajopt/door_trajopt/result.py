"""Result type shared by the backends, and the checks done before a solve."""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from door_trajopt.problem import START_TOLERANCE, FloatArray, TrajectoryProblem

__all__ = ["OptimizationResult", "Outcome", "invalid_guess_reason", "invalid_input_result"]


class Outcome(enum.Enum):
    """How an optimisation ended."""

    SUCCESS = "success"
    """Converged with every constraint within tolerance."""
    INFEASIBLE = "infeasible"
    """Stopped (converged or stalled) with a constraint still violated."""
    ITERATION_LIMIT = "iteration_limit"
    """Hit the iteration cap; the trajectory is the last iterate."""
    INVALID_INPUT = "invalid_input"
    """The initial guess (or a callback value) was unusable; see ``message``."""


@dataclass(frozen=True)
class OptimizationResult:
    """Outcome of one backend run.

    ``trajectory`` is the full ``(n, m)`` trajectory including the fixed
    waypoints (read-only).  ``max_violation`` is the largest ``|h_i|`` or
    ``max(g_i, 0)`` (joint limits included) and ``violated_constraint`` names
    the constraint block holding it when it exceeds the backend tolerance.
    """

    trajectory: FloatArray
    outcome: Outcome
    cost: float
    max_violation: float
    violated_constraint: str | None
    iterations: int
    solve_time_s: float
    message: str = ""

    def __post_init__(self) -> None:
        trajectory = np.array(self.trajectory, dtype=np.float64)
        trajectory.setflags(write=False)
        object.__setattr__(self, "trajectory", trajectory)

    @property
    def success(self) -> bool:
        """Shorthand for ``outcome is Outcome.SUCCESS``."""
        return self.outcome is Outcome.SUCCESS


def invalid_guess_reason(problem: TrajectoryProblem, guess: FloatArray) -> str | None:
    """Return why ``guess`` cannot start an optimisation, or ``None`` if it can.

    The guess must be an ``(n, m)`` finite array whose fixed waypoints match
    the problem's ``start`` (and ``end``) within :data:`START_TOLERANCE`.
    """
    array = np.asarray(guess)
    expected = (problem.n_waypoints, problem.n_dof)
    if array.shape != expected:
        return f"initial guess has shape {array.shape}, expected {expected}"
    if not np.issubdtype(array.dtype, np.number):
        return f"initial guess has non-numeric dtype {array.dtype}"
    bad = ~np.isfinite(array)
    if bad.any():
        waypoint, dof = np.argwhere(bad)[0]
        return f"initial guess has non-finite value at waypoint {waypoint}, DOF {dof}"
    if np.max(np.abs(array[0] - problem.start)) > START_TOLERANCE:
        return "initial guess waypoint 0 differs from problem.start"
    if problem.end is not None and np.max(np.abs(array[-1] - problem.end)) > START_TOLERANCE:
        return "initial guess last waypoint differs from problem.end"
    return None


def invalid_input_result(guess: object, message: str, solve_time_s: float) -> OptimizationResult:
    """Build an ``INVALID_INPUT`` result echoing the guess (NaN-filled if unusable)."""
    try:
        trajectory = np.array(guess, dtype=np.float64, ndmin=2)
    except (TypeError, ValueError):
        trajectory = np.full((1, 1), np.nan)
    return OptimizationResult(
        trajectory=trajectory,
        outcome=Outcome.INVALID_INPUT,
        cost=float("nan"),
        max_violation=float("nan"),
        violated_constraint=None,
        iterations=0,
        solve_time_s=solve_time_s,
        message=message,
    )
