"""Parameters of the FSM supervisor (defaults mirrored in params/fsm_supervisor.yaml)."""

from door_contract.parameters import ParameterSpec

NODE_NAME = "fsm_supervisor"

SUPERVISOR_PARAMETERS = (
    ParameterSpec("autonomy", "supervised", "which transitions wait for the operator (FlexBE-like)",
                  choices=("full", "supervised", "step")),
    ParameterSpec("state_timeout", 60.0, "timeout of every state", unit="s", minimum=1.0, maximum=3600.0),
    ParameterSpec("max_repeats", 3, "repeats of a failed sub-state before FAILED", minimum=0, maximum=20),
)
