"""Bags keep what real ``ros2 bag play`` needs: each topic's offered QoS (read back from
metadata.yaml), ``ros_distro: jazzy``, optional zstd mcap chunks; the player restores
transient-local topics, the recorder records a latched message published before it joined."""

import signal
import subprocess

import pytest
import rclpy
import yaml
from diagnostic_msgs.msg import DiagnosticArray
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from rclpy.serialization import deserialize_message, serialize_message
from ros_helpers import executor_for, spin_until
from rosbags.interfaces import QosDurability, QosReliability
from std_msgs.msg import String

from door_bringup.bags.qos import offered_qos, playback_profile
from door_bringup.bags.recorder import message_digest, recorded_key
from door_bringup.bags.storage import BagError, BagWriter, Compression, StorageFormat, read_messages, recorded_qos
from door_contract.converters.diagnostics import status_values
from door_contract.node_support import create_contract_publisher
from door_contract.qos import matching_subscription
from door_contract.topics import Topics

LATCHED = offered_qos(Topics.TASK_STATE.qos.to_profile())
VOLATILE = offered_qos(Topics.OPERATOR.qos.to_profile())
BEST_EFFORT = offered_qos(Topics.CLOCK.qos.to_profile())
OTHER_LATCHED, OTHER_VOLATILE = "/other_robot/state", "/other_robot/command"  # not in the contract


