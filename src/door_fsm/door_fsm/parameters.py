"""Parameters of the FSM supervisor (defaults mirrored in params/fsm_supervisor.yaml)."""

from door_contract.parameters import ParameterSpec

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
                  "a timeout repeats the state", unit="s", minimum=1.0, maximum=3600.0),
    ParameterSpec("execution_timeout_factor", 2.0, "an execution may take its nominal duration (trajectory "
                  "length, steps × step_duration) times this, plus the margin; robot clock",
                  minimum=1.0, maximum=100.0),
    ParameterSpec("execution_timeout_margin", 10.0, "added to every execution's deadline, robot clock",
                  unit="s", minimum=0.1, maximum=3600.0),
    ParameterSpec("approval_timeout", 300.0, "bound on waiting for the operator, wall clock", unit="s",
                  minimum=1.0, maximum=86400.0),
    ParameterSpec("max_repeats", 3, "automatic repeats of a failed or timed-out state (and hand slips) "
                  "before FAILED", minimum=0, maximum=20),
    ParameterSpec("required_nodes", ("sim_bridge", "door_detector", "footstep_planner", "trajectory_optimizer"),
                  "nodes whose disappearance fails the task (and stops all motion)"),
    ParameterSpec("start_delay", 1.0, "wait before starting the task (lets the graph connect)", unit="s",
                  minimum=0.0, maximum=60.0),
    ParameterSpec("graph_timeout", 30.0, "after start_delay, how long to wait for every required node "
                  "before starting anyway", unit="s", minimum=0.0, maximum=600.0),
)
