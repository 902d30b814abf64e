"""A plain-text progress bar on stderr (no dependencies)."""

from __future__ import annotations

import sys
import time
from typing import TextIO

__all__ = ["ProgressBar"]


class ProgressBar:
    """``[#######.........]  42/98  43%  12.3 s  label`` redrawn in place with ``\\r``.

    Disabled (silent) when ``enabled`` is False, e.g. in tests.
    """

    def __init__(self, total: int, enabled: bool = True, width: int = 30,
                 stream: TextIO | None = None) -> None:
        self._total = max(int(total), 1)
        self._enabled = enabled
        self._width = width
        self._stream = stream if stream is not None else sys.stderr
        self._start = time.perf_counter()
        self._done = 0

    def advance(self, label: str = "") -> None:
        """Count one item as done and redraw."""
        self._done = min(self._done + 1, self._total)
        if not self._enabled:
            return
        filled = int(round(self._width * self._done / self._total))
        bar = "#" * filled + "." * (self._width - filled)
        elapsed = time.perf_counter() - self._start
        self._stream.write(f"\r[{bar}] {self._done:>4}/{self._total} {100 * self._done / self._total:3.0f}% "
                           f"{elapsed:6.1f} s  {label[:40]:<40}")
        self._stream.flush()

    def close(self) -> None:
        """End the line."""
        if self._enabled:
            self._stream.write("\n")
            self._stream.flush()
