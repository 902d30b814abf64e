"""Time parameterisation of an optimised path within joint velocity and acceleration limits.

Waypoints are spaced uniformly by Δt = max(Δt_v, Δt_a, Δt_min, D / (T − 1)) (D the motion's
minimum duration, T the waypoints): Δt_v makes the largest
joint step |Δq| reach at most v_max (per joint), Δt_a keeps finite-difference accelerations
|q_{t+1} − 2q_t + q_{t−1}| / Δt² below a_max. Velocities are central differences (zero at
both ends: the robot starts and stops at rest).
"""

from __future__ import annotations

import numpy as np

from door_contract.converters.trajectory import JointPath

__all__ = ["time_parameterise"]


def time_parameterise(positions: np.ndarray, joint_names: tuple[str, ...], velocity_limits: np.ndarray,
                      acceleration_limit: float = 2.0, minimum_step: float = 0.05,
                      minimum_duration: float = 0.0) -> JointPath:
    """A :class:`JointPath` through ``positions`` (T, K) respecting the limits (rad/s, rad/s²),
    taking at least ``minimum_duration`` (s)."""
    steps = np.abs(np.diff(positions, axis=0))
    dt_velocity = float(np.max(steps / velocity_limits[None, :])) if steps.size else 0.0
    second = np.abs(np.diff(positions, n=2, axis=0))
    dt_acceleration = float(np.sqrt(np.max(second) / acceleration_limit)) if second.size else 0.0
    dt = max(dt_velocity, dt_acceleration, minimum_step, minimum_duration / max(len(positions) - 1, 1))
    times = np.arange(len(positions)) * dt
    velocities = np.gradient(positions, dt, axis=0)
    velocities[0] = velocities[-1] = 0.0
    return JointPath(times, joint_names, positions, velocities)
