"""Parameters of the trajectory optimizer node (defaults mirrored in params/trajectory_optimizer.yaml).

The motion-library defaults are taken from :class:`MotionOptions` and :class:`MotionLibrary`
themselves: the node had kept 16 waypoints after the library moved to 10, and planned
push and ready motions ~3× slower in the graph than in the benchmark.
"""

from door_contract.parameters import ParameterSpec
from door_trajopt.library import MotionLibrary
from door_trajopt.motions import MotionOptions

NODE_NAME = "trajectory_optimizer"
LIBRARY_DEFAULTS = MotionOptions()

OPTIMIZER_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml)"),
    ParameterSpec("backend", "sqp", "default optimiser: TrajOpt-style SQP ([Banerjee 2015]) or constrained "
                  "CHOMP ([Zucker 2013]); a request may choose", choices=("sqp", "chomp")),
    ParameterSpec("waypoints", LIBRARY_DEFAULTS.waypoints, "waypoints per motion", minimum=4, maximum=200),
    ParameterSpec("velocity_scale", MotionLibrary.velocity_scale, "fraction of the URDF joint velocity limits used",
                  minimum=0.01, maximum=1.0),
    ParameterSpec("initial_guesses", MotionLibrary.starts, "initial guesses tried per motion ([Banerjee 2015]: multiple random)",
                  minimum=1, maximum=20),
    ParameterSpec("handle_turn", LIBRARY_DEFAULTS.handle_turn, "handle turn angle ([Banerjee 2015]: ~80°; the sim handle stops at 1.0)",
                  unit="rad", minimum=0.1, maximum=1.0),
    ParameterSpec("push_angle", LIBRARY_DEFAULTS.push_angle, "door angle the arm pushes to; the body pushes it further while "
                  "walking (beyond ~0.3 rad TALOS's forearm meets the latch-side post)", unit="rad",
                  minimum=0.05, maximum=1.5),
    ParameterSpec("pull_angle", LIBRARY_DEFAULTS.pull_angle, "door angle the arm pulls to ([Banerjee 2015]: ~40°; TALOS reaches ~0.35 "
                  "from beside the latch edge, and the other hand blocks the gap)", unit="rad", minimum=0.05, maximum=1.5),
    ParameterSpec("lever_radius", 0.066, "lever axis to grasp point", unit="m", minimum=0.0, maximum=0.2),
    ParameterSpec("state_timeout", 1.0, "joint states / odometry older than this are stale", unit="s",
                  minimum=0.05, maximum=60.0),
)
