"""ament_python package door_robot: Robot profiles (TALOS, Atlas v4, DRC-HUBO) and Pinocchio kinematics; ROS-free."""

from glob import glob

from setuptools import find_packages, setup

PACKAGE = "door_robot"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(exclude=["test", "tests"]),
    package_data={"": ["py.typed"]},  # PEP 561: the packages are typed
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
        # The robot profiles, this package's own profiles/ (the checkout's params/ links to them),
        # found in the share when installed (door_robot.locations.params_dir; the folder name is
        # locations.PROFILES_SHARE). Only paths inside this folder: the package builds anywhere.
        (f"share/{PACKAGE}/profiles", sorted(glob("profiles/robot_*.yaml"))),
    ],
    install_requires=["setuptools"],
    zip_safe=True,
    maintainer="Door traversal team",
    maintainer_email="door-traversal@example.org",
    description="Robot profiles (TALOS, Atlas v4, DRC-HUBO) and Pinocchio kinematics; ROS-free.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
        ],
    },
)
