"""Robot profiles and Pinocchio kinematics of the door-traversal humanoids (ROS-free)."""
