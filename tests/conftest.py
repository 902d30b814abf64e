"""Test-wide set-up: the network rule and a ROS domain of this test process's own.

* ``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST`` always (no DDS traffic leaves the machine);
* ``ROS_DOMAIN_ID``: a free id in 10..99 leased for the whole session
  (:func:`door_bringup.domains.lease_domain`, the locks the Monte-Carlo's workers take too), so
  concurrently running test processes and campaigns never share a domain. Child processes
  (nodes under test) inherit both.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from door_bringup.domains import lease_domain
from door_bringup.workspace import Workspace, repository_root

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
os.environ.setdefault("FASTRTPS_DEFAULT_PROFILES_FILE", str(repository_root() / "params" / "fastdds_profile.xml"))
_DOMAIN = lease_domain(10, count=90)  # held (its lock file open) until the session's process exits
os.environ["ROS_DOMAIN_ID"] = str(_DOMAIN.domain)
os.environ.setdefault("DOOR_SHARED_DATA", str(repository_root().parent / "shared" / "data"))


@pytest.fixture(scope="session")
def ros_domain_id() -> int:
    """This test process's ROS domain (also in the environment of every child process)."""
    return _DOMAIN.domain


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
