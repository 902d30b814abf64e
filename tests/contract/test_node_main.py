"""Every node module's entry point is ``main = node_main(Node, __name__)``: the ``main`` that
console_scripts (``ros2 run``) call, and the program itself under ``python -m``."""

import ast
import subprocess
import sys

import pytest

from door_contract.node_support import node_main


def test_node_main_is_the_module_main_and_runs_nothing_when_imported():
    def factory():
        raise AssertionError("a node was built on import")

    main = node_main(factory, "some.module")
    assert callable(main) and "factory" in main.__doc__


def test_every_node_module_ends_in_node_main(workspace):
    paths = sorted(workspace.root.glob("src/*/*/*_node.py")) + sorted(workspace.root.glob("sim_bridge/*/*_node.py"))
    assert len(paths) >= 7
    for path in paths:
        last = ast.parse(path.read_text()).body[-1]
        assert ast.unparse(last).startswith("main = node_main("), path
        assert 'if __name__ == "__main__"' not in path.read_text(), path


@pytest.mark.ros  # the node's context starts before it reads its parameters
def test_python_dash_m_runs_the_node_and_exits_with_its_code(workspace):
    """``python -m door_fsm.fsm_supervisor_node`` is the node: a bad parameter exits 2 with one line."""
    command = [sys.executable, "-m", "door_fsm.fsm_supervisor_node", "--ros-args", "-p", "autonomy:=yolo"]
    result = subprocess.run(command, env=workspace.environment(), capture_output=True, text=True, timeout=60)
    output = result.stdout + result.stderr
    assert result.returncode == 2, output
    assert "'autonomy'" in output and "Traceback" not in output, output
