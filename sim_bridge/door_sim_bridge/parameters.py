"""Parameters of the simulation bridge (defaults mirrored in params/sim_bridge.yaml)."""

from door_contract.parameters import ParameterSpec
from door_contract.ranges import FieldRange

NODE_NAME = "sim_bridge"

BRIDGE_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml)"),
    ParameterSpec("seed", 0, "random seed of the scene (noise, wind phase)", FieldRange(0, 2**31 - 1, "")),
    ParameterSpec("physics_rate", 240.0, "physics steps per simulated second", FieldRange(60.0, 2000.0, "Hz")),
    ParameterSpec("real_time", False, "pace the simulation to the wall clock (false: as fast as possible)"),
    ParameterSpec("state_rate", 50.0, "/joint_states, /odom and /sim/door_joint_states rate (sim time)",
                  FieldRange(1.0, 500.0, "Hz")),
    ParameterSpec("tf_rate", 20.0, "/tf rate (sim time); 0: no /tf", FieldRange(0.0, 500.0, "Hz")),
    ParameterSpec("mesh_uris", "package", "how /robot_description names meshes: package:// (Foxglove via "
                  "the bridge, RViz via the ament index) or file:// (this machine)", choices=("package", "file")),
    ParameterSpec("clock_rate", 100.0, "/clock rate (sim time)", FieldRange(1.0, 1000.0, "Hz")),
    ParameterSpec("camera_rate", 2.0, "head camera frame rate (sim time); 0 disables the camera", FieldRange(0.0, 30.0, "Hz")),
    ParameterSpec("camera_width", 640, "head camera image width", FieldRange(64, 2048, "px")),
    ParameterSpec("camera_height", 480, "head camera image height", FieldRange(48, 2048, "px")),
    ParameterSpec("depth_noise", 0.0, "depth noise σ = k·z² coefficient (stereo-like)", FieldRange(0.0, 0.1, "1/m")),
    ParameterSpec("colour_noise", 0.0, "colour noise σ", FieldRange(0.0, 50.0, "intensity levels")),
    ParameterSpec("door_opening", "push", "how the door opens seen from the robot", choices=("push", "pull")),
    ParameterSpec("hinge_side", "left", "hinge side seen from the robot", choices=("left", "right")),
    ParameterSpec("door_width", 0.914, "door leaf width (DRC: 36 in)", FieldRange(0.6, 1.2, "m")),
    ParameterSpec("handle_height", 0.91, "lever axis above the floor", FieldRange(0.7, 1.2, "m")),
    ParameterSpec("closer_stiffness", 8.0, "door closer spring", FieldRange(0.0, 100.0, "N·m/rad")),
    ParameterSpec("wind_amplitude", 0.0, "wind torque amplitude on the door (0: off)", FieldRange(0.0, 50.0, "N·m")),
    ParameterSpec("grasp_break_force", 200.0, "grasp constraint force beyond which the hand slips",
                  FieldRange(10.0, 5000.0, "N")),
    ParameterSpec("grasp_model", "compliant", "how a closed hand holds the lever: at a point, free to turn "
                  "about it (compliant), or locked in orientation, sliding along the lever (rigid)",
                  choices=("compliant", "rigid")),
    ParameterSpec("stance_distance", 3.0, "robot base to the door plane at the start", FieldRange(0.5, 6.0, "m")),
    ParameterSpec("stance_lateral", 0.0, "robot lateral offset from the doorway centre", FieldRange(-2.0, 2.0, "m")),
    ParameterSpec("supervisor_timeout", 3.0, "stop every execution when the supervisor's heartbeat "
                  "(/diagnostics, 1 Hz) is gone this long, wall clock; 0 disables the dead-man", FieldRange(0.0, 600.0, "s")),
    ParameterSpec("supervisor_node", "fsm_supervisor", "node whose heartbeat the dead-man watches"),
    ParameterSpec("stance_yaw", 0.0, "robot yaw relative to facing the door", FieldRange(-1.0, 1.0, "rad")),
    ParameterSpec("door_colour", (0.55, 0.33, 0.17), "door leaf colour, RGB in [0, 1]"),
    ParameterSpec("frame_colour", (0.92, 0.92, 0.88), "door frame (jambs, header) colour, RGB in [0, 1]"),
    ParameterSpec("handle_colour", (0.85, 0.70, 0.15), "lever handle colour, RGB in [0, 1]"),
    ParameterSpec("wall_colour", (0.45, 0.58, 0.72), "wall colour, RGB in [0, 1]"),
    ParameterSpec("floor_colour", (0.30, 0.30, 0.30), "floor colour, RGB in [0, 1]"),
    ParameterSpec("light_direction", (-50.0, 30.0, 100.0), "towards the directional light, odom axes "
                  "(any non-zero length; default: the renderer's own)"),
)
