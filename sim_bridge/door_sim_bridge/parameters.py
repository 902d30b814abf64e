"""Parameters of the simulation bridge (defaults mirrored in params/sim_bridge.yaml)."""

from door_contract.parameters import ParameterSpec

NODE_NAME = "sim_bridge"

BRIDGE_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml)"),
    ParameterSpec("seed", 0, "random seed of the scene (noise, wind phase)", minimum=0, maximum=2**31 - 1),
    ParameterSpec("physics_rate", 240.0, "physics steps per simulated second", unit="Hz",
                  minimum=60.0, maximum=2000.0),
    ParameterSpec("real_time", False, "pace the simulation to the wall clock (false: as fast as possible)"),
    ParameterSpec("state_rate", 50.0, "/joint_states, /odom and /sim/door_joint_states rate (sim time)",
                  unit="Hz", minimum=1.0, maximum=500.0),
    ParameterSpec("tf_rate", 20.0, "/tf rate (sim time); 0: no /tf", unit="Hz", minimum=0.0, maximum=500.0),
    ParameterSpec("mesh_uris", "package", "how /robot_description names meshes: package:// (Foxglove via "
                  "the bridge, RViz via the ament index) or file:// (this machine)", choices=("package", "file")),
    ParameterSpec("clock_rate", 100.0, "/clock rate (sim time)", unit="Hz", minimum=1.0, maximum=1000.0),
    ParameterSpec("camera_rate", 2.0, "head camera frame rate (sim time); 0 disables the camera", unit="Hz",
                  minimum=0.0, maximum=30.0),
    ParameterSpec("camera_width", 640, "head camera image width", unit="px", minimum=64, maximum=2048),
    ParameterSpec("camera_height", 480, "head camera image height", unit="px", minimum=48, maximum=2048),
    ParameterSpec("depth_noise", 0.0, "depth noise σ = k·z² coefficient (stereo-like)", unit="1/m",
                  minimum=0.0, maximum=0.1),
    ParameterSpec("colour_noise", 0.0, "colour noise σ", unit="intensity levels", minimum=0.0, maximum=50.0),
    ParameterSpec("door_opening", "push", "how the door opens seen from the robot", choices=("push", "pull")),
    ParameterSpec("hinge_side", "left", "hinge side seen from the robot", choices=("left", "right")),
    ParameterSpec("door_width", 0.914, "door leaf width (DRC: 36 in)", unit="m", minimum=0.6, maximum=1.2),
    ParameterSpec("handle_height", 0.91, "lever axis above the floor", unit="m", minimum=0.7, maximum=1.2),
    ParameterSpec("closer_stiffness", 8.0, "door closer spring", unit="N·m/rad", minimum=0.0, maximum=100.0),
    ParameterSpec("wind_amplitude", 0.0, "wind torque amplitude on the door (0: off)", unit="N·m",
                  minimum=0.0, maximum=50.0),
    ParameterSpec("grasp_break_force", 200.0, "grasp constraint force beyond which the hand slips",
                  unit="N", minimum=10.0, maximum=5000.0),
    ParameterSpec("grasp_model", "compliant", "how a closed hand holds the lever: at a point, free to turn "
                  "about it (compliant), or locked in orientation, sliding along the lever (rigid)",
                  choices=("compliant", "rigid")),
    ParameterSpec("stance_distance", 3.0, "robot base to the door plane at the start", unit="m",
                  minimum=0.5, maximum=6.0),
    ParameterSpec("stance_lateral", 0.0, "robot lateral offset from the doorway centre", unit="m",
                  minimum=-2.0, maximum=2.0),
    ParameterSpec("supervisor_timeout", 3.0, "stop every execution when the supervisor's heartbeat "
                  "(/diagnostics, 1 Hz) is gone this long, wall clock; 0 disables the dead-man", unit="s",
                  minimum=0.0, maximum=600.0),
    ParameterSpec("supervisor_node", "fsm_supervisor", "node whose heartbeat the dead-man watches"),
    ParameterSpec("stance_yaw", 0.0, "robot yaw relative to facing the door", unit="rad",
                  minimum=-1.0, maximum=1.0),
    ParameterSpec("door_colour", (0.55, 0.33, 0.17), "door leaf colour, RGB in [0, 1]"),
    ParameterSpec("frame_colour", (0.92, 0.92, 0.88), "door frame (jambs, header) colour, RGB in [0, 1]"),
    ParameterSpec("handle_colour", (0.85, 0.70, 0.15), "lever handle colour, RGB in [0, 1]"),
    ParameterSpec("wall_colour", (0.45, 0.58, 0.72), "wall colour, RGB in [0, 1]"),
    ParameterSpec("floor_colour", (0.30, 0.30, 0.30), "floor colour, RGB in [0, 1]"),
    ParameterSpec("light_direction", (-50.0, 30.0, 100.0), "towards the directional light, odom axes "
                  "(any non-zero length; default: the renderer's own)"),
)
