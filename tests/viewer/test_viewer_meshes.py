"""A robot made of a mesh, in a real browser: the page fetches the STL the URDF names from the
server (``file://``), colours it with the URDF's material, and poses it from ``/tf_static``.

rviz2 runs alone without ``-d``: its default view (grid, robot model, TF) in the frame ``map``,
which does not exist here, so the page shows the robot in its root frame ``base``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from launchkit.ros.msgs.geometry_msgs.msg import TransformStamped
from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.tf2_msgs.msg import TFMessage

import launchkit.ros as ros
from tests.stock.conftest import latched
from tests.stock.rviz2_process import running_rviz2

# a 0.4 m cube as ASCII STL (12 triangles)
CORNERS = [(x, y, z) for x in (-0.2, 0.2) for y in (-0.2, 0.2) for z in (-0.2, 0.2)]
FACES = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


def cube_stl() -> str:
    """The cube's triangles, two per face."""
    lines = ["solid cube"]
    for a, b, c, d in FACES:
        for tri in ((a, b, c), (a, c, d)):
            lines += ["facet normal 0 0 0", "outer loop"]
            lines += [f"vertex {' '.join(map(str, CORNERS[i]))}" for i in tri]
            lines += ["endloop", "endfacet"]
    return "\n".join([*lines, "endsolid cube", ""])


def test_a_mesh_robot_is_fetched_and_drawn(router: str, tmp_path: Path, open_viewer: Any) -> None:
    mesh = tmp_path / "cube.stl"
    mesh.write_text(cube_stl())
    urdf = (
        "<robot name='meshy'><link name='base'/><link name='part'><visual><geometry>"
        f"<mesh filename='file://{mesh}' scale='1 1 1'/></geometry>"
        "<material name='orange'><color rgba='1 0.5 0 1'/></material></visual></link>"
        "<joint name='fix' type='fixed'><parent link='base'/><child link='part'/>"
        "<origin xyz='0 0 0.3'/></joint></robot>"
    )
    context = ros.Context(router=router)
    context.init([])
    node = ros.Node("mesh_probe", context=context, enable_rosout=False)
    try:
        node.create_publisher(String, "/robot_description", latched()).publish(String(data=urdf))
        fixed = TransformStamped(child_frame_id="part")
        fixed.header.frame_id = "base"
        fixed.transform.translation.z = 0.3
        fixed.transform.rotation.w = 1.0
        statics = node.create_publisher(TFMessage, "/tf_static", latched())
        statics.publish(TFMessage(transforms=[fixed]))
        with running_rviz2(router, "--asset-folder", str(tmp_path)) as rviz2:
            viewer = open_viewer(f"http://127.0.0.1:{rviz2.port}/")
            viewer.wait("s.robotLinks >= 2 && s.meshesLoaded >= 1", "the cube loaded and posed")
            assert viewer.stats()["fixedFrame"] == "base" and viewer.stats()["meshesFailed"] == 0
            point = viewer.page.evaluate("window.__viewer.project('part')")
            (colour,) = viewer.page.evaluate("p => window.__viewer.sample([p])", point)
            assert colour[0] > 100 and colour[0] > colour[2] + 60, f"not orange there: {colour}"
    finally:
        node.destroy_node()
        context.shutdown()
