"""rosbag2 files without rosbag2: storage-level reading, writing, recording and playing."""
