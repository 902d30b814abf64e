"""The Foxglove bridge's ROS-free part: ROS 2 schemas, client commands, channel refusals, the
listener queue; and the shipped layout is the generated one and names contract topics only."""

import json

import pytest

from door_contract.topics import Topics
from door_viz.foxglove_core import (
    ClientCommandError,
    EventKind,
    SchemaLibrary,
    ServerEvents,
    client_channel_refusal,
    client_string,
)
from door_viz.layout import LAYOUT_FILE, layout_text, panel_configs


def test_schemas_are_ros2msg_with_their_dependencies():
    schemas = SchemaLibrary()
    pose = schemas.schema("geometry_msgs/msg/PoseStamped").decode()
    assert pose.startswith("std_msgs/Header header\n")
    assert "\nMSG: builtin_interfaces/Time\n" in pose and "=" * 80 in pose
    assert schemas.schema("tf2_msgs/msg/TFMessage") is not None
    assert schemas.schema("my_msgs/msg/Unknown") is None
    for topic in Topics.all():
        assert schemas.schema(topic.type_name) is not None, topic.name


def test_client_strings_are_json_std_msgs_strings():
    assert client_string("json", b'{"data": "approve 7"}') == "approve 7"
    for encoding, data in [("cdr", b'{"data": "x"}'), ("json", b"approve"), ("json", b'{"data": 7}'),
                           ("json", b'{"data": "x", "more": 1}'), ("json", b"\xff\xfe"), ("json", b"[" * 100000)]:
        with pytest.raises(ClientCommandError):
            client_string(encoding, data)


def test_only_allowed_topics_typed_string_in_json_are_accepted():
    allowed = (Topics.OPERATOR.name,)
    assert client_channel_refusal(Topics.OPERATOR.name, "std_msgs/msg/String", "json", allowed) is None
    assert client_channel_refusal(Topics.OPERATOR.name, "", "json", allowed) is None
    assert "only on" in client_channel_refusal(Topics.ARM_TRAJECTORY.name, "std_msgs/msg/String", "json", allowed)
    assert "not geometry" in client_channel_refusal(Topics.OPERATOR.name, "geometry_msgs/msg/Twist", "json", allowed)
    assert "JSON" in client_channel_refusal(Topics.OPERATOR.name, "std_msgs/msg/String", "cdr", allowed)


class _Client:
    id = 4


class _Channel:
    id, topic, encoding, schema_name = 9, "/door_task/operator", "json", "std_msgs/msg/String"


def test_listener_calls_are_queued_in_order():
    events = ServerEvents()
    events.on_subscribe(_Client(), _Channel())
    events.on_client_advertise(_Client(), _Channel())
    events.on_message_data(_Client(), 9, b'{"data": "pause"}')
    drained = events.drain()
    assert [e.kind for e in drained] == [EventKind.SUBSCRIBE, EventKind.CLIENT_ADVERTISE, EventKind.CLIENT_MESSAGE]
    assert drained[2].data == b'{"data": "pause"}' and events.drain() == []


def test_shipped_layout_is_the_generated_one_and_names_only_contract_topics():
    assert LAYOUT_FILE.read_text() == layout_text(), "run python -m door_viz.layout"
    names = {topic.name for topic in Topics.all()}
    configs = panel_configs()
    named = set()
    for config in configs.values():
        named |= set(config.get("topics", {}))
        named |= {config[k] for k in ("topicName",) if k in config}
        named |= {v for k, v in config.get("imageMode", {}).items() if k.endswith("Topic")}
        named |= {config["topicPath"].split(".")[0]} if "topicPath" in config else set()
    assert named <= names and {Topics.ROBOT_DESCRIPTION.name, Topics.PROPOSAL_MARKERS.name} <= named
    buttons = [json.loads(c["value"])["data"] for k, c in configs.items() if k.startswith("Publish!")]
    assert {"pause", "stop", "resume", "abort"} <= set(buttons) and "approve 1" in buttons
