"""Starts, watches and stops the graph's node processes (what ``ros2 launch`` would do).

ROS-free: each node is a child process in its own session, so a Ctrl-C in the terminal
reaches only this supervisor, which then stops the children in order: SIGINT (rclpy's
clean shutdown), then SIGTERM, then SIGKILL after the grace periods. A node whose middleware
teardown hangs ends itself with SIGALRM before the first grace is over
(:mod:`door_contract.teardown_bound`): :func:`stopped_cleanly` counts that as stopped on request.

A SIGINT or SIGTERM that arrives while a child is being started is handled once the child is
on the list :meth:`ProcessSupervisor.stop` signals (:func:`signals_deferred`): raised inside
``subprocess.Popen`` after the fork, its KeyboardInterrupt lost the Popen object, and the
child, in a session of its own, ran on with nothing to stop it (seen once: a sim bridge still
running 60 s after a Monte-Carlo's SIGTERM). :meth:`ProcessSupervisor.stop` holds them back too,
until every child is down: a second stop raised inside it left the children not yet signalled
running (seen in CI: a Monte-Carlo worker stopping its graph on the first SIGTERM got a second
one from the pool, which terminates the other workers once one has exited, and a trajectory
optimiser ran on).
"""

from __future__ import annotations

import signal
import subprocess
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from door_bringup.graph_spec import NodeLaunch
from door_bringup.interrupts import signals_deferred
from door_bringup.workspace import Workspace
from door_contract.teardown_bound import TEARDOWN_ABANDONED

__all__ = ["ABANDONED_TEARDOWN_NOTE", "NodeProcess", "ProcessSupervisor", "stopped_cleanly", "teardown_abandoned"]

ABANDONED_TEARDOWN_NOTE = ("its middleware teardown hung and was abandoned at its bound "
                           "(a Fast DDS deadlock; its stacks are in its log)")
"""What to tell a user about a node whose exit code says :func:`teardown_abandoned`."""


def teardown_abandoned(exit_code: int) -> bool:
    """Whether a node ended itself because its middleware teardown hung past its bound."""
    return exit_code == -TEARDOWN_ABANDONED


def stopped_cleanly(exit_code: int) -> bool:
    """Whether a node stopped on request by itself: exit 0, or its hung teardown abandoned
    (its work was done; the hang is Fast DDS's, :mod:`door_contract.teardown_bound`)."""
    return exit_code == 0 or teardown_abandoned(exit_code)


@dataclass
class NodeProcess:
    launch: NodeLaunch
    process: subprocess.Popen
    log_path: Path | None = None

    @property
    def exit_code(self) -> int | None:
        return self.process.poll()


@dataclass
class ProcessSupervisor:
    workspace: Workspace
    log_dir: Path | None = None
    children: list[NodeProcess] = field(default_factory=list)

    def start(self, launch: NodeLaunch, ros_args: Sequence[str] = (),
              env: dict[str, str] | None = None, args: Sequence[str] = ()) -> NodeProcess:
        """Start ``launch`` as ``<exe> <args> --ros-args --params-file params/<node>.yaml <ros_args>``."""
        command = [str(self.workspace.executable(launch.package, launch.executable)), *args, "--ros-args"]
        params_file = self.workspace.params_file(launch.node_name)
        if params_file.is_file():
            command += ["--params-file", str(params_file)]
        command += list(ros_args)
        log_path = None
        output = None
        if self.log_dir is not None:
            self.log_dir.mkdir(parents=True, exist_ok=True)
            log_path = self.log_dir / f"{launch.node_name}.log"
            output = log_path.open("w")
        with signals_deferred():  # a stop now finds the child on the list
            process = subprocess.Popen(command, env=self.workspace.environment(env), stdout=output,
                                       stderr=subprocess.STDOUT if output else None, start_new_session=True)
            child = NodeProcess(launch, process, log_path)
            self.children.append(child)
        return child

    def exited(self) -> list[NodeProcess]:
        """Children that have stopped on their own (crash, kill, bad parameter)."""
        return [child for child in self.children if child.exit_code is not None]

    def stop(self, grace_s: float = 5.0) -> dict[str, int]:
        """Stop every child (SIGINT → SIGTERM → SIGKILL); returns exit codes by node name. A
        SIGINT or SIGTERM arriving meanwhile is raised once every child is down."""
        with signals_deferred():
            return self._stop_children(grace_s)

    def _stop_children(self, grace_s: float) -> dict[str, int]:
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL):
            running = [c for c in self.children if c.exit_code is None]
            for child in running:
                child.process.send_signal(sig)
            deadline = time.monotonic() + grace_s
            for child in running:
                try:
                    child.process.wait(timeout=max(0.0, deadline - time.monotonic()))
                except subprocess.TimeoutExpired:
                    pass
            if all(c.exit_code is not None for c in self.children):
                break
        return {c.launch.node_name: c.process.wait() for c in self.children}
