"""Parameters of the FSM supervisor (defaults mirrored in params/fsm_supervisor.yaml)."""

from door_contract.parameters import ParameterSpec
from door_contract.ranges import FieldRange

__all__ = ["NODE_NAME", "SUPERVISOR_PARAMETERS"]

NODE_NAME = "fsm_supervisor"

SUPERVISOR_PARAMETERS = (
    ParameterSpec("autonomy", "supervised", "which transitions wait for the operator (FlexBE-like)",
                  choices=("full", "supervised", "step")),
    ParameterSpec("opening", "push", "how the door opens as seen from the robot", choices=("push", "pull")),
    ParameterSpec("backend", "sqp", "trajectory optimiser backend asked for every motion",
                  choices=("sqp", "chomp")),
    ParameterSpec("robot_profile", "talos", "robot profile (params/robot_<name>.yaml): its arms are the hands "
                  "it grasps with, its step_duration sets how long a footstep plan may take"),
    ParameterSpec("planning_timeout", 60.0, "bound on planning one state (detection included), wall clock; "
                  "a timeout repeats the state", FieldRange(1.0, 3600.0, "s")),
    ParameterSpec("execution_timeout_factor", 2.0, "an execution may take its nominal duration (trajectory "
                  "length, steps × step_duration) times this, plus the margin; robot clock",
                  FieldRange(1.0, 100.0, "")),
    ParameterSpec("execution_timeout_margin", 10.0, "added to every execution's deadline, robot clock",
                  FieldRange(0.1, 3600.0, "s")),
    ParameterSpec("approval_timeout", 300.0, "bound on waiting for the operator, wall clock", FieldRange(1.0, 86400.0, "s")),
    ParameterSpec("max_repeats", 3, "automatic repeats of a failed or timed-out state (and hand slips) "
                  "before FAILED", FieldRange(0, 20, "")),
    ParameterSpec("required_nodes", ("sim_bridge", "door_detector", "footstep_planner", "trajectory_optimizer"),
                  "nodes whose disappearance fails the task (and stops all motion)"),
    ParameterSpec("start_delay", 1.0, "wait before starting the task (lets the graph connect)", FieldRange(0.0, 60.0, "s")),
    ParameterSpec("graph_timeout", 30.0, "after start_delay, how long to wait for every required node "
                  "before starting anyway", FieldRange(0.0, 600.0, "s")),
)
