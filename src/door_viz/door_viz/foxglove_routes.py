"""Where the Foxglove bridge sends what, without ROS or the SDK: its routing tables.

* **ROS → Foxglove.** Every ROS topic is offered once as a server channel (or, for a type
  without a schema, never: :meth:`Routes.unrouted`). A ROS subscription exists only while at
  least one client subscribes to the topic's channel: :meth:`Routes.watch` says when to
  make one (the first client) and when to drop it (the last one gone).
* **Foxglove → ROS.** A client's advertised channel is accepted only on an allowed topic,
  typed ``std_msgs/msg/String`` in JSON (:func:`~door_viz.foxglove_core.client_channel_refusal`);
  its messages are republished on that topic (:meth:`Routes.client_message`), anything else
  is refused with the reason (the node logs it and tells the client in a status).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from enum import Enum

from door_viz.foxglove_core import (
    JSON_ENCODING,
    ClientCommandError,
    EventKind,
    ServerEvent,
    client_channel_refusal,
    client_string,
)

__all__ = ["ClientMessage", "Routes", "Watch", "WatchChange"]


class Watch(str, Enum):
    START = "start"  # the first client subscribed: subscribe on ROS
    STOP = "stop"    # the last client left: drop the ROS subscription


@dataclass(frozen=True)
class WatchChange:
    """What a (un)subscription of a client changes on the ROS side for ``topic`` of ``type_name``."""

    watch: Watch
    topic: str
    type_name: str


@dataclass(frozen=True)
class ClientMessage:
    """A client's message to republish: the text of a std_msgs/String on ``topic``."""

    topic: str
    text: str


class Routes:
    def __init__(self, client_topics: Iterable[str]) -> None:
        """``client_topics``: the topics clients may publish on."""
        self.client_topics = tuple(client_topics)
        self._type_of_topic: dict[str, str] = {}
        self._unrouted: set[str] = set()
        self._topic_of_channel: dict[int, str] = {}
        self._watchers: dict[str, set[int]] = {}  # topic -> the clients subscribed to it
        self._client_channels: dict[tuple[int, int], str] = {}  # (client, its channel) -> topic

    # ------------------------------------------------------------------ ROS → Foxglove
    def unseen(self, topics_and_types: Iterable[tuple[str, list[str]]]) -> list[tuple[str, str]]:
        """The (topic, type) of the graph's topics not yet routed nor refused (first type of each)."""
        return [(topic, types[0]) for topic, types in topics_and_types
                if types and topic not in self._type_of_topic and topic not in self._unrouted]

    def route(self, topic: str, type_name: str, channel: int) -> None:
        """``topic`` is offered on server channel ``channel``."""
        self._type_of_topic[topic] = type_name
        self._topic_of_channel[channel] = topic

    def unrouted(self, topic: str) -> None:
        """``topic`` is not forwarded (its type has no schema); it is not offered again."""
        self._unrouted.add(topic)

    @property
    def channels(self) -> int:
        """How many topics are offered."""
        return len(self._topic_of_channel)

    def watch(self, event: ServerEvent) -> WatchChange | None:
        """A client (un)subscribed a server channel: what changes on the ROS side, if anything."""
        topic = self._topic_of_channel.get(event.channel)
        if topic is None:
            return None
        watchers = self._watchers.setdefault(topic, set())
        before = bool(watchers)
        if event.kind is EventKind.SUBSCRIBE:
            watchers.add(event.client)
        else:
            watchers.discard(event.client)
        if bool(watchers) == before:
            return None
        return WatchChange(Watch.START if watchers else Watch.STOP, topic, self._type_of_topic[topic])

    # ------------------------------------------------------------------ Foxglove → ROS
    def advertise(self, event: ServerEvent) -> str | None:
        """A client advertised a channel: accepted (None), or the reason it is refused."""
        refusal = client_channel_refusal(event.topic, event.schema_name, event.encoding, self.client_topics)
        if refusal is not None:
            return f"client {event.client}: {refusal}"
        self._client_channels[(event.client, event.channel)] = event.topic
        return None

    def unadvertise(self, event: ServerEvent) -> None:
        self._client_channels.pop((event.client, event.channel), None)

    def client_message(self, event: ServerEvent) -> ClientMessage:
        """What to republish for a client's message; raises :class:`ClientCommandError` naming
        the client when the channel was never accepted or the message is not a JSON String."""
        topic = self._client_channels.get((event.client, event.channel))
        if topic is None:
            raise ClientCommandError(f"client {event.client}: message on channel {event.channel}, which was "
                                     "refused or never advertised")
        try:
            return ClientMessage(topic, client_string(JSON_ENCODING, event.data))
        except ClientCommandError as error:
            raise ClientCommandError(f"client {event.client} on {topic}: {error}") from None
