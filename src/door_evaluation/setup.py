"""ament_python package door_evaluation: evaluations and benchmarks of the cores (on the simulator or alone)."""

from setuptools import find_packages, setup

PACKAGE = "door_evaluation"

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
    description="Evaluations and benchmarks of the cores (the detector's Table II on the simulator, time per frame; "
                "the footstep planner's and the trajectory optimiser's benchmarks, toy problems and peer comparison; "
                "the simulator's real-time factor).",
    license="Apache-2.0",
)
