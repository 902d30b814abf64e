"""Parameters of the trajectory optimizer node (defaults mirrored in params/trajectory_optimizer.yaml).

The motion-library defaults are taken from :class:`MotionOptions` and :class:`MotionLibrary`
themselves: the node had kept 16 waypoints after the library moved to 10, and planned
push and ready motions ~3× slower in the graph than in the benchmark. Their ranges are the
options' too (:func:`door_trajopt.motions.option_range`).
"""

from door_contract.parameters import ParameterSpec
from door_contract.ranges import FieldRange
from door_trajopt.library import MotionLibrary
from door_trajopt.motions import MotionOptions, option_range

__all__ = ["NODE_NAME", "OPTIMIZER_PARAMETERS"]

NODE_NAME = "trajectory_optimizer"
LIBRARY_DEFAULTS = MotionOptions()

OPTIMIZER_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml)"),
    ParameterSpec("backend", "sqp", "default optimiser: TrajOpt-style SQP ([Banerjee 2015]) or constrained "
                  "CHOMP ([Zucker 2013]); a request may choose", choices=("sqp", "chomp")),
    ParameterSpec("waypoints", LIBRARY_DEFAULTS.waypoints, "waypoints per motion", option_range("waypoints")),
    ParameterSpec("velocity_scale", MotionLibrary.velocity_scale, "fraction of the URDF joint velocity limits used",
                  FieldRange(0.01, 1.0, "")),
    ParameterSpec("initial_guesses", MotionLibrary.starts, "initial guesses tried per motion ([Banerjee 2015]: multiple random)",
                  FieldRange(1, 20, "")),
    ParameterSpec("handle_turn", LIBRARY_DEFAULTS.handle_turn, "handle turn angle ([Banerjee 2015]: ~80°; the sim handle stops at 1.0)",
                  option_range("handle_turn")),
    ParameterSpec("push_angle", LIBRARY_DEFAULTS.push_angle, "door angle the arm pushes to; the body pushes it further while "
                  "walking (beyond ~0.3 rad TALOS's forearm meets the latch-side post)", option_range("push_angle")),
    ParameterSpec("pull_angle", LIBRARY_DEFAULTS.pull_angle, "door angle the arm pulls to ([Banerjee 2015]: ~40°; TALOS reaches ~0.35 "
                  "from beside the latch edge, and the other hand blocks the gap)", option_range("pull_angle")),
    ParameterSpec("lever_radius", 0.066, "lever axis to grasp point", FieldRange(0.0, 0.2, "m")),
    ParameterSpec("state_timeout", 1.0, "joint states / odometry older than this are stale", FieldRange(0.05, 60.0, "s")),
)
