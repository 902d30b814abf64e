"""Printing detection results in the form of [Banerjee 2015]'s Table II.

An *outcome* (:class:`Outcome`) is any object with ``scenario.distance`` (m), ``scenario.yaw``
(rad) and, per mode ("automatic", "operator"), an attribute of that name (:class:`ModeResult`)
with ``success`` (bool), ``handle_error`` (m, NaN when nothing was detected), ``normal_error``
(deg), ``outcome`` (the failure's name) and ``seconds`` (detection wall time per frame); a
*grid* (:class:`Grid`) has ``distances`` and ``yaws``. Both evaluations (single frames, :mod:`door_evaluation.detection.evaluate_sim`;
the head search, :mod:`door_evaluation.detection.table_two`) print through these functions.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Protocol

import numpy as np

__all__ = ["CELL_TARGET", "HANDLE_TOLERANCE", "MODES", "NORMAL_TOLERANCE_DEG", "Grid", "ModeResult", "Outcome",
           "Placed", "mode_of", "orientation_range", "paper_form", "paper_table", "rate", "success_table", "summary",
           "worst_cell"]

HANDLE_TOLERANCE = 0.02
"""Success: handle within this distance of the ground truth (m)."""
NORMAL_TOLERANCE_DEG = 2.0
"""Success: normal within this angle of the ground truth (deg)."""
CELL_TARGET = 0.98
"""Issue 13's target: detection success in every cell of 1–4 m × ±0.6 rad."""
MODES = ("automatic", "operator")
PAPER_TABLE_II = (
    ("2.6 - 4 m", "-", "failure", "-0.5 to 0.6", "success"),
    ("2.41 - 2.6 m", "-0.35 to 0.55", "success", "-0.45 to 0.55", "success"),
    ("1.8 - 2.41 m", "-0.2 to 0.5", "success", "-0.35 to 0.5", "success"),
    ("1.4 - 1.8 m", "-0.5 to 0.0", "success", "-0.5 to 0.45", "success"),
    ("1 - 1.3 m", "-", "failure", "-0.2 to 0.2", "success"),
)
"""[Banerjee 2015] Table II: distance, automatic orientation range and result, operator-aided."""


class Placed(Protocol):
    """Where a scene was seen from."""

    @property
    def distance(self) -> float: ...  # m
    @property
    def yaw(self) -> float: ...  # rad


class ModeResult(Protocol):
    """One mode's result on one scene."""

    @property
    def success(self) -> bool: ...
    @property
    def handle_error(self) -> float: ...  # m, NaN when nothing was detected
    @property
    def normal_error(self) -> float: ...  # deg
    @property
    def outcome(self) -> str: ...
    @property
    def seconds(self) -> float: ...


class Outcome(Protocol):
    """A scene and, per mode of :data:`MODES`, its :class:`ModeResult`."""

    @property
    def scenario(self) -> Placed: ...
    @property
    def automatic(self) -> ModeResult: ...
    @property
    def operator(self) -> ModeResult: ...


class Grid(Protocol):
    @property
    def distances(self) -> tuple[float, ...]: ...
    @property
    def yaws(self) -> tuple[float, ...]: ...


def mode_of(outcome: Outcome, mode: str) -> ModeResult:
    """The per-mode result of an outcome."""
    if mode not in MODES:
        raise KeyError(f"mode {mode!r} is not one of {MODES}")
    return outcome.automatic if mode == "automatic" else outcome.operator


def _cell(outcomes: Sequence[Outcome], mode: str, distance: float, yaw: float) -> list[ModeResult]:
    return [mode_of(o, mode) for o in outcomes if o.scenario.distance == distance and o.scenario.yaw == yaw]


def rate(modes: Sequence[ModeResult]) -> float:
    """Fraction of successes (0 for none)."""
    return sum(m.success for m in modes) / max(len(modes), 1)


def orientation_range(outcomes: Sequence[Outcome], mode: str, grid: Grid, distance: float,
                      threshold: float = 1.0) -> str:
    """The paper's "orientation range" of one distance: the angles from the smallest to the
    largest whose cells reach ``threshold`` ("-" when none does)."""
    good = [yaw for yaw in grid.yaws if (cell := _cell(outcomes, mode, distance, yaw)) and rate(cell) >= threshold]
    return f"{min(good):+.1f} to {max(good):+.1f}" if good else "-"


