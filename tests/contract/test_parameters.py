"""Parameter specs: validation messages, and params/*.yaml equal to the declared defaults."""

import math

import pytest

from door_bringup.graph_spec import FOXGLOVE_BRIDGE, GRAPH
from door_bringup.params_files import SPECS_BY_NODE
from door_contract.errors import ParameterRangeError
from door_contract.parameters import ParameterSpec, defaults, read_params_file, validate_all
from door_contract.ranges import FieldRange

RATE = ParameterSpec("rate", 10.0, "a rate", FieldRange(1.0, 100.0, "Hz"))


def test_every_node_has_a_params_file_equal_to_its_specs(workspace):
    assert set(SPECS_BY_NODE) == {launch.node_name for launch in (*GRAPH, FOXGLOVE_BRIDGE)}
    for node_name, specs in SPECS_BY_NODE.items():
        in_file = read_params_file(workspace.params_file(node_name), node_name)
        assert validate_all(specs, in_file) == defaults(specs), node_name


def test_every_parameter_is_documented():
    for specs in SPECS_BY_NODE.values():
        for spec in specs:
            assert len(spec.description) > 10, spec.name
            assert spec.validate(spec.default) == spec.default


@pytest.mark.parametrize("value", [0.5, 101.0, math.nan, "fast", True])
def test_bad_value_names_parameter_and_range(value):
    with pytest.raises(ParameterRangeError, match=r"'rate'.*\[1, 100\] Hz"):
        RATE.validate(value)


def test_integers_are_accepted_for_floats_but_not_the_reverse():
    assert RATE.validate(20) == 20.0
    frames = ParameterSpec("frames", 10, "frames voted", FieldRange(1, 100, "frames"))
    with pytest.raises(ParameterRangeError, match="an integer"):
        frames.validate(2.5)


def test_choices_and_unknown_names():
    autonomy = ParameterSpec("autonomy", "supervised", "level", choices=("full", "supervised"))
    with pytest.raises(ParameterRangeError, match="one of 'full', 'supervised'"):
        autonomy.validate("yolo")
    with pytest.raises(ParameterRangeError, match="unknown parameter"):
        validate_all([autonomy], {"autonmy": "full"})


def test_an_inverted_range_is_one_clear_error():
    from door_contract.errors import ParameterRangeError
    from door_contract.parameters import require_ordered

    require_ordered({"low": 0.8, "high": 1.0}, "low", "high")
    with pytest.raises(ParameterRangeError, match="'low' must not exceed 'high'"):
        require_ordered({"low": 1.2, "high": 1.0}, "low", "high")
