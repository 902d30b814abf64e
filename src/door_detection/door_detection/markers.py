"""RViz/Foxglove markers of a door estimate: outline, handle, normal."""

from __future__ import annotations

from geometry_msgs.msg import Point
from visualization_msgs.msg import Marker, MarkerArray

from door_contract.frames import Frame
from door_contract.payloads import DoorEstimate

__all__ = ["door_markers"]


def _marker(kind: int, marker_id: int, rgba: tuple[float, float, float, float]) -> Marker:
    marker = Marker(type=kind, action=Marker.ADD, id=marker_id, ns="door")
    marker.header.frame_id = Frame.ODOM.value
    marker.pose.orientation.w = 1.0
    marker.color.r, marker.color.g, marker.color.b, marker.color.a = rgba
    return marker


def door_markers(estimate: DoorEstimate) -> MarkerArray:
    outline = _marker(Marker.LINE_STRIP, 0, (0.1, 0.9, 0.1, 1.0))
    outline.scale.x = 0.02
    outline.points = [Point(x=c[0], y=c[1], z=c[2]) for c in (*estimate.corners, estimate.corners[0])]
    handle = _marker(Marker.SPHERE, 1, (0.9, 0.1, 0.1, 1.0))
    handle.scale.x = handle.scale.y = handle.scale.z = 0.05
    handle.pose.position = Point(x=estimate.handle_position[0], y=estimate.handle_position[1],
                                 z=estimate.handle_position[2])
    normal = _marker(Marker.ARROW, 2, (0.1, 0.3, 1.0, 1.0))
    normal.scale.x, normal.scale.y, normal.scale.z = 0.02, 0.04, 0.06
    start = estimate.handle_position
    end = tuple(s + 0.3 * n for s, n in zip(start, estimate.normal))
    normal.points = [Point(x=start[0], y=start[1], z=start[2]), Point(x=end[0], y=end[1], z=end[2])]
    return MarkerArray(markers=[outline, handle, normal])
