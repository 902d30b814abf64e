"""Test-wide set-up: the network rule and a ROS domain of this test process's own.

* ``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST`` always (no DDS traffic leaves the machine);
* ``ROS_DOMAIN_ID``: a free id in 10..99 held by an exclusive file lock for the whole
  session, so concurrently running test processes never share a domain. Child processes
  (nodes under test) inherit both.
"""

from __future__ import annotations

import fcntl
import os
import tempfile
from pathlib import Path

import pytest

from door_bringup.workspace import Workspace, repository_root


def _claim_domain_id() -> tuple[int, object]:
    lock_dir = Path(tempfile.gettempdir())
    for domain_id in range(10, 100):
        handle = open(lock_dir / f"door_traversal_ros_domain_{domain_id}.lock", "w")
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return domain_id, handle
        except OSError:
            handle.close()
    raise RuntimeError("no free ROS_DOMAIN_ID in 10..99")


os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
os.environ.setdefault("FASTRTPS_DEFAULT_PROFILES_FILE", str(repository_root() / "params" / "fastdds_profile.xml"))
_DOMAIN_ID, _DOMAIN_LOCK = _claim_domain_id()
os.environ["ROS_DOMAIN_ID"] = str(_DOMAIN_ID)
os.environ.setdefault("DOOR_SHARED_DATA", str(repository_root().parent / "shared" / "data"))


@pytest.fixture(scope="session")
def ros_domain_id() -> int:
    """This test process's ROS domain (also in the environment of every child process)."""
    return _DOMAIN_ID


@pytest.fixture(scope="session")
def workspace() -> Workspace:
    return Workspace(repository_root())


@pytest.fixture(scope="session")
def shared_data() -> Path:
    path = Path(os.environ["DOOR_SHARED_DATA"])
    if not path.is_dir():
        pytest.skip(f"shared test data not found at {path} (set DOOR_SHARED_DATA)")
    return path


@pytest.fixture
def rclpy_context(request):
    """An initialised rclpy context of its own, shut down after the test.

    Only for tests marked ``ros`` (they start DDS participants): ``pytest -m "not ros"`` then
    runs the pure suite, and a test that forgets the marker fails here instead of slipping in."""
    if request.node.get_closest_marker("ros") is None:
        pytest.fail(f"{request.node.nodeid} uses rclpy: mark it (or its module: pytestmark = pytest.mark.ros)")
    import rclpy

    context = rclpy.Context()
    rclpy.init(context=context)
    yield context
    rclpy.try_shutdown(context=context)
