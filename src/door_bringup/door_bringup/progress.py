"""The main job's progress line: where the task is while it runs (ROS-free formatting).

    [progress]   41 s | sim 27.5 s | 3/4 OPEN_DOOR/TURN_HANDLE | base (-0.62, -0.15) m | door 0.12 rad

Phases are [Banerjee 2015]'s four (Table I): DETECT_DOOR, WALK_TO_DOOR, OPEN_DOOR (with its
sub-state), WALK_THROUGH. On a terminal the line is rewritten in place; in a log file it is
printed every ``log_period_s``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

from door_bringup.table_one import PHASES, phase_of
from door_contract.vocabulary import TaskState

__all__ = ["ProgressPrinter", "TaskProgress", "numbered_state", "progress_line"]


@dataclass(frozen=True)
class TaskProgress:
    """What the bus says about the task now (None: not heard yet)."""

    wall_s: float = 0.0
    sim_s: float | None = None
    state: TaskState | None = None
    base_xy: tuple[float, float] | None = None
    door_angle: float | None = None  # rad, the angle the FSM's last planning request plans with

    def update(self, **changes: Any) -> TaskProgress:
        return replace(self, **changes)


def numbered_state(state: TaskState) -> str:
    """``n/4 LABEL`` for the four phases (``OPEN_DOOR/TURN_HANDLE`` is phase 3), else the label."""
    top = phase_of(state)
    return f"{PHASES.index(top) + 1}/{len(PHASES)} {state.label}" if top in PHASES else state.label


def _rounded(value: float) -> float:
    """``value`` to 2 decimals without a negative zero (-0.001 rad prints as 0.00)."""
    return round(value, 2) + 0.0


def progress_line(progress: TaskProgress) -> str:
    parts = [f"[progress] {progress.wall_s:4.0f} s"]
    if progress.sim_s is not None:
        parts.append(f"sim {progress.sim_s:.1f} s")
    parts.append(numbered_state(progress.state) if progress.state else "waiting for the FSM")
    if progress.base_xy is not None:
        parts.append(f"base ({_rounded(progress.base_xy[0]):.2f}, {_rounded(progress.base_xy[1]):.2f}) m")
    if progress.door_angle is not None:
        parts.append(f"door {_rounded(progress.door_angle):.2f} rad")
    return " | ".join(parts)


class ProgressPrinter:
    """Prints the line: in place on a terminal (every call), every ``log_period_s`` otherwise."""

    def __init__(self, write: Callable[[str], object], is_terminal: bool, log_period_s: float = 10.0) -> None:
        self._write, self._terminal, self._period = write, is_terminal, log_period_s
        self._last_logged = float("-inf")

    def show(self, progress: TaskProgress) -> None:
        line = progress_line(progress)
        if self._terminal:
            self._write(f"\r\033[K{line}")
        elif progress.wall_s - self._last_logged >= self._period:
            self._last_logged = progress.wall_s
            self._write(f"{line}\n")

    def interrupt(self) -> None:
        """Before another line is printed: end the in-place line."""
        if self._terminal:
            self._write("\r\033[K")
