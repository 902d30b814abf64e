"""Parameters of the simulation bridge (defaults mirrored in params/sim_bridge.yaml).

Parameters that are fields of the world's configuration take their ranges from it
(:mod:`door_sim_bridge.world_ranges`); ``camera_rate`` keeps its own (0 disables the camera).
"""

from door_contract.parameters import ParameterSpec
from door_contract.ranges import FieldRange
from door_sim_bridge.world_ranges import CAMERA_RANGES, DOOR_RANGES, STANCE_RANGES, WIND_RANGES, WORLD_RANGES

__all__ = ["BRIDGE_PARAMETERS", "NODE_NAME"]

NODE_NAME = "sim_bridge"

BRIDGE_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml)"),
    ParameterSpec("seed", 0, "random seed of the scene (noise, wind phase)", WORLD_RANGES["seed"]),
    ParameterSpec("physics_rate", 240.0, "physics steps per simulated second", WORLD_RANGES["physics_rate"]),
    ParameterSpec("real_time", False, "pace the simulation to the wall clock (false: as fast as possible)"),
    ParameterSpec("state_rate", 50.0, "/joint_states, /odom and /sim/door_joint_states rate (sim time)",
                  FieldRange(1.0, 500.0, "Hz")),
    ParameterSpec("tf_rate", 20.0, "/tf rate (sim time); 0: no /tf", FieldRange(0.0, 500.0, "Hz")),
    ParameterSpec("mesh_uris", "package", "how /robot_description names meshes: package:// (Foxglove via "
                  "the bridge, RViz via the ament index) or file:// (this machine)", choices=("package", "file")),
    ParameterSpec("clock_rate", 100.0, "/clock rate (sim time)", FieldRange(1.0, 1000.0, "Hz")),
    ParameterSpec("camera_rate", 2.0, "head camera frame rate (sim time) while the robot walks; 0 disables the camera",
                  FieldRange(0.0, 30.0, "Hz")),
    ParameterSpec("camera_rate_standing", 8.0, "head camera frame rate (sim time) while the robot does not walk "
                  "(detection works then; rendering costs ~0.14 s of CPU per frame); 0: camera_rate",
                  FieldRange(0.0, 30.0, "Hz")),
    ParameterSpec("camera_width", 640, "head camera image width", CAMERA_RANGES["width"]),
    ParameterSpec("camera_height", 480, "head camera image height", CAMERA_RANGES["height"]),
    ParameterSpec("depth_noise", 0.0, "depth noise σ = k·z² coefficient (stereo-like)", CAMERA_RANGES["depth_noise_coefficient"]),
    ParameterSpec("colour_noise", 0.0, "colour noise σ", CAMERA_RANGES["colour_noise_sigma"]),
    ParameterSpec("door_opening", "push", "how the door opens seen from the robot", choices=("push", "pull")),
    ParameterSpec("hinge_side", "left", "hinge side seen from the robot", choices=("left", "right")),
    ParameterSpec("door_width", 0.914, "door leaf width (DRC: 36 in)", DOOR_RANGES["width"]),
    ParameterSpec("handle_height", 0.91, "lever axis above the floor", DOOR_RANGES["handle_height"]),
    ParameterSpec("closer_stiffness", 8.0, "door closer spring", DOOR_RANGES["closer_stiffness"]),
    ParameterSpec("wind_amplitude", 0.0, "wind torque amplitude on the door (0: off)", WIND_RANGES["amplitude"]),
    ParameterSpec("grasp_break_force", 200.0, "grasp constraint force beyond which the hand slips",
                  WORLD_RANGES["grasp_break_force"]),
    ParameterSpec("grasp_model", "compliant", "how a closed hand holds the lever: at a point, free to turn "
                  "about it (compliant), or locked in orientation, sliding along the lever (rigid)",
                  choices=("compliant", "rigid")),
    ParameterSpec("contact_solver", "sequential_impulse", "PyBullet's constraint solver: iterative "
                  "(sequential_impulse, solver_iterations sweeps) or direct LCP (dantzig)",
                  choices=("sequential_impulse", "dantzig")),
    ParameterSpec("solver_iterations", 50, "sweeps per physics step of the iterative constraint solver",
                  WORLD_RANGES["solver_iterations"]),
    ParameterSpec("stance_distance", 3.0, "robot base to the door plane at the start", STANCE_RANGES["distance"]),
    ParameterSpec("stance_lateral", 0.0, "robot lateral offset from the doorway centre", STANCE_RANGES["lateral_offset"]),
    ParameterSpec("supervisor_timeout", 3.0, "stop every execution when the supervisor's heartbeat "
                  "(/diagnostics, 1 Hz) is gone this long, wall clock; 0 disables the dead-man", FieldRange(0.0, 600.0, "s")),
    ParameterSpec("supervisor_node", "fsm_supervisor", "node whose heartbeat the dead-man watches"),
    ParameterSpec("stance_yaw", 0.0, "robot yaw relative to facing the door", STANCE_RANGES["yaw"]),
    ParameterSpec("door_colour", (0.55, 0.33, 0.17), "door leaf colour, RGB in [0, 1]"),
    ParameterSpec("frame_colour", (0.92, 0.92, 0.88), "door frame (jambs, header) colour, RGB in [0, 1]"),
    ParameterSpec("handle_colour", (0.85, 0.70, 0.15), "lever handle colour, RGB in [0, 1]"),
    ParameterSpec("wall_colour", (0.45, 0.58, 0.72), "wall colour, RGB in [0, 1]"),
    ParameterSpec("floor_colour", (0.30, 0.30, 0.30), "floor colour, RGB in [0, 1]"),
    ParameterSpec("light_direction", (-50.0, 30.0, 100.0), "towards the directional light, odom axes "
                  "(any non-zero length; default: the renderer's own)"),
)
