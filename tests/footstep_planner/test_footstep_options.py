"""FootstepPlannerOptions: defaults are valid; a bad value names its field and range."""

from __future__ import annotations

import math

import pytest

from footstep_planner.errors import FootstepPlannerError
from footstep_planner.options import FootstepPlannerOptions


def test_defaults_describe_talos() -> None:
    options = FootstepPlannerOptions()
    assert options.max_stride == pytest.approx(0.30)
    assert options.nominal_foot_separation == pytest.approx(0.20)
    assert (options.foot_length, options.foot_width) == pytest.approx((0.22, 0.13))
    assert options.body_half_width == pytest.approx(0.38)
    assert options.heuristic_weight == 1.0


@pytest.mark.parametrize("field, value", [
    ("max_stride", 0.0), ("max_stride", -0.1), ("max_stride", 2.0),
    ("max_backward_step", -0.01), ("max_side_step", 0.6), ("max_turn", 2.0),
    ("foot_length", 0.0), ("foot_width", 0.5), ("body_half_width", 0.0),
    ("step_cost", 0.0), ("distance_weight", -1.0), ("heuristic_weight", 0.5),
    ("max_expansions", 0), ("max_planning_time", 0.0), ("goal_position_tolerance", 0.0),
    ("goal_yaw_tolerance", 4.0), ("grid_resolution", 0.0), ("yaw_resolution", 1.0),
    ("search_margin", 0.0), ("max_stride", math.nan), ("max_turn", math.inf), ("body_offset", 0.6),
    ("body_offset", math.nan),
])
def test_out_of_range_value_names_the_field_and_range(field: str, value: float) -> None:
    with pytest.raises(FootstepPlannerError) as caught:
        FootstepPlannerOptions(**{field: value})
    assert caught.value.field == field
    assert field in str(caught.value)
    assert "allowed range" in str(caught.value)


def test_error_is_the_packages_own_not_a_value_error() -> None:
    """The node rejects FootstepPlannerError as bad input; a bug's ValueError must not pass for one."""
    assert not issubclass(FootstepPlannerError, ValueError)
    with pytest.raises(FootstepPlannerError):
        FootstepPlannerOptions(max_stride=-1.0)


@pytest.mark.parametrize("value", [True, "0.3", None])
def test_non_numbers_are_rejected(value: object) -> None:
    with pytest.raises(FootstepPlannerError) as caught:
        FootstepPlannerOptions(max_stride=value)  # type: ignore[arg-type]
    assert caught.value.field == "max_stride"


def test_max_expansions_must_be_an_integer() -> None:
    with pytest.raises(FootstepPlannerError) as caught:
        FootstepPlannerOptions(max_expansions=1000.5)  # type: ignore[arg-type]
    assert caught.value.field == "max_expansions"


def test_min_separation_must_keep_the_soles_apart() -> None:
    with pytest.raises(FootstepPlannerError) as caught:
        FootstepPlannerOptions(min_foot_separation=0.10)  # narrower than a 0.13 m sole
    assert caught.value.field == "min_foot_separation"
    with pytest.raises(FootstepPlannerError):
        FootstepPlannerOptions(min_foot_separation=0.25)  # wider than the nominal stance


def test_options_are_frozen() -> None:
    options = FootstepPlannerOptions()
    with pytest.raises(AttributeError):
        options.max_stride = 0.4  # type: ignore[misc]


def test_snap_to_goal_must_be_a_bool() -> None:
    with pytest.raises(FootstepPlannerError, match="snap_to_goal must be a bool"):
        FootstepPlannerOptions(snap_to_goal="yes")
    assert FootstepPlannerOptions(snap_to_goal=True).snap_to_goal
