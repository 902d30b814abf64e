"""Teardown that cannot hold a campaign hostage.

Destroying the main job's operator node once hung for 90 min inside Fast DDS (seed 9 at
``--jobs 4``, stop 38: ``Node.destroy_node`` → ``Publisher.destroy`` waited on a lock that was
never released, after the graph's processes had exited; rclpy and Fast DDS report such hangs
as rare and racy, see ros2/rclpy#456). The run's result was known by then, but the Monte-Carlo
worker never returned it, and its pool waited on that worker for ever. :func:`finishes_within`
runs such a step on a daemon thread and gives up waiting after a bound: the caller reports the
leak and goes on; a daemon thread does not keep the process alive at exit.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

__all__ = ["TEARDOWN_S", "finishes_within"]

TEARDOWN_S = 30.0
"""s (wall clock) a node's teardown may take: destroying a node takes milliseconds, even with
four graphs on two cores."""


def finishes_within(step: Callable[[], None], timeout_s: float) -> bool:
    """Run ``step`` on a daemon thread; whether it finished within ``timeout_s``. An exception it
    raises is re-raised here when it finished in time."""
    errors: list[BaseException] = []

    def guarded() -> None:
        try:
            step()
        except BaseException as error:  # handed to the caller's thread below
            errors.append(error)

    worker = threading.Thread(target=guarded, name="teardown", daemon=True)
    worker.start()
    worker.join(timeout_s)
    if worker.is_alive():
        return False
    if errors:
        raise errors[0]
    return True
