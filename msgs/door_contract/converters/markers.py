""":class:`~door_contract.marker_shapes.MarkerShape` values → ``visualization_msgs/MarkerArray``."""

from __future__ import annotations

from collections.abc import Iterable

from geometry_msgs.msg import Point
from visualization_msgs.msg import Marker, MarkerArray

from door_contract.converters._checks import require_finite
from door_contract.converters.pose import matrix_to_pose
from door_contract.frames import Frame
from door_contract.marker_shapes import MarkerKind, MarkerShape
from door_contract.stamps import Stamp, to_time_msg

__all__ = ["shape_to_marker", "shapes_to_marker_array"]

_TYPES = {MarkerKind.ARROW: Marker.ARROW, MarkerKind.CUBE: Marker.CUBE, MarkerKind.SPHERE: Marker.SPHERE,
          MarkerKind.LINE_STRIP: Marker.LINE_STRIP, MarkerKind.LINE_LIST: Marker.LINE_LIST,
          MarkerKind.TRIANGLE_LIST: Marker.TRIANGLE_LIST, MarkerKind.TEXT: Marker.TEXT_VIEW_FACING}


def shape_to_marker(shape: MarkerShape, stamp: Stamp | None = None, frame_id: str = Frame.ODOM.value) -> Marker:
    """One Marker (action ADD); NonFiniteError if a point, the pose or the colour is NaN/inf."""
    marker = Marker(ns=shape.namespace, id=shape.marker_id, type=_TYPES[shape.kind], action=Marker.ADD)
    marker.header.frame_id = frame_id
    if stamp is not None:
        marker.header.stamp = to_time_msg(stamp)
    marker.pose = matrix_to_pose(shape.pose)
    marker.scale.x, marker.scale.y, marker.scale.z = (float(v) for v in require_finite(shape.scale, "marker scale"))
    marker.color.r, marker.color.g, marker.color.b, marker.color.a = (
        float(v) for v in require_finite(shape.rgba, "marker colour"))
    marker.points = [Point(x=float(x), y=float(y), z=float(z))
                     for x, y, z in require_finite(shape.points, "marker points").reshape(-1, 3)]
    marker.text = shape.text
    return marker


def shapes_to_marker_array(shapes: Iterable[MarkerShape], stamp: Stamp | None = None,
                           frame_id: str = Frame.ODOM.value, replace: bool = True) -> MarkerArray:
    """A MarkerArray of ``shapes``; with ``replace`` it starts with a DELETEALL marker, so the
    array is the whole picture (markers of an older, longer plan disappear)."""
    markers = [Marker(action=Marker.DELETEALL)] if replace else []
    if replace:
        markers[0].header.frame_id = frame_id
    markers += [shape_to_marker(shape, stamp, frame_id) for shape in shapes]
    return MarkerArray(markers=markers)
