"""Mesh URIs of the robots' URDFs resolve to files; file:// rewriting; nothing outside a package."""

from pathlib import Path
from urllib.parse import urlparse

import pytest

from door_robot.meshes import PACKAGE_URI, MeshUris, package_roots, resolve_package_uri, rewrite_mesh_uris
from door_robot.profile import load_profile


@pytest.mark.parametrize("profile", ["talos", "atlas_v4", "drc_hubo"])
def test_every_mesh_of_every_profile_resolves(profile, shared_data):
    urdf = load_profile(profile).urdf_path
    uris = {m.group(0) for m in PACKAGE_URI.finditer(urdf.read_text())}
    assert len(uris) > 20
    assert [u for u in uris if resolve_package_uri(u, urdf) is None] == []


def test_file_uris_name_existing_files_and_package_uris_are_kept():
    urdf = load_profile("talos").urdf_path
    text = urdf.read_text()
    rewritten = rewrite_mesh_uris(text, urdf, MeshUris.FILE)
    assert "package://" not in rewritten
    files = [Path(urlparse(u).path) for u in rewritten.split('"') if u.startswith("file://")]
    assert len(files) >= 41 and all(f.is_file() for f in files)
    assert rewrite_mesh_uris(text, urdf, MeshUris.PACKAGE) == text


def test_example_robot_data_is_found_without_a_urdf_path():
    roots = package_roots("example-robot-data")
    assert roots and (roots[0] / "robots" / "talos_data").is_dir()


@pytest.mark.parametrize("uri", [
    "package://example-robot-data/../../../../../../etc/passwd",
    "package://example-robot-data/robots/talos_data/robots/talos_reduced.urdf",  # not a mesh
    "package://example-robot-data/robots/talos_data/meshes/none.stl",
    "package://no_such_package/meshes/a.stl",
    "file:///etc/passwd",
])
def test_only_meshes_inside_a_package_resolve(uri):
    assert resolve_package_uri(uri) is None
