"""Node parameters as validated specs: description, type and allowed range (with its unit).

Each package lists its parameters as a tuple of :class:`ParameterSpec` in a ROS-free
module; the node declares them with full descriptors (:func:`declare_parameters`), and
``params/<node>.yaml`` (ROS 2 ``--params-file`` format) holds the same defaults (a test
keeps the two equal). A bad value raises :class:`ParameterRangeError` naming the
parameter and its allowed range (a number's through the contract's one range check,
:func:`door_contract.ranges.check_in_range`, in the words of every core's options);
:func:`door_contract.node_support.run_node` turns that into a fatal log line and exit code 2.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from door_contract.errors import ParameterRangeError
from door_contract.ranges import FieldRange, check_in_range

__all__ = ["ParameterSpec", "ParameterValue", "defaults", "read_params_file", "require_ordered", "validate_all"]

ParameterValue = bool | int | float | str | tuple[Any, ...]


@dataclass(frozen=True)
class ParameterSpec:
    """One declared parameter. A number's bounds and unit are ``allowed_range`` (None: any finite
    value), the same :class:`~door_contract.ranges.FieldRange` a core checks its option with when
    the parameter configures one (the range is then taken from the core, written once)."""

    name: str
    default: ParameterValue
    description: str
    allowed_range: FieldRange | None = None
    choices: tuple[str, ...] = ()

    @property
    def unit(self) -> str:
        """The unit of a number (``""`` for none)."""
        return self.allowed_range.unit if self.allowed_range is not None else ""

    @property
    def is_number(self) -> bool:
        """True for an ``int`` or ``float`` parameter (not a ``bool``)."""
        return isinstance(self.default, (int, float)) and not isinstance(self.default, bool)

    def numeric_range(self) -> FieldRange:
        """The interval a number must lie in (any finite value when the spec gives none)."""
        return self.allowed_range if self.allowed_range is not None else _ANY_NUMBER

    def allowed(self) -> str:
        """Human-readable allowed values, used in every error message."""
        if self.choices:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        if self.is_number:
            kind = "an integer" if isinstance(self.default, int) else "a number"
            return kind if self.allowed_range is None else f"{kind} in {self.allowed_range.describe()}"
        kind = {bool: "boolean", str: "string", tuple: "list"}[type(self.default)]
        return f"a {kind}"

    def validate(self, value: Any) -> ParameterValue:
        """``value`` converted to the default's type, or :class:`ParameterRangeError`; a number
        is checked by :func:`~door_contract.ranges.check_in_range` against its range."""
        if self.is_number:
            return self._validate_number(value)
        coerced = self._coerce(value)
        if self.choices and coerced not in self.choices:
            raise self._error(coerced)
        return coerced

    def _validate_number(self, value: Any) -> int | float:
        integer = isinstance(self.default, int)
        number: int | float = value
        if not integer and isinstance(value, int) and not isinstance(value, bool):
            number = float(value)
        check_in_range(f"parameter '{self.name}'", number, self.numeric_range(), ParameterRangeError,
                       integer=integer)
        return number  # checked: an int, or a finite float

    def _coerce(self, value: Any) -> ParameterValue:
        expected = type(self.default)
        if isinstance(self.default, bool):
            if not isinstance(value, bool):
                raise self._error(value)
            return value
        if expected is tuple and isinstance(value, (list, tuple)):
            return tuple(value)
        if not isinstance(value, expected) or isinstance(value, bool):
            raise self._error(value)
        return value

    def _error(self, value: Any) -> ParameterRangeError:
        return ParameterRangeError(
            f"parameter '{self.name}' = {value!r} is invalid: expected {self.allowed()}")


_ANY_NUMBER = FieldRange(-math.inf, math.inf, "")


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
