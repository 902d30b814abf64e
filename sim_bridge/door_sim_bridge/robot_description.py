"""``/robot_description``: the URDF the simulation loaded, with meshes a viewer can resolve.

The sim loads ``DoorWorld.robot.urdf_text``: for the physical robot the profile's URDF with
box collision soles and every mesh made absolute (:mod:`door_sim_bridge.world.robot_urdf`),
for the kinematic one the profile's URDF as it is. :func:`loaded_urdf` takes that very text,
so /robot_description and the TF tree (:mod:`door_sim_bridge.tf_tree`) have exactly the sim's
links and joints, and only gives each mesh back the name the profile's URDF gave it
(``package://example-robot-data/...``): the absolute paths of the sim's copy are paths of this
machine, which Foxglove (through the bridge's asset handler) and RViz (through the ament index)
cannot use elsewhere.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from door_robot.meshes import MeshUris, rewrite_mesh_uris
from door_sim_bridge.world import DoorWorld
from door_sim_bridge.world.robot_urdf import resolve_mesh

__all__ = ["loaded_urdf", "profile_mesh_names", "robot_description"]


def profile_mesh_names(urdf_text: str, profile_urdf: Path) -> str:
    """``urdf_text`` with every mesh the sim resolved (:func:`resolve_mesh`) named as in
    ``profile_urdf`` again; meshes it names otherwise are kept as they are."""
    original = {mesh.get("filename", "") for mesh in ET.parse(profile_urdf).getroot().iter("mesh")}
    names = {resolve_mesh(name, profile_urdf.parent): name for name in original if name}
    root = ET.fromstring(urdf_text)
    renamed = False
    for mesh in root.iter("mesh"):
        name = names.get(mesh.get("filename", ""))
        if name is not None and name != mesh.get("filename"):
            mesh.set("filename", name)
            renamed = True
    return ET.tostring(root, encoding="unicode") if renamed else urdf_text


def loaded_urdf(world: DoorWorld) -> tuple[str, Path]:
    """The URDF text ``world`` (a DoorWorld) loaded, its meshes named as in the profile's URDF,
    and that file (``package://`` URIs are resolved relative to it)."""
    path = Path(world.profile.urdf_path)
    return profile_mesh_names(world.robot.urdf_text, path), path


def robot_description(world: DoorWorld, mesh_uris: MeshUris = MeshUris.PACKAGE) -> str:
    """What /robot_description carries: the loaded URDF, meshes as ``mesh_uris`` says."""
    text, path = loaded_urdf(world)
    return rewrite_mesh_uris(text, path, mesh_uris)
