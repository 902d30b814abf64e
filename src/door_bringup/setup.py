"""ament_python package door_bringup: Runs the graph without ros2 launch, records and plays rosbag2 bags, operator console."""

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
        # The node parameter files, this package's own params/ (the checkout's params/ links to
        # them), for installed use (launch/door_task.launch.py). Only paths inside this folder:
        # the package builds anywhere. The robot profiles they name are door_robot's.
        (f"share/{PACKAGE}/params", sorted(glob("params/*.yaml"))),
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
