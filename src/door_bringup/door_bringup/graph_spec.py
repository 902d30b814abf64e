"""The node graph of DESIGN.md: which executable of which package runs which node."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class NodeLaunch:
    package: str
    executable: str
    node_name: str
    use_sim_time: bool = True  # every node but the clock's source runs on /clock (docs/CLOCKS.md)


GRAPH = (
    NodeLaunch("door_sim_bridge", "sim_bridge", "sim_bridge", use_sim_time=False),  # publishes /clock
    NodeLaunch("door_detection", "door_detector", "door_detector"),
    NodeLaunch("footstep_planner", "footstep_planner", "footstep_planner"),
    NodeLaunch("door_trajopt", "trajectory_optimizer", "trajectory_optimizer"),
    NodeLaunch("door_fsm", "fsm_supervisor", "fsm_supervisor"),
)