def success_table(outcomes: Sequence[Outcome], mode: str, grid: Grid) -> str:
    """Rows: distances; columns: angle bins (successes/scenes); then the paper-style range
    of angles where every scene succeeded and the row's success rate."""
    per_cell = max(len(_cell(outcomes, mode, d, y)) for d in grid.distances for y in grid.yaws)
    width = max(5, 2 * len(str(per_cell)) + 1)
    header = ("distance | " + " | ".join(f"{yaw:+.1f}".center(width) for yaw in grid.yaws) +
              " | orientation range (rad) | success")
    lines = [header, "-" * len(header)]
    for distance in grid.distances:
        cells = []
        for yaw in grid.yaws:
            cell = _cell(outcomes, mode, distance, yaw)
            cells.append(f"{sum(m.success for m in cell)}/{len(cell)}".center(width))
        row = [mode_of(o, mode) for o in outcomes if o.scenario.distance == distance]
        span = orientation_range(outcomes, mode, grid, distance)
        lines.append(f"{distance:6.1f} m | " + " | ".join(cells) + f" | {span:^23} | {rate(row):6.1%}")
    return "\n".join(lines)


def paper_form(outcomes: Sequence[Outcome], grid: Grid) -> str:
    """Ours in the layout of [Banerjee 2015] Table II: per distance, each mode's orientation range
    (cells at ≥ 98 %) and result (success when every cell of the row reaches 98 %)."""
    lines = ["distance | automatic: orientation (rad), result, rate | operator-aided: orientation (rad), result, rate"]
    for distance in grid.distances:
        parts = []
        for mode in MODES:
            cells = [_cell(outcomes, mode, distance, yaw) for yaw in grid.yaws]
            ok = all(cell and rate(cell) >= CELL_TARGET for cell in cells)
            row = [m for cell in cells for m in cell]
            span = orientation_range(outcomes, mode, grid, distance, CELL_TARGET)
            parts.append(f"{span:>13}, {'success' if ok else 'failure'}, {rate(row):6.1%}")
        lines.append(f"{distance:6.1f} m | {parts[0]:<41} | {parts[1]}")
    return "\n".join(lines)


def worst_cell(outcomes: Sequence[Outcome], mode: str, grid: Grid) -> tuple[float, float, float]:
    """(rate, distance, yaw) of the cell with the lowest success rate."""
    cells = [(rate(cell), d, y) for d in grid.distances for y in grid.yaws if (cell := _cell(outcomes, mode, d, y))]
    return min(cells)


def summary(outcomes: Sequence[Outcome], mode: str) -> str:
    """Overall success, error percentiles of detected frames, failures, time per frame."""
    modes = [mode_of(o, mode) for o in outcomes]
    detected = [m for m in modes if math.isfinite(m.handle_error)]
    times = np.array([m.seconds for m in modes if m.seconds > 0]) * 1000
    failures: dict[str, int] = {}
    for m in modes:
        if not m.success:
            key = m.outcome if not math.isfinite(m.handle_error) else "outside tolerance"
            failures[key] = failures.get(key, 0) + 1
    text = [f"{mode}: success {sum(m.success for m in modes)}/{len(modes)} ({rate(modes):.1%})"]
    if detected:
        handle = np.array([m.handle_error for m in detected]) * 100
        normal = np.array([m.normal_error for m in detected])
        text.append(f"  handle error cm: median {np.median(handle):.2f}, 95% {np.percentile(handle, 95):.2f}, "
                    f"max {handle.max():.2f}; normal error deg: median {np.median(normal):.2f}, "
                    f"95% {np.percentile(normal, 95):.2f}, max {normal.max():.2f}")
    if times.size:
        text.append(f"  time per frame: median {np.median(times):.1f} ms, "
                    f"95% {np.percentile(times, 95):.1f} ms, max {times.max():.1f} ms")
    if failures:
        text.append("  failures: " + ", ".join(f"{k} {v}" for k, v in sorted(failures.items())))
    return "\n".join(text)


def paper_table() -> str:
    """[Banerjee 2015] Table II, for comparison."""
    lines = ["[Banerjee 2015] Table II (Atlas, DRC): distance | automatic range, result | operator-aided range, result"]
    lines += [f"  {d:>12} | {a:>13}, {ar:<7} | {o:>13}, {orr}" for d, a, ar, o, orr in PAPER_TABLE_II]
    return "\n".join(lines)