@pytest.mark.parametrize("storage", list(StorageFormat))
def test_offered_qos_and_distro_are_written_and_read_back(tmp_path, storage):
    with BagWriter(tmp_path / "bag", storage) as writer:
        writer.add_topic("/door_task/state", "std_msgs/msg/String", [LATCHED])
        writer.add_topic("/door_task/operator", "std_msgs/msg/String", [VOLATILE, VOLATILE])
        writer.write("/door_task/state", "std_msgs/msg/String", 5, serialize_message(String(data="DETECT_DOOR")))
        writer.write("/unknown", "std_msgs/msg/String", 6, serialize_message(String(data="x")))
    qos = recorded_qos(tmp_path / "bag")
    assert qos["/door_task/state"] == [LATCHED] and LATCHED.durability is QosDurability.TRANSIENT_LOCAL
    assert qos["/door_task/operator"] == [VOLATILE, VOLATILE] and qos["/unknown"] == []
    info = yaml.safe_load((tmp_path / "bag" / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    assert info["ros_distro"] == "jazzy" and info["version"] == 9


def test_real_bags_qos_strings_are_read(shared_data):
    qos = recorded_qos(shared_data / "bags" / "rosbag2_talker_sqlite3")
    assert qos["/topic"][0].reliability is QosReliability.RELIABLE
    assert qos["/rosout"][0].durability is QosDurability.TRANSIENT_LOCAL
    rosout = playback_profile(qos["/rosout"], QoSProfile(depth=100))
    assert rosout.durability is DurabilityPolicy.TRANSIENT_LOCAL
    assert qos["/rosout"][0].depth == 0 and rosout.depth == 100  # unknown when recorded: not 1 (stop 43's CI lost a line)


def test_zstd_mcap_round_trip_is_byte_identical_and_smaller(tmp_path):
    sent = [serialize_message(String(data="door " * 2000 + str(i))) for i in range(50)]
    for compression in Compression:
        with BagWriter(tmp_path / compression.value, StorageFormat.MCAP, compression) as writer:
            for i, data in enumerate(sent):
                writer.write("/door_task/report", "std_msgs/msg/String", 1_000 + i, data)
        assert [m.data for m in read_messages(tmp_path / compression.value)] == sent
    sizes = {c: sum(f.stat().st_size for f in (tmp_path / c.value).glob("*.mcap")) for c in Compression}
    assert sizes[Compression.ZSTD] * 10 < sizes[Compression.NONE]


def test_zstd_is_refused_for_sqlite3(tmp_path):
    with pytest.raises(BagError, match="mcap"):
        BagWriter(tmp_path / "bag", StorageFormat.SQLITE3, Compression.ZSTD)


def test_player_and_recorder_profiles_follow_the_offers():
    fallback = QoSProfile(depth=7)
    latched = playback_profile([LATCHED], fallback)
    assert (latched.durability, latched.depth) == (DurabilityPolicy.TRANSIENT_LOCAL, 1)
    mixed = playback_profile([LATCHED, VOLATILE], fallback)
    assert (mixed.durability, mixed.reliability) == (DurabilityPolicy.VOLATILE, ReliabilityPolicy.RELIABLE)
    assert playback_profile([BEST_EFFORT], fallback).reliability is ReliabilityPolicy.BEST_EFFORT
    assert playback_profile([], fallback) is fallback
    latched, best_effort = Topics.TASK_STATE.qos.to_profile(), Topics.CLOCK.qos.to_profile()
    record = matching_subscription([latched, best_effort], fallback)
    assert (record.reliability, record.durability) == (ReliabilityPolicy.BEST_EFFORT, DurabilityPolicy.VOLATILE)
    assert matching_subscription([latched], fallback).durability is DurabilityPolicy.TRANSIENT_LOCAL
    assert matching_subscription([], fallback) is fallback


@pytest.mark.ros
def test_recorder_stores_offered_qos_and_the_latched_message_it_joined_after(workspace, rclpy_context, tmp_path):
    """... and its heartbeat names a digest of the last message it wrote on each latched topic."""
    node = rclpy.create_node("bag_qos_test", context=rclpy_context)
    state = create_contract_publisher(node, Topics.TASK_STATE)
    operator = create_contract_publisher(node, Topics.OPERATOR)
    state.publish(String(data="WALK_TO_DOOR"))  # before the recorder exists: only latching delivers it
    heartbeats = []  # the recorder's own counts and digests, on /diagnostics
    node.create_subscription(DiagnosticArray, Topics.DIAGNOSTICS.name, lambda a: heartbeats.append(
        status_values(a, "bag_recorder")), 10)
    def recorded(key: str) -> str | None:
        return next((h[key] for h in reversed(heartbeats) if h and key in h), None)
    executor = executor_for(node, rclpy_context)
    recorder = subprocess.Popen([str(workspace.executable("door_bringup", "bag_record")), str(tmp_path / "bag"),
                                 "--storage", "mcap", "--compression", "zstd",
                                 "--topics", Topics.TASK_STATE.name, Topics.OPERATOR.name],
                                env=workspace.environment(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        assert spin_until(executor, lambda: operator.get_subscription_count() > 0
                          and state.get_subscription_count() > 0, 60.0)
        operator.publish(String(data="approve 3"))
        assert spin_until(executor, lambda: int(recorded("recorded") or 0) >= 2, 60.0)
        assert recorded(recorded_key(Topics.TASK_STATE.name)) == message_digest(String(data="WALK_TO_DOOR"))
        assert recorded(recorded_key(Topics.OPERATOR.name)) is None  # volatile: no digest
        state.publish(String(data="DONE"))  # what the main job waits for before it stops the graph
        done = message_digest(String(data="DONE"))
        assert spin_until(executor, lambda: recorded(recorded_key(Topics.TASK_STATE.name)) == done, 60.0)
    finally:
        recorder.send_signal(signal.SIGINT)
        output = recorder.communicate(timeout=30)[0]
    assert recorder.returncode == 0, output
    qos = recorded_qos(tmp_path / "bag")
    assert [q.durability for q in qos[Topics.TASK_STATE.name]] == [QosDurability.TRANSIENT_LOCAL], output
    assert [q.durability for q in qos[Topics.OPERATOR.name]] == [QosDurability.VOLATILE]
    words = [(m.topic, deserialize_message(m.data, String).data) for m in read_messages(tmp_path / "bag")]
    assert sorted(words) == sorted([(Topics.TASK_STATE.name, "WALK_TO_DOOR"), (Topics.OPERATOR.name, "approve 3"),
                                    (Topics.TASK_STATE.name, "DONE")]), output
    node.destroy_node()


@pytest.mark.ros
def test_player_replays_a_latched_topic_transient_local(workspace, rclpy_context, tmp_path):
    """Topics outside the contract too: the QoS comes from the bag, not from door_contract."""
    with BagWriter(tmp_path / "bag", StorageFormat.SQLITE3) as writer:
        writer.add_topic(OTHER_LATCHED, "std_msgs/msg/String", [LATCHED])
        writer.add_topic(OTHER_VOLATILE, "std_msgs/msg/String", [VOLATILE])
        for i, (topic, word) in enumerate([(OTHER_LATCHED, "DONE"), (OTHER_VOLATILE, "approve 1"),
                                           (OTHER_LATCHED, "DONE")]):
            writer.write(topic, "std_msgs/msg/String", i * 1_000_000_000, serialize_message(String(data=word)))
    node = rclpy.create_node("bag_play_qos_test", context=rclpy_context)
    executor = executor_for(node, rclpy_context)
    player = subprocess.Popen([str(workspace.executable("door_bringup", "bag_play")), str(tmp_path / "bag")],
                              env=workspace.environment(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    offered = {}
    try:
        def publishers_seen() -> bool:
            for topic in (OTHER_LATCHED, OTHER_VOLATILE):
                infos = [i for i in node.get_publishers_info_by_topic(topic) if i.node_name == "bag_player"]
                if infos:
                    offered[topic] = infos[0].qos_profile
            return len(offered) == 2
        assert spin_until(executor, publishers_seen, 60.0)
    finally:
        output = player.communicate(timeout=60)[0]
    assert offered[OTHER_LATCHED].durability is DurabilityPolicy.TRANSIENT_LOCAL, output
    assert offered[OTHER_VOLATILE].durability is DurabilityPolicy.VOLATILE
    node.destroy_node()
