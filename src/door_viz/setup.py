"""ament_python package door_viz: see the graph as a ROS user would (proposal markers, Foxglove bridge, layout)."""

from glob import glob

from setuptools import find_packages, setup

PACKAGE = "door_viz"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(exclude=["test", "tests"]),
    package_data={"": ["py.typed"]},  # PEP 561: the packages are typed
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
        (f"share/{PACKAGE}/layouts", glob("layouts/*.json")),
    ],
    install_requires=["setuptools"],
    zip_safe=True,
    maintainer="Door traversal team",
    maintainer_email="door-traversal@example.org",
    description="Proposal markers, a Foxglove WebSocket bridge with operator publishing, a Foxglove layout.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "proposal_markers = door_viz.proposal_markers_node:main",
            "foxglove_bridge = door_viz.foxglove_bridge_node:main",
        ],
    },
)
