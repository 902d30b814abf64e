"""``sensor_msgs/JointState`` ↔ {joint name: position}."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from sensor_msgs.msg import JointState

from door_contract.converters._checks import require_finite
from door_contract.errors import ShapeError
from door_contract.stamps import Stamp, to_time_msg

__all__ = ["joint_state_to_positions", "positions_to_joint_state"]


def joint_state_to_positions(msg: JointState) -> dict[str, float]:
    """Positions by joint name (rad or m); rejects size mismatch, duplicates, NaN/inf."""
    if len(msg.name) != len(msg.position):
        raise ShapeError(f"JointState has {len(msg.name)} names but {len(msg.position)} positions")
    if len(set(msg.name)) != len(msg.name):
        raise ShapeError("JointState names are not unique")
    positions = require_finite(np.asarray(msg.position, dtype=float), "JointState.position")
    return dict(zip(msg.name, positions.tolist()))


def positions_to_joint_state(positions: Mapping[str, float], stamp: Stamp | None = None,
                             velocities: Mapping[str, float] | None = None) -> JointState:
    msg = JointState()
    if stamp is not None:
        msg.header.stamp = to_time_msg(stamp)
    msg.name = list(positions)
    msg.position = require_finite(np.fromiter(positions.values(), float, len(positions)),
                                  "joint positions").tolist()
    if velocities is not None:
        msg.velocity = [float(velocities[name]) for name in msg.name]
    return msg
