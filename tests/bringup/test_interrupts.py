"""A SIGTERM stops the Monte-Carlo (and the main job) as Ctrl-C does: the graphs' node processes
(each in a session of its own, out of the terminal's reach) and the pool's workers are stopped,
none is left running. The processes watched are the job's own descendants, taken while it runs
(other tests' nodes share the ROS domain). The main job alone was already safe once rclpy.init
had installed rclpy's SIGTERM handler; the Monte-Carlo's main never calls it."""

import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from door_bringup.graph_spec import GRAPH
from door_bringup.interrupts import INTERRUPTED, interrupt_on_sigterm, signals_deferred
from door_bringup.processes import NodeProcess, ProcessSupervisor
from door_bringup.workspace import Workspace


def test_a_sigterm_raises_keyboard_interrupt_in_the_main_thread():
    previous = signal.getsignal(signal.SIGTERM)
    try:
        interrupt_on_sigterm()
        with pytest.raises(KeyboardInterrupt, match="SIGTERM"):
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)  # not a synchronisation: the signal interrupts it at once
    finally:
        signal.signal(signal.SIGTERM, previous)


def test_a_sigterm_while_a_child_starts_is_raised_once_the_child_is_kept():
    """ProcessSupervisor.start holds a stop back until the new child is on its list: a SIGTERM
    raised inside Popen lost the child, which ran on in a session of its own."""
    previous = signal.getsignal(signal.SIGTERM)
    kept = []
    try:
        interrupt_on_sigterm()
        installed = signal.getsignal(signal.SIGTERM)
        with pytest.raises(KeyboardInterrupt, match="SIGTERM"):
            with signals_deferred():
                os.kill(os.getpid(), signal.SIGTERM)
                kept.append("child")  # reached: the signal waits for the block's end
        assert kept == ["child"]
        assert signal.getsignal(signal.SIGTERM) is installed  # the handler before the block is back
    finally:
        signal.signal(signal.SIGTERM, previous)


def _stubborn_child() -> subprocess.Popen:
    """A child in a session of its own that ignores SIGINT (as a node busy in C code may), so
    that the supervisor's stop goes on to SIGTERM after its grace period."""
    script = "import signal, time; signal.signal(signal.SIGINT, signal.SIG_IGN); print(flush=True); time.sleep(60)"
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, start_new_session=True)
    child.stdout.readline()  # its handler is in place
    return child


def test_a_sigterm_during_the_supervisors_stop_is_raised_once_every_child_is_down(tmp_path):
    """CI: a Monte-Carlo worker stopping its graph on the first SIGTERM got a second one (the pool
    terminates the other workers once one exits); raised inside the stop, it left a node running."""
    previous = signal.getsignal(signal.SIGTERM)
    supervisor = ProcessSupervisor(Workspace(tmp_path))
    supervisor.children += [NodeProcess(launch, _stubborn_child()) for launch in GRAPH[:3]]
    second_stop = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGTERM))
    try:
        interrupt_on_sigterm()
        second_stop.start()
        with pytest.raises(KeyboardInterrupt, match="SIGTERM"):
            supervisor.stop(grace_s=2.0)  # the SIGINT grace: the SIGTERM comes 1.7 s before its end
        assert not second_stop.is_alive()  # the signal came during the stop, not after it
        assert [child.exit_code for child in supervisor.children] == [-signal.SIGTERM] * 3
    finally:
        signal.signal(signal.SIGTERM, previous)
        second_stop.cancel()
        for child in supervisor.children:
            child.process.kill()
            child.process.wait()


def _stat(pid: int) -> list[str]:
    """The fields of ``/proc/<pid>/stat`` after the command name (state, parent pid, ...); [] when gone."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return []


def _children(parent: int) -> set[int]:
    """The processes whose parent is ``parent`` (the graph's nodes are the main job's children)."""
    return {int(entry.name) for entry in Path("/proc").iterdir()
            if entry.name.isdigit() and (fields := _stat(int(entry.name))) and int(fields[1]) == parent}


def _descendants(root: int) -> set[int]:
    """Every process below ``root`` (children, their children, ...)."""
    found, frontier = set(), {root}
    while frontier:
        frontier = set().union(*(_children(pid) for pid in frontier)) - found
        found |= frontier
    return found


def _is_node(pid: int) -> bool:
    """Whether ``pid`` runs one of the workspace's installed executables (a node)."""
    try:
        return b"ros_ws/install" in Path(f"/proc/{pid}/cmdline").read_bytes()
    except OSError:
        return False


Process = tuple[int, str]
"""A process as (pid, start time in clock ticks since boot): a pid alone may be reused on this
shared machine (pid_max 32768) by another job's process before the check looks again."""


def _identity(pid: int) -> Process | None:
    """The process ``pid`` names now; None when gone."""
    fields = _stat(pid)
    return (pid, fields[19]) if len(fields) > 19 else None


def _started(root: int, graph: set[Process], nodes: int) -> bool:
    """Whether ``nodes`` node processes run below ``root`` now (every descendant seen is kept in
    ``graph``)."""
    below = {process for pid in _descendants(root) if (process := _identity(pid)) is not None}
    graph.update(below)
    return sum(1 for pid, _ in _alive(below) if _is_node(pid)) >= nodes


def _alive(processes: set[Process]) -> set[Process]:
    """Those of ``processes`` still running (not zombies, pid not taken over by another process)."""
    return {(pid, start) for pid, start in processes
            if (fields := _stat(pid)) and len(fields) > 19 and fields[19] == start and fields[0] != "Z"}


def _command(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")[:200]
    except OSError:
        return "(gone)"


def _until(condition, deadline_s: float) -> bool:
    deadline = time.monotonic() + deadline_s
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.2)  # polling a condition with a deadline
    return condition()


@pytest.mark.slow
@pytest.mark.ros
def test_a_sigterm_to_the_monte_carlo_stops_every_graph_and_worker(workspace, tmp_path):
    """Two trials at once (two pool workers, each with a graph of 6 node processes): a SIGTERM
    to the Monte-Carlo leaves nothing running. Before, it left the 12 nodes and both workers,
    which went on starting trials. It ends with one line saying how to resume, not a traceback."""
    stderr = tmp_path / "stderr.txt"
    with stderr.open("w") as sink:
        job = subprocess.Popen([sys.executable, "-m", "door_bringup.monte_carlo", "--trials", "2", "--jobs", "2",
                                "--seed", "11", "--runs-dir", str(tmp_path)], env=workspace.environment(), stdout=subprocess.DEVNULL,
                               stderr=sink)
    below: set[Process] = set()
    try:
        assert _until(lambda: _started(job.pid, below, 10), 180.0), "the two graphs did not start"
        assert job.poll() is None
        job.send_signal(signal.SIGTERM)
        assert job.wait(timeout=90) == INTERRUPTED
        assert _until(lambda: not _alive(below), 60.0), [_command(pid) for pid, _ in _alive(below)]  # none orphaned
        said = stderr.read_text()
        assert "interrupted (SIGTERM): 0 of 2 trials finished; --resume " in said and "Traceback" not in said
        assert f"--resume {tmp_path}/monte_carlo_" in said  # the campaign's folder is where it was told
    finally:
        job.kill()
        for pid, _ in _alive(below):
            os.kill(pid, signal.SIGKILL)
