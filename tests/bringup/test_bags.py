"""rosbag2 without rosbag2: the real bags are read and played completely; record → play round trip."""

import signal
import subprocess

import pytest
import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from rclpy.serialization import deserialize_message, serialize_message
from ros_helpers import executor_for, spin_until
from sensor_msgs.msg import Image
from std_msgs.msg import String

from door_bringup.bags.player import PlaybackOptions, PlaybackOptionsError, playback_offsets
from door_bringup.bags.storage import BagError, BagWriter, StorageFormat, list_topics, read_messages
from door_contract.topics import Topics, interface_class

REAL_BAGS = {  # folder: {topic: count} (SOURCES.md 1b, 1c)
    "rosbag2_talker_sqlite3": {"/topic": 10, "/rosout": 10},
    "rosbag2_talker_mcap": {"/topic": 10, "/rosout": 10},
    "ros2bag_tools_images_sqlite3": {"/image": 3},
}


@pytest.mark.parametrize("folder", sorted(REAL_BAGS))
def test_real_bags_are_read_completely(shared_data, folder):
    topics = {t.name: t.message_count for t in list_topics(shared_data / "bags" / folder)}
    assert topics == REAL_BAGS[folder]


def test_real_image_bag_decodes(shared_data):
    messages = list(read_messages(shared_data / "bags" / "ros2bag_tools_images_sqlite3"))
    images = [deserialize_message(m.data, Image) for m in messages]
    assert [list(i.data) for i in images] == [[0, 128, 128, 255]] * 3
    assert [m.timestamp_ns for m in messages] == sorted(m.timestamp_ns for m in messages)


def test_talker_strings_are_in_order(shared_data):
    strings = [deserialize_message(m.data, String).data
               for m in read_messages(shared_data / "bags" / "rosbag2_talker_mcap", topics=["/topic"])]
    assert strings == [f"Hello, world! {i}" for i in range(10)]


@pytest.mark.parametrize("storage", list(StorageFormat))
def test_write_then_read_is_byte_identical(tmp_path, storage):
    sent = [serialize_message(String(data=f"door {i}")) for i in range(5)]
    with BagWriter(tmp_path / "bag", storage) as writer:
        for i, data in enumerate(sent):
            writer.write("/door_task/state", "std_msgs/msg/String", 1_000 + i, data)
    back = list(read_messages(tmp_path / "bag"))
    assert [m.data for m in back] == sent
    assert {m.type_name for m in back} == {"std_msgs/msg/String"}


def test_missing_bag_is_a_clear_error(tmp_path):
    with pytest.raises(BagError, match="metadata.yaml"):
        list(read_messages(tmp_path))


def test_playback_timing_scales_with_rate():
    assert playback_offsets([5_000_000_000, 6_000_000_000, 9_000_000_000], 2.0) == [0.0, 0.5, 2.0]
    with pytest.raises(PlaybackOptionsError, match="rate"):
        PlaybackOptions(rate=0.0)
    with pytest.raises(PlaybackOptionsError, match="--wait-for-all-acked"):
        PlaybackOptions(wait_for_all_acked_s=-1.0)


def _receive_all(context, node, messages, command, workspace):
    """Subscribe to the topics of ``messages``, run the player and spin until every one of
    them arrived (byte for byte) and the player exited, or 60 s. Counting arrivals would not do:
    /rosout also carries the player's own log lines."""
    topics_and_types = {m.topic: m.type_name for m in messages}
    received = {topic: [] for topic in topics_and_types}
    for topic, type_name in topics_and_types.items():
        node.create_subscription(interface_class(type_name), topic,
                                 lambda data, t=topic: received[t].append(bytes(data)), 100, raw=True)
    executor = executor_for(node, context)
    process = subprocess.Popen(command, env=workspace.environment(), stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
    try:
        spin_until(executor, lambda: all(m.data in received[m.topic] for m in messages)
                   and process.poll() is not None, 60.0)
    finally:
        if process.poll() is None:
            process.send_signal(signal.SIGINT)
        output = process.communicate(timeout=30)[0]
    return received, output


@pytest.mark.ros
@pytest.mark.parametrize("folder", ["rosbag2_talker_sqlite3", "rosbag2_talker_mcap", "ros2bag_tools_images_sqlite3"])
def test_player_delivers_every_message_of_real_bags(shared_data, workspace, rclpy_context, folder):
    bag = shared_data / "bags" / folder
    messages = list(read_messages(bag))
    node = rclpy.create_node("bag_play_test", context=rclpy_context)
    command = [str(workspace.executable("door_bringup", "bag_play")), str(bag), "--rate", "20",
               "--wait-for-subscribers", "20", "--wait-for-all-acked", "10"]
    received, output = _receive_all(rclpy_context, node, messages, command, workspace)
    for message in messages:
        assert message.data in received[message.topic], f"{message.topic}: a message of the bag was not delivered\n{output}"
    node.destroy_node()


@pytest.mark.ros
def test_record_then_play_round_trip(workspace, rclpy_context, tmp_path):
    node = rclpy.create_node("bag_record_test", context=rclpy_context)
    publisher = node.create_publisher(String, "/door_task/operator", 10)
    recorder_counts = []  # "recorded" reported by the recorder on /diagnostics
    node.create_subscription(DiagnosticArray, Topics.DIAGNOSTICS.name, lambda a: recorder_counts.extend(
        int(kv.value) for s in a.status if s.name == "bag_recorder" for kv in s.values if kv.key == "recorded"), 10)
    executor = executor_for(node, rclpy_context)
    recorder = subprocess.Popen([str(workspace.executable("door_bringup", "bag_record")),
                                 str(tmp_path / "run"), "--storage", "mcap", "--topics", "/door_task/operator"],
                                env=workspace.environment(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        assert spin_until(executor, lambda: publisher.get_subscription_count() > 0, 60.0)
        for word in ("approve", "pause", "resume", "approve"):
            publisher.publish(String(data=word))
        assert spin_until(executor, lambda: recorder_counts and recorder_counts[-1] >= 4, 60.0)
    finally:
        recorder.send_signal(signal.SIGINT)
        output = recorder.communicate(timeout=30)[0]
    assert recorder.returncode == 0, output
    words = [deserialize_message(m.data, String).data for m in read_messages(tmp_path / "run")]
    assert words == ["approve", "pause", "resume", "approve"], output
    node.destroy_node()
