"""ament_python package footstep_planner: A* footstep planner to the door stand pose and through the doorway."""

from setuptools import find_packages, setup

PACKAGE = "footstep_planner"

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
    description="A* footstep planner to the door stand pose and through the doorway.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "footstep_planner = footstep_planner.footstep_planner_node:main",
        ],
    },
)
