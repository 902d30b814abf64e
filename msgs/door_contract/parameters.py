"""Node parameters as validated specs: description, type, unit and allowed range.

Each package lists its parameters as a tuple of :class:`ParameterSpec` in a ROS-free
module; the node declares them with full descriptors (:func:`declare_parameters`), and
``params/<node>.yaml`` (ROS 2 ``--params-file`` format) holds the same defaults (a test
keeps the two equal). A bad value raises :class:`ParameterRangeError` naming the
parameter and its allowed range; :func:`door_contract.node_support.run_node` turns that
into a fatal log line and exit code 2.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from door_contract.errors import ParameterRangeError

ParameterValue = bool | int | float | str | tuple


@dataclass(frozen=True)
class ParameterSpec:
    """One declared parameter. ``minimum``/``maximum`` bound numbers (inclusive)."""

    name: str
    default: ParameterValue
    description: str
    unit: str = ""
    minimum: float | None = None
    maximum: float | None = None
    choices: tuple[str, ...] = ()

    def allowed(self) -> str:
        """Human-readable allowed values, used in every error message."""
        if self.choices:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        low = "-inf" if self.minimum is None else f"{self.minimum:.10g}"
        high = "inf" if self.maximum is None else f"{self.maximum:.10g}"
        kind = {bool: "boolean", int: "integer", float: "number", str: "string",
                tuple: "list"}[type(self.default)]
        if isinstance(self.default, (bool, str, tuple)):
            return f"a {kind}"
        return f"{'an' if kind == 'integer' else 'a'} {kind} in [{low}, {high}]" + (
            f" {self.unit}" if self.unit else "")

    def validate(self, value: Any) -> ParameterValue:
        """``value`` converted to the default's type, or :class:`ParameterRangeError`."""
        value = self._coerce(value)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            if not math.isfinite(value) or (self.minimum is not None and value < self.minimum) or (
                    self.maximum is not None and value > self.maximum):
                raise self._error(value)
        if self.choices and value not in self.choices:
            raise self._error(value)
        return value

    def _coerce(self, value: Any) -> ParameterValue:
        expected = type(self.default)
        if isinstance(self.default, bool):
            if not isinstance(value, bool):
                raise self._error(value)
            return value
        if expected is float and isinstance(value, (int, float)) and not isinstance(value, bool):
            return float(value)
        if expected is tuple and isinstance(value, (list, tuple)):
            return tuple(value)
        if not isinstance(value, expected) or isinstance(value, bool):
            raise self._error(value)
        return value

    def _error(self, value: Any) -> ParameterRangeError:
        return ParameterRangeError(
            f"parameter '{self.name}' = {value!r} is invalid: expected {self.allowed()}")


def require_ordered(values: Mapping[str, Any], low: str, high: str) -> None:
    """:class:`ParameterRangeError` unless ``values[low] <= values[high]`` (a range's two ends)."""
    if values[low] > values[high]:
        raise ParameterRangeError(f"parameters '{low}' = {values[low]!r} and '{high}' = {values[high]!r} "
                                  f"are invalid: '{low}' must not exceed '{high}'")


def validate_all(specs: Iterable[ParameterSpec], values: Mapping[str, Any]) -> dict[str, Any]:
    """Validate ``values`` (missing ones take defaults); unknown names are an error too.

    Each value has its spec's kind (checked here), which the mapping's type cannot say: it is
    typed ``Any`` so callers read ``params["max_stride"]`` as the float its spec declares."""
    by_name = {spec.name: spec for spec in specs}
    unknown = sorted(set(values) - set(by_name))
    if unknown:
        raise ParameterRangeError(f"unknown parameter(s) {', '.join(unknown)}; "
                                  f"known: {', '.join(sorted(by_name))}")
    return {name: spec.validate(values.get(name, spec.default)) for name, spec in by_name.items()}


def read_params_file(path: Path, node_name: str) -> dict[str, Any]:
    """The ``ros__parameters`` of ``node_name`` in a ROS 2 params file (``/**`` also matches)."""
    document = yaml.safe_load(Path(path).read_text()) or {}
    for key in (node_name, f"/{node_name}", "/**"):
        if key in document:
            return dict(document[key].get("ros__parameters", {}))
    raise ParameterRangeError(f"{path} has no section for node {node_name!r}")


def defaults(specs: Iterable[ParameterSpec]) -> dict[str, ParameterValue]:
    return {spec.name: spec.default for spec in specs}
