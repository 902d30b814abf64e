"""The sim bridge's dead-man: no supervisor heartbeat for ``timeout_s`` → stop everything.

The supervisor publishes its health on /diagnostics every second (wall clock, steady:
heartbeats are wall-clock, so this timeout is too). Once a heartbeat has been seen, silence
longer than ``timeout_s`` trips the dead-man: the running execution is stopped and new
ones are refused until a heartbeat arrives again. Before any heartbeat it is not armed,
so the bridge still runs alone (tests, ``ros2 topic pub`` by hand). ``timeout_s`` = 0
disables it.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class DeadMan:
    timeout_s: float
    supervisor: str = "fsm_supervisor"
    last_beat: float | None = None  # wall s
    tripped: bool = False

    def beat(self, now: float) -> bool:
        """A heartbeat at ``now``; True when it ends a tripped state."""
        self.last_beat = now
        recovered, self.tripped = self.tripped, False
        return recovered

    def check(self, now: float) -> str | None:
        """The reason to stop, once, when the silence has just exceeded the timeout."""
        if self.tripped or self.timeout_s <= 0 or self.last_beat is None:
            return None
        silent = now - self.last_beat
        if silent <= self.timeout_s:
            return None
        self.tripped = True
        return f"supervisor /{self.supervisor} silent for {silent:.1f} s (dead-man, limit {self.timeout_s:g} s)"

    def refusal(self) -> str | None:
        """Why a new execution is refused now, or None."""
        return f"supervisor /{self.supervisor} heartbeat lost: executions refused until it is back" \
            if self.tripped else None
