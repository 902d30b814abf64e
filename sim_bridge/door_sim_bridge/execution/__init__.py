"""Incremental execution of joint trajectories and footstep plans on a :class:`DoorWorld`."""

from door_sim_bridge.execution.base import Execution, ExecutionPhase, ExecutionResult
from door_sim_bridge.execution.footsteps import FootstepExecution, validate_footsteps
from door_sim_bridge.execution.trajectory import TrajectoryExecution, validate_trajectory

__all__ = ["Execution", "ExecutionPhase", "ExecutionResult", "FootstepExecution", "TrajectoryExecution",
           "validate_footsteps", "validate_trajectory"]
