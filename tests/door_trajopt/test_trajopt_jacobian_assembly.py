"""Waypoint-constraint Jacobians assembled from their entries equal the generic per-block
sparse path, fixed waypoints' columns dropped, and a NaN entry still names its block."""

import numpy as np
import scipy.sparse as sp

from door_trajopt.constraints import ConstraintStack, free_jacobian
from door_trajopt.problem import ConstraintKind, JointLimits, TrajectoryProblem
from door_trajopt.result import Outcome
from door_trajopt.sqp import SqpSolver
from door_trajopt.waypoint_constraints import fixed_dof, waypoint_constraint

N, M = 6, 2


def _curved(bad: bool = False):
    def function(q, need_jacobian):
        value = np.array([q[0] ** 2 + q[1] - 0.5, np.sin(q[1])])
        if not need_jacobian:
            return value, None
        jacobian = np.array([[2.0 * q[0], 1.0], [0.0, np.cos(q[1])]])
        return value, (jacobian * np.nan if bad else jacobian)
    return function


def _problem(bad: bool = False) -> TrajectoryProblem:
    constraints = (waypoint_constraint("curved", ConstraintKind.EQUALITY, _curved(bad), 2, range(1, N), M, N),
                   fixed_dof("pinned", 1, {2: 0.1, 3: 0.1}, M, N))
    return TrajectoryProblem(n_waypoints=N, start=np.zeros(M), end=np.array([0.7, 0.0]),
                             limits=JointLimits.unbounded(M), constraints=constraints)


def test_entries_in_pattern_order_give_the_generic_jacobian_without_the_fixed_end():
    problem = _problem()
    stack = ConstraintStack.of_kind(problem, ConstraintKind.EQUALITY)
    trajectory = np.random.default_rng(2).normal(size=(N, M))
    fast = stack.jacobian(trajectory)
    generic = sp.vstack([free_jacobian(block.jacobian(trajectory), block.size, stack.columns, block.name)
                         for block in stack.blocks], format="csr")
    assert fast.shape == generic.shape == (2 * (N - 1) + 2, (N - 2) * M)
    np.testing.assert_array_equal(fast.toarray(), generic.toarray())


def test_a_nan_jacobian_entry_ends_the_solve_naming_its_block():
    problem = _problem(bad=True)
    guess = problem.linear_interpolation(problem.end)
    result = SqpSolver(problem).solve(guess)
    assert result.outcome is Outcome.INVALID_INPUT and "curved" in result.message
