"""Where a URDF's meshes are: ``package://`` URIs resolved to files, and URDF text rewritten.

A URDF names its meshes ``package://<package>/<path>``. The package's root directory is
found, in this order:

1. the ament index (``AMENT_PREFIX_PATH``), as RViz and ``ros2`` tools resolve it on a real
   install;
2. the pip package's prefix ``<site-packages>/cmeel.prefix/share/<package>`` (example-robot-data
   from PyPI ships its own ament index there);
3. next to the URDF: an ancestor directory named ``<package>``, or an ancestor's child of that
   name (the seed papers' Atlas v4 and DRC-HUBO keep ``atlas_description/`` beside their URDF).

Foxglove asks for ``package://`` assets through its WebSocket (the bridge's asset handler
calls :func:`resolve_package_uri`); ``file://`` URIs (:func:`rewrite_mesh_uris`) suit RViz or
Foxglove desktop on the same machine without any package path set-up.
"""

from __future__ import annotations

import re
from enum import Enum
from pathlib import Path

from door_robot.locations import cmeel_share_dir

__all__ = ["PACKAGE_URI", "MeshUris", "package_roots", "resolve_package_uri", "rewrite_mesh_uris"]

PACKAGE_URI = re.compile(r"package://(?P<package>[A-Za-z0-9_.\-]+)/(?P<path>[^\"'<>\s]+)")
MESH_SUFFIXES = frozenset({".stl", ".dae", ".obj", ".glb", ".gltf", ".png", ".jpg", ".jpeg", ".mtl"})


class MeshUris(str, Enum):
    """How ``/robot_description`` names meshes."""

    PACKAGE = "package"  # package://<package>/<path>, as the URDF has them
    FILE = "file"        # file:///absolute/path of this machine


def _ament_share(package: str) -> Path | None:
    try:
        from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
    except ImportError:
        return None
    try:
        return Path(get_package_share_directory(package))
    except (PackageNotFoundError, KeyError, ValueError, OSError):  # OSError: no AMENT_PREFIX_PATH
        return None


def package_roots(package: str, urdf_path: Path | None = None) -> list[Path]:
    """Directories that may be the root of ``package``, in search order (module docstring)."""
    candidates = [_ament_share(package), cmeel_share_dir() / package]
    if urdf_path is not None:
        for ancestor in Path(urdf_path).resolve().parents:
            candidates += [ancestor if ancestor.name == package else None, ancestor / package]
    roots: list[Path] = []
    for candidate in candidates:
        if candidate is not None and candidate.is_dir() and candidate.resolve() not in roots:
            roots.append(candidate.resolve())
    return roots


def resolve_package_uri(uri: str, urdf_path: Path | None = None) -> Path | None:
    """The mesh or texture file a ``package://`` URI names, or None.

    Only existing files with a mesh/texture suffix inside the package root are returned, so
    a client cannot read anything else through it (``..`` cannot leave the root).
    """
    match = PACKAGE_URI.fullmatch(uri)
    if match is None or Path(match["path"]).suffix.lower() not in MESH_SUFFIXES:
        return None
    for root in package_roots(match["package"], urdf_path):
        path = (root / match["path"]).resolve()
        if path.is_relative_to(root) and path.is_file():
            return path
    return None


def rewrite_mesh_uris(urdf_text: str, urdf_path: Path, scheme: MeshUris) -> str:
    """``urdf_text`` with its ``package://`` URIs in ``scheme``.

    FILE: each resolvable URI becomes ``file://<absolute path>``; an unresolvable one is kept
    (a viewer then reports that mesh missing, as it would on a real install). PACKAGE: unchanged.
    """
    if scheme is MeshUris.PACKAGE:
        return urdf_text

    def as_file(match: re.Match[str]) -> str:
        path = resolve_package_uri(match.group(0), urdf_path)
        return path.as_uri() if path is not None else match.group(0)

    return PACKAGE_URI.sub(as_file, urdf_text)
