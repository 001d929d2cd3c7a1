"""The ROS-free simulation core: PyBullet world, URDF Gazebo extensions, sensors, pacing."""
