"""``rclpy.impl``."""
