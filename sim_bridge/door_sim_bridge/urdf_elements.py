"""The parts of a URDF's XML elements that the bridge cannot do without (ROS-free).

``Element.find`` and ``Element.get`` answer None for what is absent; where the URDF must have
it (a joint's ``<parent>`` and ``<child>``, their ``link``, a movable joint's ``name``) these
helpers raise a :class:`~door_sim_bridge.errors.SimulationError` naming what is missing.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from door_sim_bridge.errors import SimulationError

__all__ = ["joint_link", "required_attribute", "required_child"]


def required_child(element: ET.Element, tag: str) -> ET.Element:
    """The first ``<tag>`` child of ``element``; SimulationError if it has none."""
    child = element.find(tag)
    if child is None:
        raise SimulationError(f"URDF <{element.tag}> {element.get('name')!r} has no <{tag}>")
    return child


def required_attribute(element: ET.Element, name: str) -> str:
    """The attribute ``name`` of ``element``; SimulationError if it has none."""
    value = element.get(name)
    if value is None:
        raise SimulationError(f"URDF <{element.tag}> has no {name!r} attribute")
    return value


def joint_link(joint: ET.Element, tag: str) -> str:
    """The link a ``<joint>`` names in its ``<parent>`` or ``<child>`` (``tag``)."""
    end = required_child(joint, tag)
    link = end.get("link")
    if link is None:
        raise SimulationError(f"URDF joint {joint.get('name')!r}: <{tag}> has no 'link' attribute")
    return link
