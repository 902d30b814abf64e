"""``--robot``: one option of the main job reaches every node that takes a robot profile, for
every profile there is (from the graph spec and the nodes' parameter specs; no process starts)."""

from __future__ import annotations

import pytest

from door_bringup.door_task import TaskOptions, parse_options
from door_bringup.graph_spec import FOXGLOVE_BRIDGE, GRAPH
from door_bringup.params_files import ROBOT_PARAMETER, SPECS_BY_NODE, robot_names, robot_nodes
from door_robot.locations import params_dir

PROFILES = ("atlas_v4", "drc_hubo", "g1", "talos")


def test_the_choices_are_the_profiles_there_are():
    assert robot_names() == PROFILES
    assert all((params_dir() / f"robot_{name}.yaml").is_file() for name in PROFILES)


def test_every_node_of_the_graph_takes_a_robot_profile():
    """The graph is robot-agnostic only if no node assumes one (the detector and FSM did)."""
    assert {launch.node_name for launch in (*GRAPH, FOXGLOVE_BRIDGE)} == set(robot_nodes())
    for node in robot_nodes():
        spec = next(spec for spec in SPECS_BY_NODE[node] if spec.name == ROBOT_PARAMETER)
        assert spec.default == "talos", node


@pytest.mark.parametrize("robot", PROFILES)
def test_the_robot_reaches_each_nodes_parameters(robot):
    overrides = TaskOptions(robot=robot, foxglove_port=8765).node_overrides()
    for launch in (*GRAPH, FOXGLOVE_BRIDGE):
        arguments = overrides[launch.node_name]
        given = [arguments[i + 1] for i, word in enumerate(arguments) if word == "-p"]
        assert given.count(f"{ROBOT_PARAMETER}:={robot}") == 1, (launch.node_name, arguments)
        assert not any(value.startswith(f"{ROBOT_PARAMETER}:=") and value != f"{ROBOT_PARAMETER}:={robot}"
                       for value in given)


def test_the_command_line_names_the_robot(request):
    request.getfixturevalue("shared_data")  # atlas_v4's URDF is in ../shared/data
    assert parse_options(["--robot", "atlas_v4"])[0].robot == "atlas_v4"
    assert parse_options([])[0].robot == "talos"


def test_an_unknown_robot_or_one_whose_urdf_is_absent_is_refused_before_anything_starts(monkeypatch, tmp_path,
                                                                                       capsys):
    with pytest.raises(SystemExit) as stop:
        parse_options(["--robot", "nao"])
    assert stop.value.code == 2 and "invalid choice: 'nao'" in capsys.readouterr().err
    monkeypatch.setenv("DOOR_SHARED_DATA", str(tmp_path))  # no ../shared here: Atlas's URDF is missing
    with pytest.raises(SystemExit) as stop:
        parse_options(["--robot", "atlas_v4"])
    assert stop.value.code == 2 and "--robot: robot profile 'atlas_v4': URDF not found" in capsys.readouterr().err
