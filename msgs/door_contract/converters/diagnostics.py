"""``diagnostic_msgs/DiagnosticArray`` from a node's status."""

from __future__ import annotations

from collections.abc import Mapping
from enum import IntEnum

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue

from door_contract.stamps import Stamp, to_time_msg

__all__ = ["Health", "diagnostic_array", "status_values"]


class Health(IntEnum):
    OK = 0
    WARN = 1
    ERROR = 2
    STALE = 3


def diagnostic_array(node_name: str, health: Health, message: str,
                     values: Mapping[str, object] | None = None, stamp: Stamp | None = None) -> DiagnosticArray:
    """One-status array: ``name`` is the node, ``values`` its timings and counters."""
    array = DiagnosticArray()
    if stamp is not None:
        array.header.stamp = to_time_msg(stamp)
    status = DiagnosticStatus(level=bytes([int(health)]), name=node_name, message=message,
                              hardware_id="door_traversal")
    status.values = [KeyValue(key=str(k), value=str(v)) for k, v in (values or {}).items()]
    array.status = [status]
    return array


def status_values(array: DiagnosticArray, node_name: str) -> dict[str, str] | None:
    """The ``values`` of ``node_name``'s status in ``array`` (None when it holds none)."""
    for status in array.status:
        if status.name == node_name:
            return {pair.key: pair.value for pair in status.values}
    return None
