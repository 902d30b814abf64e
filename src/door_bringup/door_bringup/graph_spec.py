"""The node graph of DESIGN.md (and its proposal markers): which executable of which package runs which node."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["FOXGLOVE_BRIDGE", "GRAPH", "NodeLaunch"]


@dataclass(frozen=True)
class NodeLaunch:
    package: str
    executable: str
    node_name: str
    #: run on /clock (docs/CLOCKS.md): every node but the clock's source and the ones needing no time
    #: (use_sim_time subscribes a node to the 100 Hz /clock)
    use_sim_time: bool = True


GRAPH = (
    NodeLaunch("door_sim_bridge", "sim_bridge", "sim_bridge", use_sim_time=False),  # publishes /clock
    NodeLaunch("door_detection", "door_detector", "door_detector"),
    NodeLaunch("footstep_planner", "footstep_planner", "footstep_planner"),
    NodeLaunch("door_trajopt", "trajectory_optimizer", "trajectory_optimizer"),
    NodeLaunch("door_fsm", "fsm_supervisor", "fsm_supervisor"),
    NodeLaunch("door_viz", "proposal_markers", "proposal_markers", use_sim_time=False),  # needs no time
)

#: The live view (``door_task --foxglove``): not part of the task, so not in GRAPH.
FOXGLOVE_BRIDGE = NodeLaunch("door_viz", "foxglove_bridge", "foxglove_bridge")
