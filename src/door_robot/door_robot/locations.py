"""Where profiles, URDFs and the shared test data are found (no globals: plain functions).

* the robot profiles ``robot_<name>.yaml`` are in ``$DOOR_PARAMS_DIR``, else in the checkout's
  ``params/``, else (installed) in door_robot's own share, ``share/door_robot/profiles``
  (door_robot's setup.py installs them there: this package never looks into another's share);
* ``package: example-robot-data`` URDFs live under ``<site-packages>/cmeel.prefix/share``;
* ``shared_data:`` URDFs live under ``$DOOR_SHARED_DATA`` or ``<repo>/../shared/data``.
"""

from __future__ import annotations

import os
import sysconfig
from pathlib import Path


def repository_root() -> Path:
    """The checkout this module belongs to (src/door_robot/door_robot → three levels up)."""
    return Path(__file__).resolve().parents[3]


PROFILES_SHARE = "profiles"
"""The folder of door_robot's share directory the robot profiles are installed in."""


def params_dir() -> Path:
    """The folder of the robot profiles: $DOOR_PARAMS_DIR, else the checkout's params/, else
    ``share/door_robot/profiles`` (installed; found through the ament index)."""
    if "DOOR_PARAMS_DIR" in os.environ:
        return Path(os.environ["DOOR_PARAMS_DIR"])
    in_checkout = repository_root() / "params"
    if in_checkout.is_dir():
        return in_checkout
    from ament_index_python.packages import get_package_share_directory

    return Path(get_package_share_directory("door_robot")) / PROFILES_SHARE


def shared_data_dir() -> Path:
    return Path(os.environ.get("DOOR_SHARED_DATA", repository_root().parent / "shared" / "data"))


def cmeel_share_dir() -> Path:
    """``cmeel.prefix/share`` of the running interpreter (example-robot-data, pinocchio)."""
    return Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share"
