"""The network rule: DDS discovery stays on this machine unless the user widens it.

Without ``ROS_AUTOMATIC_DISCOVERY_RANGE`` Fast DDS multicasts on every interface (issue #12
counted 11 RTPS packets in 20 s from one node). Every entry point of the project calls
:func:`keep_discovery_local` before its first DDS participant exists; sourcing
``ros_ws/install/setup.sh`` sets the same default through door_contract's colcon hook
(``hook/discovery_range.dsv``), so other executables started from that shell keep it too.
A range the user set explicitly (``SUBNET``, ``SYSTEM_DEFAULT``…) is kept.
"""

from __future__ import annotations

import os
from collections.abc import MutableMapping

__all__ = ["DISCOVERY_RANGE", "LOCAL_RANGE", "keep_discovery_local"]

DISCOVERY_RANGE = "ROS_AUTOMATIC_DISCOVERY_RANGE"
LOCAL_RANGE = "LOCALHOST"


def keep_discovery_local(environ: MutableMapping[str, str] | None = None) -> str:
    """Set the discovery range to LOCALHOST unless already set (non-empty); returns it."""
    env = os.environ if environ is None else environ
    if not env.get(DISCOVERY_RANGE):
        env[DISCOVERY_RANGE] = LOCAL_RANGE
    return env[DISCOVERY_RANGE]
