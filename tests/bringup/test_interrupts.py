"""A SIGTERM stops the main job as Ctrl-C does: its graph's node processes (each in a session
of its own, out of the terminal's reach) are stopped, none is left running."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from door_bringup.interrupts import interrupt_on_sigterm


def test_a_sigterm_raises_keyboard_interrupt_in_the_main_thread():
    previous = signal.getsignal(signal.SIGTERM)
    try:
        interrupt_on_sigterm()
        with pytest.raises(KeyboardInterrupt, match="SIGTERM"):
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)  # not a synchronisation: the signal interrupts it at once
    finally:
        signal.signal(signal.SIGTERM, previous)


def _graph_processes(domain: str) -> list[int]:
    """Node processes of the workspace's install in ROS domain ``domain``."""
    found = []
    for entry in Path("/proc").iterdir():
        try:
            command = (entry / "cmdline").read_bytes()
            environment = (entry / "environ").read_bytes().split(b"\0")
        except (OSError, ValueError):
            continue
        if b"ros_ws/install" in command and f"ROS_DOMAIN_ID={domain}".encode() in environment:
            found.append(int(entry.name))
    return found


def _until(condition, deadline_s: float) -> bool:
    deadline = time.monotonic() + deadline_s
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.2)  # polling a condition with a deadline
    return condition()


@pytest.mark.slow
@pytest.mark.ros
def test_a_sigterm_to_the_main_job_stops_its_whole_graph(workspace, tmp_path):
    domain = os.environ["ROS_DOMAIN_ID"]
    job = subprocess.Popen([sys.executable, "-m", "door_bringup.door_task", "--no-bag", "--run-dir", str(tmp_path)],
                           env=workspace.environment(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        assert _until(lambda: len(_graph_processes(domain)) >= 5, 120.0), "the graph did not start"
        job.send_signal(signal.SIGTERM)
        assert job.wait(timeout=90) != 0
        assert _until(lambda: not _graph_processes(domain), 30.0), _graph_processes(domain)
    finally:
        job.kill()
        for pid in _graph_processes(domain):
            os.kill(pid, signal.SIGKILL)
