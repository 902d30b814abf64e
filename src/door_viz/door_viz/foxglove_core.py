"""The ROS-free part of the Foxglove bridge: schemas, client commands, assets, and the hand-over
of the WebSocket server's callbacks to the ROS node.

* **Schemas.** Each ROS topic becomes a Foxglove channel with message encoding ``cdr`` (the
  bytes DDS carries, forwarded unchanged) and a ``ros2msg`` schema: the message definition
  followed by every type it uses, each after a line of 80 ``=`` and ``MSG: <type>`` — the
  format rosbag2 writes into mcap files, generated here from rosbags' Jazzy type store.
* **Client publishing.** A Foxglove Publish or button panel sends ``{"data": "approve 7"}``
  (encoding ``json``) on an advertised client channel; only the configured topics
  (``/door_task/operator``) with type ``std_msgs/msg/String`` are accepted.
* **Assets.** Foxglove fetches the URDF's ``package://`` meshes through the socket; only mesh
  and texture files inside a package resolve (:func:`door_robot.meshes.resolve_package_uri`).
* **Threads.** The server calls its listener from its own threads; :class:`ServerEvents`
  queues those calls so that the node handles them on its executor (rclpy entities are
  created and used from one thread).
"""

from __future__ import annotations

import json
import queue
from dataclasses import dataclass
from enum import Enum
from pathlib import Path
from typing import TYPE_CHECKING

from rosbags.typesys import Stores, get_typestore

from door_robot.meshes import resolve_package_uri
from door_viz.errors import DoorVizError

if TYPE_CHECKING:  # the SDK's types (the listener is called with them); the module runs without importing it
    from foxglove import Parameter
    from foxglove.websocket import ChannelView, Client, ClientChannel, PlaybackControlRequest, PlaybackState

__all__ = ["JSON_ENCODING", "ClientCommandError", "EventKind", "SchemaLibrary", "ServerEvent", "ServerEvents",
           "client_channel_refusal", "client_string", "mesh_asset"]

STRING_TYPE = "std_msgs/msg/String"
JSON_ENCODING = "json"


class ClientCommandError(DoorVizError):
    """A client's message that is not a std_msgs/String in JSON."""


class SchemaLibrary:
    """``ros2msg`` schema text of ROS 2 Jazzy types (None for a type it does not know)."""

    def __init__(self) -> None:
        self._typestore = get_typestore(Stores.ROS2_JAZZY)

    def schema(self, type_name: str) -> bytes | None:
        if type_name not in self._typestore.fielddefs:
            return None
        definition, _ = self._typestore.generate_msgdef(type_name, ros_version=2)
        return definition.encode()


def client_string(encoding: str, data: bytes) -> str:
    """The text of a client's std_msgs/String message in JSON (``{"data": "approve 7"}``)."""
    if encoding != JSON_ENCODING:
        raise ClientCommandError(f"client messages must be JSON, got encoding {encoding!r}")
    try:
        document = json.loads(bytes(data).decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as error:
        raise ClientCommandError(f"client message is not JSON: {error}") from None
    if not isinstance(document, dict) or not isinstance(document.get("data"), str) or len(document) != 1:
        raise ClientCommandError('a std_msgs/String in JSON is {"data": "<text>"}')
    return document["data"]


def client_channel_refusal(topic: str, schema_name: str, encoding: str, allowed: tuple[str, ...]) -> str | None:
    """Why a client's advertised channel is refused, or None when it is accepted."""
    if topic not in allowed:
        return f"clients may publish only on {', '.join(allowed)}, not {topic}"
    if schema_name not in ("", STRING_TYPE):
        return f"{topic} carries {STRING_TYPE}, not {schema_name}"
    if encoding != JSON_ENCODING:
        return f"publish JSON on {topic}, not {encoding}"
    return None


def mesh_asset(uri: str, urdf_path: Path | None) -> bytes | None:
    """The bytes of a ``package://`` mesh or texture the robot's URDF names, or None."""
    path = resolve_package_uri(uri, urdf_path)
    return path.read_bytes() if path is not None else None


class EventKind(str, Enum):
    SUBSCRIBE = "subscribe"
    UNSUBSCRIBE = "unsubscribe"
    CLIENT_ADVERTISE = "client_advertise"
    CLIENT_UNADVERTISE = "client_unadvertise"
    CLIENT_MESSAGE = "client_message"


@dataclass(frozen=True)
class ServerEvent:
    """One listener call: ``channel`` is the server channel id (subscriptions) or the client's
    channel id (client publishing)."""

    kind: EventKind
    client: int
    channel: int
    topic: str = ""
    schema_name: str = ""
    encoding: str = ""
    data: bytes = b""


class ServerEvents:
    """The server's listener: every callback becomes a :class:`ServerEvent` in a thread-safe
    queue that the node drains (:meth:`drain`). Every callback of the protocol is implemented
    (the SDK logs an error for missing ones)."""

    def __init__(self) -> None:
        self._queue: queue.SimpleQueue[ServerEvent] = queue.SimpleQueue()

    def on_subscribe(self, client: Client, channel: ChannelView) -> None:
        self._queue.put(ServerEvent(EventKind.SUBSCRIBE, client.id, channel.id, channel.topic))

    def on_unsubscribe(self, client: Client, channel: ChannelView) -> None:
        self._queue.put(ServerEvent(EventKind.UNSUBSCRIBE, client.id, channel.id, channel.topic))

    def on_client_advertise(self, client: Client, channel: ClientChannel) -> None:
        self._queue.put(ServerEvent(EventKind.CLIENT_ADVERTISE, client.id, channel.id, channel.topic,
                                    channel.schema_name or "", channel.encoding or ""))

    def on_client_unadvertise(self, client: Client, client_channel_id: int) -> None:
        self._queue.put(ServerEvent(EventKind.CLIENT_UNADVERTISE, client.id, client_channel_id))

    def on_message_data(self, client: Client, client_channel_id: int, data: bytes) -> None:
        self._queue.put(ServerEvent(EventKind.CLIENT_MESSAGE, client.id, client_channel_id, data=bytes(data)))

    def on_get_parameters(self, client: Client, param_names: list[str],
                          request_id: str | None = None) -> list[Parameter]:
        return []

    def on_set_parameters(self, client: Client, parameters: list[Parameter],
                          request_id: str | None = None) -> list[Parameter]:
        return parameters

    def on_parameters_subscribe(self, param_names: list[str]) -> None:
        return None

    def on_parameters_unsubscribe(self, param_names: list[str]) -> None:
        return None

    def on_connection_graph_subscribe(self) -> None:
        return None

    def on_connection_graph_unsubscribe(self) -> None:
        return None

    def on_playback_control_request(self, playback_control_request: PlaybackControlRequest) -> PlaybackState | None:
        return None

    def drain(self, limit: int = 1000) -> list[ServerEvent]:
        """The queued events, oldest first (at most ``limit``)."""
        events: list[ServerEvent] = []
        while len(events) < limit:
            try:
                events.append(self._queue.get_nowait())
            except queue.Empty:
                break
        return events
