"""``door_graph``: run the node graph here, where ``ros2 launch`` is not available.

``door_graph --check`` starts the graph's nodes as separate processes, waits (with a deadline)
until each appears in the ROS graph, then stops them with SIGINT and reports their exit
codes — the smoke test of the set-up. On a real ROS install use ``launch/door_task.launch.py``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import rclpy
from rclpy.node import Node

from door_bringup.graph_spec import GRAPH
from door_bringup.processes import ABANDONED_TEARDOWN_NOTE, ProcessSupervisor, stopped_cleanly, teardown_abandoned
from door_bringup.workspace import Workspace, repository_root
from door_contract.network import keep_discovery_local

__all__ = ["check_graph", "main"]


def wait_for_nodes(probe: Node, names: set[str], timeout_s: float,
                   supervisor: ProcessSupervisor | None = None) -> set[str]:
    """Spin ``probe`` until every name in ``names`` is in the graph; returns the missing ones.

    Gives up early when a supervised process has already exited.
    """
    deadline = time.monotonic() + timeout_s
    missing = set(names)
    while missing and time.monotonic() < deadline and not (supervisor and supervisor.exited()):
        rclpy.spin_once(probe, timeout_sec=0.1)
        missing = names - set(probe.get_node_names())
    return missing


def check_graph(workspace: Workspace, timeout_s: float, log_dir: Path | None) -> int:
    supervisor = ProcessSupervisor(workspace, log_dir)
    keep_discovery_local()  # this runner's own probe participant too
    rclpy.init()
    probe = rclpy.create_node("door_graph_probe")
    try:
        for launch in GRAPH:
            supervisor.start(launch)
            print(f"started {launch.package}/{launch.executable}", flush=True)
        missing = wait_for_nodes(probe, {launch.node_name for launch in GRAPH}, timeout_s, supervisor)
        for name in sorted({launch.node_name for launch in GRAPH} - missing):
            print(f"  /{name} is up", flush=True)
        for name in sorted(missing):
            print(f"  /{name} did NOT appear within {timeout_s:.0f} s", flush=True)
    finally:
        codes = supervisor.stop()
        probe.destroy_node()
        rclpy.try_shutdown()
    for name, code in codes.items():
        hung = f" ({ABANDONED_TEARDOWN_NOTE})" if teardown_abandoned(code) else ""
        print(f"  /{name} exited with code {code}{hung}", flush=True)
    return 0 if not missing and all(stopped_cleanly(code) for code in codes.values()) else 1


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="start, verify and stop the graph")
    parser.add_argument("--timeout", type=float, default=30.0, help="seconds to wait for the nodes")
    parser.add_argument("--log-dir", type=Path, default=None, help="write each node's output here")
    args = parser.parse_args(argv)
    return check_graph(Workspace(repository_root()), args.timeout, args.log_dir)


if __name__ == "__main__":
    sys.exit(main())
