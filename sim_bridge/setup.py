"""ament_python package door_sim_bridge: PyBullet hardware-simulation bridge: robot, door with latch and springs, head RGB-D camera."""

from setuptools import find_packages, setup

PACKAGE = "door_sim_bridge"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(exclude=["test", "tests"]),
    package_data={"": ["py.typed"]},  # PEP 561: the packages are typed
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
    ],
    install_requires=["setuptools"],
    zip_safe=True,
    maintainer="Door traversal team",
    maintainer_email="door-traversal@example.org",
    description="PyBullet hardware-simulation bridge: robot, door with latch and springs, head RGB-D camera.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "sim_bridge = door_sim_bridge.sim_bridge_node:main",
        ],
    },
)
