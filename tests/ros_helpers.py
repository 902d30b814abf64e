"""Helpers for tests that talk to nodes over real DDS: waiting on conditions with deadlines."""

from __future__ import annotations

import time
from collections.abc import Callable

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node


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
