"""A node whose middleware teardown hangs ends itself at its bound, with its stacks in its log
(stop 42: Fast DDS deadlocked destroying the sim bridge in one shutdown in ~40, and the graph's
supervisor had to SIGKILL it; a ``ros2 run`` stopped with Ctrl-C would have hung for good)."""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap

import pytest
import rclpy
from ros_helpers import executor_for, node_names, spin_until

from door_bringup.processes import stopped_cleanly, teardown_abandoned
from door_contract.teardown_bound import TEARDOWN_ABANDONED, TeardownBound

# The hang holds the GIL as the real one does (a C call through ctypes.PyDLL keeps it): no
# Python-level timer could end it, only the kernel's alarm.
HANGING_NODE = textwrap.dedent("""
    import ctypes
    from rclpy.node import Node
    from door_contract.node_support import run_node
    from door_contract.teardown_bound import TeardownBound

    class HangingTeardown(Node):
        def __init__(self):
            super().__init__("hanging_teardown")

        def destroy_node(self):
            print("destroying the node", flush=True)
            libc = ctypes.PyDLL(None)
            while True:
                libc.pause()

    raise SystemExit(run_node(HangingTeardown, teardown=TeardownBound(stacks_after_s=0.5, limit_s=1.5)))
""")


@pytest.mark.ros
def test_a_node_whose_teardown_hangs_ends_itself_at_the_bound(workspace, rclpy_context, tmp_path):
    log = tmp_path / "hanging_teardown.log"
    with log.open("w") as output:
        process = subprocess.Popen([sys.executable, "-c", HANGING_NODE], env=workspace.environment(),
                                   stdout=output, stderr=subprocess.STDOUT)
    probe = rclpy.create_node("teardown_probe", context=rclpy_context)
    try:
        executor = executor_for(probe, rclpy_context)
        up = spin_until(executor, lambda: "hanging_teardown" in node_names(probe) or process.poll() is not None, 60.0)
        assert up and process.poll() is None, log.read_text()
        process.send_signal(signal.SIGINT)
        code = process.wait(timeout=60.0)
    finally:
        if process.poll() is None:
            process.kill()
        probe.destroy_node()
    text = log.read_text()
    assert code == -TEARDOWN_ABANDONED, text
    assert teardown_abandoned(code) and stopped_cleanly(code)
    assert "destroying the node" in text and "Timeout (0:00:00.500000)!" in text, text  # the stacks
    assert "in destroy_node" in text, text


def test_exit_codes_other_than_a_clean_one_or_an_abandoned_teardown_are_not_a_clean_stop():
    assert stopped_cleanly(0) and not teardown_abandoned(0)
    for code in (1, 2, -signal.SIGKILL, -signal.SIGTERM, int(TEARDOWN_ABANDONED)):
        assert not stopped_cleanly(code), code


@pytest.mark.parametrize("stacks_after_s, limit_s", [(0.0, 4.0), (4.0, 4.0), (5.0, 4.0), (-1.0, 4.0)])
def test_a_bound_whose_stacks_come_after_its_limit_is_refused(stacks_after_s, limit_s):
    with pytest.raises(ValueError, match="stacks_after_s < limit_s"):
        TeardownBound(stacks_after_s, limit_s)
