#!/usr/bin/env bash
# The image's entry point: the ROS and workspace environment, then the command.
set -eo pipefail
set +u
source /opt/ros/jazzy/setup.bash
source /door_traversal/ros_ws/install/setup.bash
export ROS_AUTOMATIC_DISCOVERY_RANGE=${ROS_AUTOMATIC_DISCOVERY_RANGE:-LOCALHOST}
exec "$@"
