"""ament_python package door_trajopt: TrajOpt-style SQP and constrained CHOMP over robot and door, with a door motion library."""

from setuptools import find_packages, setup

PACKAGE = "door_trajopt"

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
    description="TrajOpt-style SQP and constrained CHOMP over robot and door, with a door motion library.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "trajectory_optimizer = door_trajopt.trajectory_optimizer_node:main",
        ],
    },
)
