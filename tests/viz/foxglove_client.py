"""A minimal Foxglove WebSocket client for tests (protocol ``foxglove.sdk.v1``), with the
``websockets`` package: reads the server's advertisements, subscribes to a channel, decodes
its binary message frames, advertises a client channel and publishes on it, fetches assets.

Frames (little endian): server message data = 0x01, u32 subscription id, u64 log time (ns),
payload; server asset response = 0x04, u32 request id, u8 status, u32 error length, error,
data; client message data = 0x01, u32 client channel id, payload.
"""

from __future__ import annotations

import json
import struct
import time
from contextlib import ExitStack

from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

SUBPROTOCOL = "foxglove.sdk.v1"


class FoxgloveClient:
    def __init__(self, url: str, timeout_s: float = 30.0) -> None:
        self._open = ExitStack()  # websockets ≥ 17.1 wants its connection entered as a context manager
        self.socket = self._open.enter_context(connect(url, subprotocols=[SUBPROTOCOL], open_timeout=timeout_s,
                                                       max_size=None))
        self.server_info: dict = {}
        self.channels: dict[str, dict] = {}  # topic -> advertised channel
        self.messages: dict[int, list[bytes]] = {}  # subscription id -> payloads
        self.assets: dict[int, tuple[int, bytes]] = {}  # request id -> (status, data or error)
        self.statuses: list[dict] = []

    def close(self) -> None:
        self._open.close()

    def pump(self, condition, timeout_s: float) -> bool:
        """Read frames until ``condition()`` holds or the deadline passes."""
        deadline = time.monotonic() + timeout_s
        while not condition():
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                return False
            try:
                frame = self.socket.recv(timeout=min(remaining, 0.2))
            except TimeoutError:
                continue
            except ConnectionClosed:
                return condition()
            self._handle(frame)
        return True

    def _handle(self, frame: str | bytes) -> None:
        if isinstance(frame, str):
            document = json.loads(frame)
            if document["op"] == "serverInfo":
                self.server_info = document
            elif document["op"] == "advertise":
                self.channels.update({c["topic"]: c for c in document["channels"]})
            elif document["op"] == "status":
                self.statuses.append(document)
            return
        if frame[0] == 0x01:
            subscription, _log_time = struct.unpack_from("<IQ", frame, 1)
            self.messages.setdefault(subscription, []).append(bytes(frame[13:]))
        elif frame[0] == 0x04:
            request, status, error_length = struct.unpack_from("<IBI", frame, 1)
            self.assets[request] = (status, bytes(frame[10 + error_length:]) if status == 0
                                    else bytes(frame[10:10 + error_length]))

    def subscribe(self, subscription_id: int, topic: str) -> None:
        channel = self.channels[topic]["id"]
        self.socket.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": subscription_id, "channelId": channel}]}))

    def advertise(self, channel_id: int, topic: str, schema_name: str = "std_msgs/msg/String") -> None:
        self.socket.send(json.dumps({"op": "advertise", "channels": [
            {"id": channel_id, "topic": topic, "encoding": "json", "schemaName": schema_name}]}))

    def publish_json(self, channel_id: int, document: dict) -> None:
        self.socket.send(struct.pack("<BI", 0x01, channel_id) + json.dumps(document).encode())

    def fetch_asset(self, request_id: int, uri: str) -> None:
        self.socket.send(json.dumps({"op": "fetchAsset", "uri": uri, "requestId": request_id}))
