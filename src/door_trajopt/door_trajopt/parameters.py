"""Parameters of the trajectory optimizer node (defaults mirrored in params/trajectory_optimizer.yaml)."""

from door_contract.parameters import ParameterSpec

NODE_NAME = "trajectory_optimizer"

OPTIMIZER_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml)"),
    ParameterSpec("backend", "sqp", "optimiser: TrajOpt-style SQP (seed 001) or constrained CHOMP "
                  "(seed 000)", choices=("sqp", "chomp")),
    ParameterSpec("waypoints", 20, "waypoints per motion", minimum=3, maximum=500),
    ParameterSpec("velocity_scale", 0.5, "fraction of the URDF joint velocity limits used",
                  minimum=0.01, maximum=1.0),
)
