"""ROS 2 node ``/foxglove_bridge``: the graph, live, on a Foxglove WebSocket (foxglove-sdk).

Every ROS topic is advertised as a channel with its ROS 2 schema (``ros2msg``) and CDR
messages; a ROS subscription is made only while a client subscribes (QoS matched to the
publishers, so latched topics arrive at once). Foxglove clients may publish JSON
``std_msgs/String`` messages on the allowed topics (``/door_task/operator``: approve from a
Publish or button panel); the bridge republishes them on ROS. The URDF's ``package://``
meshes are served to the 3-D panel. Bound to 127.0.0.1 unless ``address`` says otherwise.
The ROS-free parts are :mod:`door_viz.foxglove_core` (schemas, client commands, assets, the
listener queue) and :mod:`door_viz.foxglove_routes` (what is forwarded where).
"""

from __future__ import annotations

from typing import Any, cast

import foxglove
from foxglove.websocket import Capability, StatusLevel
from rclpy.clock import Clock, ClockType
from rclpy.node import Node
from rclpy.qos import QoSProfile
from std_msgs.msg import String

from door_contract.converters.diagnostics import Health
from door_contract.errors import ParameterRangeError
from door_contract.node_support import Heartbeat, declare_parameters, node_main
from door_contract.qos import matching_subscription
from door_contract.topics import Topics, interface_class
from door_robot.errors import RobotModelError
from door_robot.profile import load_profile
from door_viz.foxglove_core import (
    JSON_ENCODING,
    ClientCommandError,
    EventKind,
    SchemaLibrary,
    ServerEvent,
    ServerEvents,
    mesh_asset,
)
from door_viz.foxglove_routes import Routes, Watch, WatchChange
from door_viz.parameters import FOXGLOVE_NODE, FOXGLOVE_PARAMETERS

__all__ = ["FoxgloveBridgeNode", "main"]

EVENT_PERIOD_S = 0.02


def contract_profile(topic: str) -> QoSProfile:
    """The contract's QoS of ``topic``; reliable, volatile, depth 10 for others."""
    spec = next((t for t in Topics.all() if t.name == topic), None)
    return spec.qos.to_profile() if spec is not None else QoSProfile(depth=10)


class FoxgloveBridgeNode(Node):
    def __init__(self) -> None:
        super().__init__(FOXGLOVE_NODE)
        p = declare_parameters(self, FOXGLOVE_PARAMETERS)
        try:
            urdf_path = load_profile(p["robot_profile"]).urdf_path
        except RobotModelError as error:
            raise ParameterRangeError(f"parameter 'robot_profile': {error}") from None
        self.schemas, self.events, self.sdk_context = SchemaLibrary(), ServerEvents(), foxglove.Context()
        self.routes = Routes(p["client_topics"])
        self.channels: dict[str, foxglove.Channel] = {}
        self.ros_subscriptions: dict[str, Any] = {}
        # one publisher per allowed topic, made now, so subscribers have matched it before a
        # client's first message (a publisher made on demand would lose that message)
        self.client_publishers = {topic: self.create_publisher(String, topic, contract_profile(topic))
                                  for topic in p["client_topics"]}
        self.forwarded = 0
        try:
            self.server = foxglove.start_server(
                name="door_traversal", host=p["address"], port=p["port"], capabilities=[Capability.ClientPublish],
                supported_encodings=[JSON_ENCODING], server_listener=self.events, context=self.sdk_context,
                asset_handler=lambda uri: mesh_asset(uri, urdf_path))
        except Exception as error:  # the SDK raises RuntimeError subclasses for bind failures
            raise ParameterRangeError(f"parameter 'address'/'port' = {p['address']}:{p['port']}: "
                                      f"cannot serve ({error})") from None
        self.heartbeat = Heartbeat(self)
        steady = Clock(clock_type=ClockType.STEADY_TIME)
        self.create_timer(p["discovery_period"], self._discover, clock=steady)
        self.create_timer(EVENT_PERIOD_S, self._handle_events, clock=steady)
        self._discover()
        self.get_logger().info(f"Foxglove: open ws://{p['address']}:{self.server.port} "
                               f"(clients may publish on {', '.join(p['client_topics'])})")

    # ------------------------------------------------------------------ ROS → Foxglove
    def _discover(self) -> None:
        for topic, type_name in self.routes.unseen(self.get_topic_names_and_types()):
            schema = self.schemas.schema(type_name)
            if schema is None:
                self.routes.unrouted(topic)  # unknown type: not forwarded (said once)
                self.get_logger().warning(f"{topic}: no schema for {type_name}, not forwarded")
                continue
            channel = foxglove.Channel(topic, message_encoding="cdr", context=self.sdk_context,
                                       schema=foxglove.Schema(name=type_name, encoding="ros2msg", data=schema))
            self.channels[topic] = channel
            self.routes.route(topic, type_name, channel.id())
        self.heartbeat.update(Health.OK, "serving", channels=self.routes.channels, forwarded=self.forwarded,
                              watched=len(self.ros_subscriptions))

    def _watch(self, change: WatchChange) -> None:
        topic = change.topic
        if change.watch is Watch.START:
            offered = [info.qos_profile for info in self.get_publishers_info_by_topic(topic)]
            channel = self.channels[topic]  # raw=True: the callback gets the CDR bytes (rclpy annotates the type)
            self.ros_subscriptions[topic] = self.create_subscription(
                interface_class(change.type_name), topic, lambda data: self._forward(channel, cast(bytes, data)),
                matching_subscription(offered, contract_profile(topic)), raw=True)
        elif topic in self.ros_subscriptions:
            self.destroy_subscription(self.ros_subscriptions.pop(topic))

    def _forward(self, channel: foxglove.Channel, data: bytes) -> None:
        channel.log(bytes(data), log_time=self.get_clock().now().nanoseconds)
        self.forwarded += 1

    # ------------------------------------------------------------------ Foxglove → ROS
    def _handle_events(self) -> None:
        for event in self.events.drain():
            if event.kind in (EventKind.SUBSCRIBE, EventKind.UNSUBSCRIBE):
                change = self.routes.watch(event)
                if change is not None:
                    self._watch(change)
            elif event.kind is EventKind.CLIENT_ADVERTISE:
                refusal = self.routes.advertise(event)
                if refusal is not None:
                    self._refuse(refusal)
            elif event.kind is EventKind.CLIENT_UNADVERTISE:
                self.routes.unadvertise(event)
            else:
                self._client_message(event)

    def _client_message(self, event: ServerEvent) -> None:
        try:
            message = self.routes.client_message(event)
        except ClientCommandError as error:
            self._refuse(str(error))
            return
        self.client_publishers[message.topic].publish(String(data=message.text))
        self.get_logger().info(f"Foxglove client {event.client} on {message.topic}: {message.text!r}")

    def _refuse(self, reason: str) -> None:
        self.get_logger().warning(reason)
        self.server.publish_status(reason, StatusLevel.Warning)

    def destroy_node(self) -> None:
        self.server.stop()
        super().destroy_node()


main = node_main(FoxgloveBridgeNode, __name__)
