"""Helpers for tests that talk to nodes over real DDS: nodes of the graph as processes, and
waiting on conditions with deadlines."""

from __future__ import annotations

import signal
import subprocess
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node

from door_bringup.graph_spec import FOXGLOVE_BRIDGE, GRAPH
from door_bringup.processes import stopped_cleanly
from door_bringup.workspace import Workspace


def start_node(workspace: Workspace, node_name: str, log: Path, *overrides: str) -> subprocess.Popen:
    """One node of the graph (or the Foxglove bridge) as a process, as ``ros2 run`` starts it: its
    params file and ``name:=value`` overrides; its output goes to ``log`` (also ``process.log``).
    The process inherits this test process's ``ROS_DOMAIN_ID``."""
    launch = next(launch for launch in (*GRAPH, FOXGLOVE_BRIDGE) if launch.node_name == node_name)
    command = [str(workspace.executable(launch.package, launch.executable)), "--ros-args",
               "--params-file", str(workspace.params_file(node_name))]
    for override in overrides:
        command += ["-p", override]
    process = subprocess.Popen(command, env=workspace.environment(), stdout=log.open("w"), stderr=subprocess.STDOUT)
    process.log = log
    return process


def stop_node(process: subprocess.Popen, timeout_s: float = 30.0) -> int:
    """Ctrl-C (SIGINT) to a node still running; its exit code, once it has exited within ``timeout_s``."""
    if process.poll() is None:
        process.send_signal(signal.SIGINT)
    return process.wait(timeout=timeout_s)


@contextmanager
def node_process(workspace: Workspace, node_name: str, log: Path, *overrides: str,
                 timeout_s: float = 30.0) -> Iterator[subprocess.Popen]:
    """:func:`start_node` for a ``with`` block (a fixture's ``yield`` inside it): the node is
    stopped at the block's end, also when the block raised; a node that ran the block through
    must stop cleanly (exit 0, or its hung middleware teardown abandoned at its bound; the
    assertion names its log)."""
    process = start_node(workspace, node_name, log, *overrides)
    try:
        yield process
    finally:
        code = stop_node(process, timeout_s)
    assert stopped_cleanly(code), log.read_text()


def spin_until(executor: SingleThreadedExecutor, condition: Callable[[], bool], timeout_s: float) -> bool:
    """Spin ``executor`` until ``condition()`` holds or the deadline passes; returns the condition."""
    deadline = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > deadline:
            return False
        executor.spin_once(timeout_sec=0.05)
    return True


def node_names(node: Node) -> set[str]:
    return set(node.get_node_names())


def executor_for(node: Node, context: rclpy.Context) -> SingleThreadedExecutor:
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    return executor
