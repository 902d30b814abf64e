"""Validation of options and problem descriptions (``TrajoptError`` naming the field)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp

from door_evaluation.trajopt.toy_problems import door_arc_case, seed000_sized_case
from door_trajopt.chomp import ChompOptions
from door_trajopt.problem import (
    Constraint,
    ConstraintKind,
    JointLimits,
    PostureCost,
    ResidualCost,
    TrajectoryProblem,
    TrajoptError,
)
from door_trajopt.qp_layout import SparsityPattern
from door_trajopt.sqp import SqpOptions


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("step_size", 0.0),
        ("step_size", 1.5),
        ("step_size", float("nan")),
        ("max_iterations", 0),
        ("max_iterations", 2.5),
        ("constraint_tolerance", 0.0),
        ("cost_tolerance", 1.0),
        ("max_backtracks", -1),
        ("active_set_iterations", 0),
        ("armijo", 0.5),
    ],
)
def test_chomp_options_reject_out_of_range(field: str, value: float) -> None:
    with pytest.raises(TrajoptError, match=f"ChompOptions.{field}"):
        ChompOptions(**{field: value})


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("max_iterations", 0),
        ("constraint_tolerance", -1.0),
        ("initial_trust_radius", 0.0),
        ("min_trust_radius", 2.0),
        ("max_trust_radius", 0.01),
        ("trust_shrink", 1.0),
        ("trust_expand", 0.5),
        ("acceptance_ratio", 0.0),
        ("initial_penalty", -3.0),
        ("penalty_margin", 0.5),
        ("penalty_increase", 1.0),
        ("qp_tolerance", 1.0),
        ("slack_curvature", -1.0),
        ("qp_max_iterations", 3),
        ("constraint_handling", "hard"),
    ],
)
def test_sqp_options_reject_out_of_range(field: str, value: object) -> None:
    with pytest.raises(TrajoptError, match=f"SqpOptions.{field}"):
        SqpOptions(**{field: value})


def test_error_message_states_allowed_range() -> None:
    with pytest.raises(TrajoptError, match=r"ChompOptions.step_size = 2.0 is outside the allowed range \(0, 1\]"):
        ChompOptions(step_size=2.0)
    assert not issubclass(TrajoptError, ValueError)


def test_defaults_are_valid() -> None:
    assert ChompOptions().step_size == 1.0
    assert SqpOptions().initial_penalty is None


def problem_with(**changes: object) -> TrajectoryProblem:
    arguments: dict[str, object] = {
        "n_waypoints": 5,
        "start": np.zeros(2),
        "limits": JointLimits(np.full(2, -1.0), np.full(2, 1.0)),
    }
    arguments.update(changes)
    return TrajectoryProblem(**arguments)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("changes", "match"),
    [
        ({"n_waypoints": 1}, "n_waypoints"),
        ({"start": np.array([2.0, 0.0])}, "start waypoint violates"),
        ({"start": np.array([np.nan, 0.0])}, "start"),
        ({"end": np.zeros(3)}, "end"),
        ({"limits": JointLimits.unbounded(3)}, "limits"),
        ({"posture": PostureCost(np.zeros(3), np.ones(3))}, "posture"),
        ({"dof_names": ("a",)}, "dof_names"),
    ],
)
def test_problem_validation(changes: dict[str, object], match: str) -> None:
    with pytest.raises(TrajoptError, match=match):
        problem_with(**changes)


def test_limits_and_costs_validate_their_values() -> None:
    with pytest.raises(TrajoptError):
        JointLimits(np.array([1.0]), np.array([0.0]))
    with pytest.raises(TrajoptError):
        PostureCost(np.zeros(2), np.array([1.0, -1.0]))
    with pytest.raises(TrajoptError, match="weight"):
        ResidualCost("pose", 1, lambda t: np.zeros(1), lambda t: np.zeros((1, 10)), weight=-1.0)


def test_duplicate_constraint_names_are_rejected() -> None:
    block = Constraint(
        "same", ConstraintKind.EQUALITY, 1, lambda t: np.zeros(1), lambda t: np.zeros((1, 10))
    )
    with pytest.raises(TrajoptError, match="unique"):
        problem_with(constraints=(block, block))


def test_constraint_pattern_shape_is_checked() -> None:
    with pytest.raises(TrajoptError, match="pattern"):
        Constraint(
            "bad",
            ConstraintKind.EQUALITY,
            2,
            lambda t: np.zeros(2),
            lambda t: np.zeros((2, 10)),
            pattern=sp.csr_matrix((3, 10)),
        )


def test_jacobian_outside_declared_pattern_is_detected() -> None:
    pattern = SparsityPattern.of(sp.csr_matrix(np.array([[1, 0], [0, 1]], dtype=bool)))
    with pytest.raises(TrajoptError, match="outside"):
        pattern.gather(sp.csr_matrix(np.array([[1.0, 2.0], [0.0, 1.0]])), "test Jacobian")
    values = pattern.gather(sp.csr_matrix(np.array([[3.0, 0.0], [0.0, 4.0]])), "test Jacobian")
    np.testing.assert_allclose(values, [3.0, 4.0])


def test_seed000_sized_problem_matches_paper_size() -> None:
    """[Zucker 2013] Sec. III: n = 104, m = 9, k = 181 (46 + 55 + 80)."""
    problem = seed000_sized_case().problem
    sizes = {c.name: c.size for c in problem.constraints}
    assert problem.n_free == 104 and problem.n_dof == 9
    assert sizes == {"hinge_fixed": 46, "handle_turned": 55, "hand_on_handle": 80}


def test_toy_jacobians_match_finite_differences() -> None:
    for case in (door_arc_case(n_waypoints=6), seed000_sized_case()):
        trajectory = case.initial_guess + 0.01
        for constraint in case.problem.constraints:
            analytic = sp.csr_matrix(constraint.jacobian(trajectory)).toarray()
            columns = np.flatnonzero(np.any(analytic != 0.0, axis=0))[:40]
            for column in columns:
                step = np.zeros(trajectory.size)
                step[column] = 1e-6
                plus = constraint.value(trajectory + step.reshape(trajectory.shape))
                minus = constraint.value(trajectory - step.reshape(trajectory.shape))
                numeric = (plus - minus) / 2e-6
                np.testing.assert_allclose(analytic[:, column], numeric, atol=1e-7)
            assert constraint.pattern is not None
            assert sp.csr_matrix(constraint.jacobian(trajectory)).nnz <= constraint.pattern.nnz


def test_node_parameter_defaults_are_the_libraries_own():
    """The node had kept 16 waypoints after the library moved to 10 (3× slower plans in the graph)."""
    from door_trajopt.library import MotionLibrary
    from door_trajopt.motions import MotionOptions
    from door_trajopt.parameters import OPTIMIZER_PARAMETERS
    defaults = {spec.name: spec.default for spec in OPTIMIZER_PARAMETERS}
    options = MotionOptions()
    assert defaults["waypoints"] == options.waypoints
    assert (defaults["handle_turn"], defaults["push_angle"], defaults["pull_angle"]) == \
        (options.handle_turn, options.push_angle, options.pull_angle)
    assert (defaults["initial_guesses"], defaults["velocity_scale"]) == \
        (MotionLibrary().starts, MotionLibrary().velocity_scale)


@pytest.mark.parametrize("field", ["block_entry", "block_standoff", "head_clearance", "release_retreat",
                                   "door_stop_lateral", "waypoints"])
@pytest.mark.parametrize("value", [-0.01, math.nan, 1000.0])
def test_motion_options_reject_out_of_range(field: str, value: float) -> None:
    from door_trajopt.motions import MotionOptions
    with pytest.raises(TrajoptError, match=f"MotionOptions.{field} = "):
        MotionOptions(**{field: value})
