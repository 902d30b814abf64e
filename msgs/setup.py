"""ament_python package door_contract: Message contract of the door-traversal graph: topics, QoS, frames, units, converters."""

from setuptools import find_packages, setup

PACKAGE = "door_contract"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(exclude=["test", "tests"]),
    package_data={"": ["py.typed"]},  # PEP 561: the packages are typed
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
        # colcon hook (listed in colcon.pkg): DDS discovery stays on this machine by default
        (f"share/{PACKAGE}/hook", ["hook/discovery_range.dsv", "hook/discovery_range.sh"]),
    ],
    install_requires=["setuptools"],
    zip_safe=True,
    maintainer="Door traversal team",
    maintainer_email="door-traversal@example.org",
    description="Message contract of the door-traversal graph: topics, QoS, frames, units, converters.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
        ],
    },
)
