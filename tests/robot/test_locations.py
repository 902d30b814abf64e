"""Where door_robot finds its robot profiles from the sources: in its own package folder, found
from its own files (a package built alone, from a tarball or in one package's Docker build, has
no checkout around it); the checkout's params/ only links to them (issue #17). The installed
lookup (the share, through the ament index) is tests/bringup/test_workspace.py's."""

import os
from pathlib import Path

import pytest

from door_robot import locations
from door_robot.profile import profile_path

PACKAGE_FOLDER = Path(locations.__file__).resolve().parents[1]


@pytest.fixture
def no_params_override(monkeypatch):
    monkeypatch.delenv("DOOR_PARAMS_DIR", raising=False)


def test_from_the_sources_the_profiles_are_in_door_robots_own_folder(no_params_override):
    assert locations.package_folder_of_these_sources() == PACKAGE_FOLDER
    assert locations.params_dir() == PACKAGE_FOLDER / locations.PROFILES_SHARE
    assert profile_path("talos") == PACKAGE_FOLDER / "profiles" / "robot_talos.yaml"


def test_the_environment_still_overrides_the_folder(monkeypatch, tmp_path):
    monkeypatch.setenv("DOOR_PARAMS_DIR", str(tmp_path))
    assert locations.params_dir() == tmp_path


def test_the_checkouts_params_links_to_each_profile(workspace):
    profiles = sorted((PACKAGE_FOLDER / "profiles").glob("robot_*.yaml"))
    assert {p.name for p in profiles} >= {"robot_talos.yaml", "robot_atlas_v4.yaml", "robot_drc_hubo.yaml", "robot_g1.yaml"}
    for profile in profiles:
        link = workspace.root / "params" / profile.name
        assert link.is_symlink() and not Path(os.readlink(link)).is_absolute(), link  # relative: any clone, any image
        assert link.resolve() == profile
