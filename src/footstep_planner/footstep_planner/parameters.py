"""Parameters of the footstep planner node (defaults mirrored in params/footstep_planner.yaml)."""

from door_contract.parameters import ParameterSpec

NODE_NAME = "footstep_planner"

PLANNER_PARAMETERS = (
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml) giving step limits"),
    ParameterSpec("heuristic_weight", 1.0, "A* heuristic weight; > 1 gives weighted A*",
                  minimum=1.0, maximum=10.0),
    ParameterSpec("max_expansions", 200000, "bound on A* node expansions", minimum=100, maximum=10000000),
    ParameterSpec("max_planning_time", 2.0, "bound on planning time", unit="s", minimum=0.01, maximum=60.0),
)
