"""ament_python package door_bringup: Runs the graph without ros2 launch, records and plays rosbag2 bags, operator console."""

import os
from glob import glob

from setuptools import find_packages, setup

PACKAGE = "door_bringup"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(exclude=["test", "tests"]),
    package_data={"": ["py.typed"]},  # PEP 561: the packages are typed
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
        (f"share/{PACKAGE}/launch", glob("launch/*.launch.py")),
        # The repository's node parameter files, for installed use; the robot profiles
        # (params/robot_*.yaml) are door_robot's and installed by door_robot.
        (f"share/{PACKAGE}/params", sorted(p for p in glob("../../params/*.yaml")
                                           if not os.path.basename(p).startswith("robot_"))),
    ],
    install_requires=["setuptools"],
    zip_safe=True,
    maintainer="Door traversal team",
    maintainer_email="door-traversal@example.org",
    description="Runs the graph without ros2 launch, records and plays rosbag2 bags, operator console.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "door_graph = door_bringup.graph:main",
            "bag_play = door_bringup.bags.player:main",
            "bag_record = door_bringup.bags.recorder:main",
            "door_task = door_bringup.door_task:main",
        ],
    },
)
