"""The sim bridge's dead-man: no supervisor heartbeat for ``timeout_s`` → stop everything.

The supervisor publishes its health on /diagnostics every second (wall clock, steady:
heartbeats are wall-clock, so this timeout is too). Once a heartbeat has been seen, silence
longer than ``timeout_s`` trips the dead-man: the running execution is stopped and new
ones are refused until a heartbeat arrives again. Before any heartbeat it is not armed,
so the bridge still runs alone (tests, ``ros2 topic pub`` by hand). ``timeout_s`` = 0
disables it.

Silence counts only while the bridge listens. A gap of more than ``deaf_after_s`` between
two checks means the bridge itself was busy (the first tick of a walk computes its whole
pattern: 1.7 s of CPU for a 39-step sideways passage, 4-5 s on a loaded machine) or not
scheduled at all: heartbeats waited in its queue, and the simulation stood still, so the gap
is taken off the silence. Without that, every sideways push passage through the graph was
stopped at its first step on a busy machine ("silent for 3.8-5.3 s"), three repeats in a row.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["DeadMan"]


@dataclass
class DeadMan:
    timeout_s: float
    supervisor: str = "fsm_supervisor"
    last_beat: float | None = None  # wall s
    tripped: bool = False
    deaf_after_s: float = 1.0  # a longer gap between checks is the bridge's own stall, not silence
    last_check: float | None = None  # wall s

    def beat(self, now: float) -> bool:
        """A heartbeat at ``now``; True when it ends a tripped state."""
        self.last_beat = now
        recovered, self.tripped = self.tripped, False
        return recovered

    def check(self, now: float) -> str | None:
        """The reason to stop, once, when the silence has just exceeded the timeout."""
        stalled = 0.0 if self.last_check is None else now - self.last_check
        self.last_check = now
        if self.tripped or self.timeout_s <= 0 or self.last_beat is None:
            return None
        if stalled > self.deaf_after_s:  # the bridge was deaf: what it missed is still queued
            self.last_beat = min(now, self.last_beat + stalled)
        silent = now - self.last_beat
        if silent <= self.timeout_s:
            return None
        self.tripped = True
        return f"supervisor /{self.supervisor} silent for {silent:.1f} s (dead-man, limit {self.timeout_s:g} s)"

    def refusal(self) -> str | None:
        """Why a new execution is refused now, or None."""
        return f"supervisor /{self.supervisor} heartbeat lost: executions refused until it is back" \
            if self.tripped else None
