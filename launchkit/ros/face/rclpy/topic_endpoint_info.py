"""``rclpy.topic_endpoint_info``: what ``get_publishers_info_by_topic`` returns."""

from launchkit.ros.node_graph import TopicEndpointInfo, TopicEndpointTypeEnum

__all__ = ["TopicEndpointInfo", "TopicEndpointTypeEnum"]
