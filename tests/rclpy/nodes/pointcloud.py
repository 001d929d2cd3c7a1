"""Publishes a PointCloud2 made with sensor_msgs_py.point_cloud2, hears it back, and prints
the points read from the message that crossed the transport."""

import numpy as np
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import PointCloud2, PointField
from sensor_msgs_py import point_cloud2
from std_msgs.msg import Header


def main() -> None:
    rclpy.init()
    node = Node("clouds")
    heard: list[PointCloud2] = []
    node.create_subscription(PointCloud2, "cloud", heard.append, 10)
    publisher = node.create_publisher(PointCloud2, "cloud", 10)
    fields = [
        PointField(name=name, offset=4 * i, datatype=PointField.FLOAT32, count=1)
        for i, name in enumerate(("x", "y", "z", "intensity"))
    ]
    points = np.array([[1.5, 2.0, -3.25, 0.5], [np.nan, 1.0, 2.0, 3.0]], dtype=np.float32)
    cloud = point_cloud2.create_cloud(Header(frame_id="map"), fields, points)
    while not heard and rclpy.ok():
        publisher.publish(cloud)
        rclpy.spin_once(node, timeout_sec=0.2)
    (got,) = heard[:1]
    print(got.width, got.height, got.point_step, got.row_step, len(got.data))
    print(point_cloud2.read_points_list(got, field_names=["x", "z"], skip_nans=True))
    print(point_cloud2.read_points_numpy(got, skip_nans=True).tolist())
    xyz = point_cloud2.create_cloud_xyz32(Header(), [[0.0, 1.0, 2.0]])
    print(
        [f.name for f in xyz.fields],
        xyz.point_step,
        list(point_cloud2.read_points(xyz)[0].tolist()),
    )
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
