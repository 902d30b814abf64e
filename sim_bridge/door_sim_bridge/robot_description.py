"""``/robot_description``: the URDF the simulation loaded, with meshes a viewer can resolve.

Today the sim loads the robot profile's URDF file itself; :func:`loaded_urdf` is the one
place that says so. When the sim loads a generated copy instead (box collision soles for
the walking robot), point :func:`loaded_urdf` at that text and everything downstream
(/robot_description, the TF tree) follows.
"""

from __future__ import annotations

from pathlib import Path

from door_robot.meshes import MeshUris, rewrite_mesh_uris


def loaded_urdf(world) -> tuple[str, Path]:
    """The URDF text ``world`` (a DoorWorld) loaded, and the file it came from (meshes are
    resolved relative to it)."""
    path = Path(world.profile.urdf_path)
    return path.read_text(), path


def robot_description(world, mesh_uris: MeshUris = MeshUris.PACKAGE) -> str:
    """What /robot_description carries: the loaded URDF, meshes as ``mesh_uris`` says."""
    text, path = loaded_urdf(world)
    return rewrite_mesh_uris(text, path, mesh_uris)
