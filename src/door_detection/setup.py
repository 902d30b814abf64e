"""ament_python package door_detection: Door and handle detection: automatic (Hough + RANSAC + plane check) and operator-aided."""

from setuptools import find_packages, setup

PACKAGE = "door_detection"

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
    description="Door and handle detection: automatic (Hough + RANSAC + plane check) and operator-aided.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "door_detector = door_detection.door_detector_node:main",
        ],
    },
)
