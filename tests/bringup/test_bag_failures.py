"""Every bad bag ends bag_play / bag_record with one line and its documented exit code, no
traceback; a message whose bytes do not deserialize is reported, skipped and counted."""

import shutil
import subprocess

import pytest
from rclpy.serialization import serialize_message
from std_msgs.msg import String

from door_bringup.bags import player, recorder
from door_bringup.bags.exit_codes import BagExit
from door_bringup.bags.storage import BagWriter, StorageFormat


def _copy(shared_data, folder, tmp_path):
    bag = tmp_path / folder
    shutil.copytree(shared_data / "bags" / folder, bag)
    for path in bag.iterdir():
        path.chmod(0o644)
    return bag


def _truncate(bag, suffix):
    storage = next(bag.glob(f"*{suffix}"))
    data = storage.read_bytes()
    storage.write_bytes(data[: len(data) // 2])


def _zero_out(bag, suffix):
    storage = next(bag.glob(f"*{suffix}"))
    data = bytearray(storage.read_bytes())
    data[len(data) // 3: len(data) // 3 + 200] = b"\xab" * 200
    storage.write_bytes(bytes(data))


def _bad_bags(shared_data, tmp_path):
    """(name, bag path, expected exit code, a word of the message)."""
    sqlite, mcap = (_copy(shared_data, f, tmp_path) for f in ("rosbag2_talker_sqlite3", "rosbag2_talker_mcap"))
    truncated_sqlite, truncated_mcap = (_copy(shared_data, f, tmp_path / "t") for f in
                                        ("rosbag2_talker_sqlite3", "rosbag2_talker_mcap"))
    _truncate(truncated_sqlite, ".db3")
    _truncate(truncated_mcap, ".mcap")
    _zero_out(mcap, ".mcap")
    not_yaml = tmp_path / "not_yaml"
    not_yaml.mkdir()
    (not_yaml / "metadata.yaml").write_text("{{{{ not: yaml: [")
    no_keys = tmp_path / "no_keys"
    no_keys.mkdir()
    (no_keys / "metadata.yaml").write_text("rosbag2_bagfile_information:\n  version: 9\n")
    lost_file = _copy(shared_data, "rosbag2_talker_sqlite3", tmp_path / "lost")
    next(lost_file.glob("*.db3")).unlink()
    bad_qos = _copy(shared_data, "rosbag2_talker_sqlite3", tmp_path / "qos")
    metadata = bad_qos / "metadata.yaml"
    metadata.write_text(metadata.read_text().replace('offered_qos_profiles: "', 'offered_qos_profiles: "not: [yaml', 1))
    return [("truncated db3", truncated_sqlite, BagExit.CORRUPT_STORAGE, "sqlite3"),
            ("truncated mcap", truncated_mcap, BagExit.CORRUPT_STORAGE, "mcap"),
            ("corrupt mcap records", mcap, BagExit.CORRUPT_STORAGE, "mcap"),
            ("metadata not YAML", not_yaml, BagExit.BAD_METADATA, "not YAML"),
            ("metadata missing keys", no_keys, BagExit.BAD_METADATA, "relative_file_paths"),
            ("storage file missing", lost_file, BagExit.BAD_METADATA, "missing"),
            ("offered QoS not YAML", bad_qos, BagExit.BAD_METADATA, "topics_with_message_count"),
            ("no bag at the path", tmp_path / "nowhere", BagExit.NOT_FOUND, "neither"),
            ("a plain file", sqlite / "metadata.yaml", BagExit.BAD_METADATA, "unknown storage")]


def test_every_bad_bag_is_one_line_and_its_exit_code(shared_data, tmp_path, capsys):
    for name, bag, code, word in _bad_bags(shared_data, tmp_path):
        assert player.main([str(bag)]) == code, name
        lines = capsys.readouterr().err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("bag_play: ") and word in lines[0], (name, lines)


@pytest.mark.parametrize("rate", ["0", "-2", "inf", "nan"])
def test_a_bad_rate_is_a_usage_error(shared_data, capsys, rate):
    bag = shared_data / "bags" / "rosbag2_talker_sqlite3"
    assert player.main([str(bag), "--rate", rate]) == BagExit.USAGE
    assert "--rate" in capsys.readouterr().err


def test_the_installed_player_prints_no_traceback(workspace, tmp_path):
    result = subprocess.run([str(workspace.executable("door_bringup", "bag_play")), str(tmp_path / "nowhere")],
                            env=workspace.environment(), capture_output=True, text=True, timeout=60)
    assert result.returncode == BagExit.NOT_FOUND
    assert "Traceback" not in result.stderr and len(result.stderr.strip().splitlines()) == 1


def test_zstd_without_mcap_is_a_usage_error(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_:
        recorder.main([str(tmp_path / "bag"), "--compression", "zstd"])
    assert exit_.value.code == BagExit.USAGE and "--storage mcap" in capsys.readouterr().err
    assert not (tmp_path / "bag").exists()


def test_recording_over_an_existing_bag_is_refused(tmp_path, capsys):
    (tmp_path / "taken").mkdir()
    assert recorder.main([str(tmp_path / "taken")]) == BagExit.CANNOT_WRITE
    assert "exists already" in capsys.readouterr().err


@pytest.mark.ros
def test_messages_that_do_not_deserialize_are_skipped_and_counted(workspace, tmp_path):
    bag = tmp_path / "bag"
    with BagWriter(bag, StorageFormat.MCAP) as writer:
        for index in range(5):
            writer.write("/door_task/state", "std_msgs/msg/String", 1_000 + index,
                         serialize_message(String(data=f"state {index}")))
        writer.write("/door_task/state", "std_msgs/msg/String", 2_000, b"\x00\x01\x00\x00\xff\xff\xff\x7f")  # 2 GB string
    result = subprocess.run([str(workspace.executable("door_bringup", "bag_play")), str(bag), "--rate", "100"],
                            env=workspace.environment(), capture_output=True, text=True, timeout=60)
    output = result.stdout + result.stderr
    assert result.returncode == BagExit.SKIPPED_MESSAGES, output
    assert "played 5 of 6 messages" in output and "skipped 1 that did not deserialize" in output
    assert "does not deserialize as std_msgs/msg/String" in output and "Traceback" not in output
