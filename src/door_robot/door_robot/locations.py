"""Where profiles, URDFs and the shared test data are found (no globals: plain functions).

* the robot profiles ``robot_<name>.yaml`` are in ``$DOOR_PARAMS_DIR``, else (running from the
  sources) in this package's own ``profiles/`` (``src/door_robot/profiles``; the checkout's
  ``params/`` links to each), else (installed) in door_robot's own share,
  ``share/door_robot/profiles`` (door_robot's setup.py installs them there: this package never
  looks into another's share, nor outside its own folder);
* ``package: example-robot-data`` URDFs live under ``<site-packages>/cmeel.prefix/share``;
* ``shared_data:`` URDFs live under ``$DOOR_SHARED_DATA`` or ``<repo>/../shared/data``.
"""

from __future__ import annotations

import os
import sysconfig
from pathlib import Path

__all__ = ["PROFILES_SHARE", "checkout_of_this_module", "cmeel_share_dir", "find_checkout",
           "package_folder_of_these_sources", "params_dir", "shared_data_dir"]


def find_checkout(start: Path) -> Path | None:
    """The nearest folder above ``start`` holding ``ros_ws/src`` and ``params/`` (the checkout),
    None outside one. A fixed number of levels up was right for the sources only: from the
    colcon install inside the checkout (``ros_ws/install/<package>/lib/…``) it named ``lib``
    (issue #12: ``door_graph --check`` failed)."""
    for folder in start.resolve().parents:
        if (folder / "ros_ws" / "src").is_dir() and (folder / "params").is_dir():
            return folder
    return None


def checkout_of_this_module() -> Path | None:
    """The checkout these sources (or their install inside it) belong to; None when installed elsewhere."""
    return find_checkout(Path(__file__))


def package_folder_of_these_sources() -> Path | None:
    """door_robot's package folder (``src/door_robot``: its package.xml, setup.py and profiles)
    when this module runs from its sources, None when it runs installed (even from the colcon
    install inside a checkout: an installed package reads its own share). Found from this file
    alone, not from the checkout's layout: the package's files travel with its folder (a source
    tarball, a build of this one package)."""
    folder = Path(__file__).resolve().parents[1]
    if (folder / "package.xml").is_file() and (folder / "setup.py").is_file():
        return folder
    return None


PROFILES_SHARE = "profiles"
"""The folder of the robot profiles: in door_robot's package folder, and in its share directory
(setup.py installs the one as the other)."""


def params_dir() -> Path:
    """The folder of the robot profiles: $DOOR_PARAMS_DIR, else ``src/door_robot/profiles`` (running from the
    sources), else ``share/door_robot/profiles`` (installed; found through the ament index)."""
    if "DOOR_PARAMS_DIR" in os.environ:
        return Path(os.environ["DOOR_PARAMS_DIR"])
    sources = package_folder_of_these_sources()
    if sources is not None:
        return sources / PROFILES_SHARE
    from ament_index_python.packages import get_package_share_directory

    return Path(get_package_share_directory("door_robot")) / PROFILES_SHARE


def shared_data_dir() -> Path:
    """``$DOOR_SHARED_DATA``, else ``../shared/data`` beside the checkout (beside the working
    directory when installed elsewhere)."""
    if "DOOR_SHARED_DATA" in os.environ:
        return Path(os.environ["DOOR_SHARED_DATA"])
    checkout = checkout_of_this_module() or Path.cwd()
    return checkout.parent / "shared" / "data"


def cmeel_share_dir() -> Path:
    """``cmeel.prefix/share`` of the running interpreter (example-robot-data, pinocchio)."""
    return Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share"
