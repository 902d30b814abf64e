"""Parameters of the simulation bridge (defaults mirrored in params/sim_bridge.yaml)."""

from door_contract.parameters import ParameterSpec

NODE_NAME = "sim_bridge"

BRIDGE_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml)"),
    ParameterSpec("seed", 0, "random seed of the scene", minimum=0, maximum=2**31 - 1),
    ParameterSpec("physics_rate", 240.0, "physics steps per simulated second", unit="Hz",
                  minimum=60.0, maximum=2000.0),
    ParameterSpec("real_time", True, "pace the simulation to the wall clock (false: as fast as possible)"),
)
