# generated-style colcon hook: keep DDS discovery on this machine unless the user chose a range
if [ -z "${ROS_AUTOMATIC_DISCOVERY_RANGE:-}" ]; then
  export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
fi
