"""ament_python package door_fsm: FSM supervisor of the door task with operator approvals and autonomy levels."""

from setuptools import find_packages, setup

PACKAGE = "door_fsm"

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
    description="FSM supervisor of the door task with operator approvals and autonomy levels.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "fsm_supervisor = door_fsm.fsm_supervisor_node:main",
            "operator_console = door_fsm.operator_console:main",
        ],
    },
)
