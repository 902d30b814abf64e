"""When the task may start, and which required node has gone, from the node names in the graph.

The task starts once ``start_delay`` has passed and every required node is up (DETECT_DOOR's
time is then the detector's, not the graph's start-up), or anyway ``graph_timeout`` later,
naming the absent ones. After the start, a required node that was seen and is gone is
reported once: the machine fails the task and stops all motion.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["GraphStep", "GraphWatch"]


@dataclass(frozen=True)
class GraphStep:
    start: bool = False
    lost: tuple[str, ...] = ()
    message: str = ""  # for the heartbeat while waiting
    warning: str = ""  # for the log


@dataclass
class GraphWatch:
    required: set[str]
    start_at: float       # s, wall clock
    graph_timeout: float  # s
    started: bool = False
    seen: set[str] = field(default_factory=set)

    def step(self, now: float, present: set[str]) -> GraphStep:
        if not self.started:
            return self._before_start(now, present)
        self.seen |= present & self.required
        lost = tuple(sorted(self.seen - present))
        self.seen -= set(lost)
        return GraphStep(lost=lost)

    def _before_start(self, now: float, present: set[str]) -> GraphStep:
        if now < self.start_at:
            return GraphStep()
        missing = sorted(self.required - present)
        if missing and now < self.start_at + self.graph_timeout:
            return GraphStep(message=f"waiting for {', '.join(missing)}")
        self.started = True
        self.seen |= present & self.required
        warning = (f"starting without {', '.join(missing)}: not up after {self.graph_timeout:.0f} s"
                   if missing else "")
        return GraphStep(start=True, warning=warning)
