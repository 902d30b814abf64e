"""Write ``params/<node>.yaml`` from the nodes' parameter specs (the specs are the source).

    python -m door_bringup.params_files          # rewrite every node's params file

A test checks that the files and the specs agree, so run this after changing a spec. The files
are door_bringup's own, ``src/door_bringup/params/<node>.yaml`` (installed in its share);
``params/<node>.yaml`` links to each and is written through, so a new node needs both its file
there and the link (tests check both). The specs also say which nodes take the robot profile
(:func:`robot_nodes`): the main job's ``--robot`` reaches exactly those, and the choices are the
profiles there are (:func:`robot_names`).
"""

from __future__ import annotations

import json
import sys

from door_bringup.workspace import Workspace, repository_root
from door_contract.parameters import ParameterSpec
from door_detection.parameters import DETECTOR_PARAMETERS
from door_fsm.parameters import SUPERVISOR_PARAMETERS
from door_robot.locations import params_dir
from door_sim_bridge.parameters import BRIDGE_PARAMETERS
from door_trajopt.parameters import OPTIMIZER_PARAMETERS
from door_viz.parameters import FOXGLOVE_NODE, FOXGLOVE_PARAMETERS, MARKERS_NODE, MARKERS_PARAMETERS
from footstep_planner.parameters import PLANNER_PARAMETERS

__all__ = ["ROBOT_PARAMETER", "SPECS_BY_NODE", "main", "robot_names", "robot_nodes"]

SPECS_BY_NODE = {
    "sim_bridge": BRIDGE_PARAMETERS,
    "door_detector": DETECTOR_PARAMETERS,
    "footstep_planner": PLANNER_PARAMETERS,
    "trajectory_optimizer": OPTIMIZER_PARAMETERS,
    "fsm_supervisor": SUPERVISOR_PARAMETERS,
    MARKERS_NODE: MARKERS_PARAMETERS,
    FOXGLOVE_NODE: FOXGLOVE_PARAMETERS,
}

ROBOT_PARAMETER = "robot_profile"
"""The parameter naming the robot profile (``params/robot_<name>.yaml``) in every node that needs one."""


def robot_nodes() -> frozenset[str]:
    """The nodes whose specs declare :data:`ROBOT_PARAMETER`: where one robot option must reach."""
    return frozenset(node for node, specs in SPECS_BY_NODE.items()
                     if any(spec.name == ROBOT_PARAMETER for spec in specs))


def robot_names() -> tuple[str, ...]:
    """The robot profiles there are (``robot_<name>.yaml`` in door_robot's profile folder), sorted."""
    return tuple(sorted(path.stem.removeprefix("robot_") for path in params_dir().glob("robot_*.yaml")))


def _yaml_value(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (str, tuple)):
        return json.dumps(list(value) if isinstance(value, tuple) else value)
    return repr(value)


def params_file_text(node_name: str, specs: tuple[ParameterSpec, ...]) -> str:
    lines = [f"# Parameters of /{node_name} (ROS 2 --params-file format), written from the node's",
             "# parameter specs by `python -m door_bringup.params_files`; edit values freely.",
             f"{node_name}:", "  ros__parameters:"]
    for spec in specs:
        entry = f"    {spec.name}: {_yaml_value(spec.default)}"
        lines.append(f"{entry.ljust(44)}  # {spec.allowed()}")
    return "\n".join(lines) + "\n"


def main() -> int:
    workspace = Workspace(repository_root())
    for node_name, specs in SPECS_BY_NODE.items():
        path = workspace.params_file(node_name)
        path.write_text(params_file_text(node_name, specs))
        print(f"wrote {path.resolve()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
