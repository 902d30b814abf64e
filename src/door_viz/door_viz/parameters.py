"""Parameters of the viewer nodes (defaults mirrored in params/<node>.yaml)."""

from door_contract.parameters import ParameterSpec
from door_contract.ranges import FieldRange
from door_contract.topics import Topics

__all__ = ["FOXGLOVE_NODE", "FOXGLOVE_PARAMETERS", "MARKERS_NODE", "MARKERS_PARAMETERS"]

MARKERS_NODE = "proposal_markers"
MARKERS_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml): kinematics of the hand "
                  "paths, sole size of the footsteps"),
)

FOXGLOVE_NODE = "foxglove_bridge"
FOXGLOVE_PARAMETERS = (
    ParameterSpec("address", "127.0.0.1", "interface the WebSocket binds to (0.0.0.0: every interface, "
                  "reachable from other machines)"),
    ParameterSpec("port", 8765, "WebSocket port (0: any free port, logged)", FieldRange(0, 65535, "")),
    ParameterSpec("robot_profile", "talos", "robot profile whose URDF's package:// meshes the bridge serves"),
    ParameterSpec("client_topics", (Topics.OPERATOR.name,), "topics a Foxglove client may publish on "
                  "(std_msgs/String, JSON {\"data\": ...})"),
    ParameterSpec("discovery_period", 0.5, "how often new ROS topics are looked for", FieldRange(0.05, 10.0, "s")),
)
