"""The Foxglove bridge's routing tables without ROS: each topic offered once (never one without a
schema); a ROS subscription from the first watching client to the last; client channels
accepted only on the allowed topics, and their messages republished there or refused with
the client and the reason."""

import pytest

from door_contract.topics import Topics
from door_viz.foxglove_core import ClientCommandError, EventKind, ServerEvent
from door_viz.foxglove_routes import ClientMessage, Routes, Watch, WatchChange

OPERATOR = Topics.OPERATOR.name
STRING = "std_msgs/msg/String"


def _subscribe(client, channel, kind=EventKind.SUBSCRIBE):
    return ServerEvent(kind, client, channel)


def test_each_topic_is_offered_once_and_one_without_a_schema_never():
    routes = Routes((OPERATOR,))
    graph = [("/odom", ["nav_msgs/msg/Odometry"]), ("/custom", ["my_msgs/msg/Thing"]), ("/typeless", [])]
    assert routes.unseen(graph) == [("/odom", "nav_msgs/msg/Odometry"), ("/custom", "my_msgs/msg/Thing")]
    routes.route("/odom", "nav_msgs/msg/Odometry", 3)
    routes.unrouted("/custom")
    assert routes.unseen(graph) == [] and routes.channels == 1
    assert routes.unseen([*graph, ("/clock", ["rosgraph_msgs/msg/Clock"])]) == [("/clock", "rosgraph_msgs/msg/Clock")]


def test_a_ros_subscription_lives_from_the_first_watching_client_to_the_last():
    routes = Routes(())
    routes.route("/odom", "nav_msgs/msg/Odometry", 3)
    start = WatchChange(Watch.START, "/odom", "nav_msgs/msg/Odometry")
    assert routes.watch(_subscribe(1, 3)) == start
    assert routes.watch(_subscribe(2, 3)) is None  # already watched
    assert routes.watch(_subscribe(1, 3, EventKind.UNSUBSCRIBE)) is None  # client 2 still watches
    assert routes.watch(_subscribe(2, 3, EventKind.UNSUBSCRIBE)) == WatchChange(Watch.STOP, "/odom",
                                                                                 "nav_msgs/msg/Odometry")
    assert routes.watch(_subscribe(2, 3, EventKind.UNSUBSCRIBE)) is None  # nobody left to drop
    assert routes.watch(_subscribe(1, 99)) is None  # a channel the bridge never offered
    assert routes.watch(_subscribe(1, 3)) == start  # watched again


def _advertise(client, channel, topic=OPERATOR, schema=STRING, encoding="json"):
    return ServerEvent(EventKind.CLIENT_ADVERTISE, client, channel, topic, schema, encoding)


def _message(client, channel, data=b'{"data": "approve 7"}'):
    return ServerEvent(EventKind.CLIENT_MESSAGE, client, channel, data=data)


def test_a_clients_messages_on_an_accepted_channel_are_republished_on_its_topic():
    routes = Routes((OPERATOR,))
    assert routes.advertise(_advertise(4, 9)) is None
    assert routes.client_message(_message(4, 9)) == ClientMessage(OPERATOR, "approve 7")
    with pytest.raises(ClientCommandError, match=f"client 4 on {OPERATOR}: client message is not JSON"):
        routes.client_message(_message(4, 9, b"approve"))
    with pytest.raises(ClientCommandError, match="client 5: message on channel 9, which was refused or never"):
        routes.client_message(_message(5, 9))  # another client's channel 9 was never advertised
    routes.unadvertise(ServerEvent(EventKind.CLIENT_UNADVERTISE, 4, 9))
    with pytest.raises(ClientCommandError, match="client 4: message on channel 9"):
        routes.client_message(_message(4, 9))


@pytest.mark.parametrize("event, reason", [
    (_advertise(4, 1, topic=Topics.ARM_TRAJECTORY.name), "client 4: clients may publish only on"),
    (_advertise(4, 2, schema="geometry_msgs/msg/Twist"), "not geometry_msgs/msg/Twist"),
    (_advertise(4, 3, encoding="cdr"), "publish JSON"),
])
def test_a_channel_outside_the_allowed_topics_types_or_encoding_is_refused_and_its_messages_too(event, reason):
    routes = Routes((OPERATOR,))
    assert reason in routes.advertise(event)
    with pytest.raises(ClientCommandError, match="refused or never advertised"):
        routes.client_message(_message(4, event.channel))
