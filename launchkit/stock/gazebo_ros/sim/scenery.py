"""The world's fixed scenery in PyBullet: the ground plane and the obstacles of a world file."""

from __future__ import annotations

from typing import Any

from launchkit.stock.gazebo_ros.sim.world import Shape, WorldSpec


def build_scenery(p: Any, client: int, world: WorldSpec) -> int | None:
    """Create ``world``'s ground (if it has one) and shapes in PyBullet ``client`` (``p`` is the
    pybullet module); the ground's body id."""
    ground: int | None = None
    if world.ground_plane:
        shape = p.createCollisionShape(p.GEOM_PLANE, physicsClientId=client)
        # A thin box, not a plane, as the visual: PyBullet has no visual for a plane and the
        # EGL renderer crashes on one.
        visual = p.createVisualShape(
            p.GEOM_BOX,
            halfExtents=(50.0, 50.0, 0.0005),
            visualFramePosition=(0.0, 0.0, -0.0005),
            rgbaColor=(0.8, 0.8, 0.8, 1),
            physicsClientId=client,
        )
        ground = p.createMultiBody(0, shape, visual, physicsClientId=client)
    for solid in world.shapes:
        add_shape(p, client, solid)
    return ground


def add_shape(p: Any, client: int, solid: Shape) -> int:
    """Create one obstacle; its body id."""
    if solid.kind == "box":
        half = [s / 2.0 for s in solid.size]
        col = p.createCollisionShape(p.GEOM_BOX, halfExtents=half, physicsClientId=client)
        vis = p.createVisualShape(
            p.GEOM_BOX, halfExtents=half, rgbaColor=solid.rgba, physicsClientId=client
        )
    elif solid.kind == "cylinder":
        radius, length = solid.size
        col = p.createCollisionShape(
            p.GEOM_CYLINDER, radius=radius, height=length, physicsClientId=client
        )
        vis = p.createVisualShape(
            p.GEOM_CYLINDER,
            radius=radius,
            length=length,
            rgbaColor=solid.rgba,
            physicsClientId=client,
        )
    else:
        col = p.createCollisionShape(p.GEOM_SPHERE, radius=solid.size[0], physicsClientId=client)
        vis = p.createVisualShape(
            p.GEOM_SPHERE,
            radius=solid.size[0],
            rgbaColor=solid.rgba,
            physicsClientId=client,
        )
    x, y, z, roll, pitch, yaw = solid.pose
    body: int = p.createMultiBody(
        solid.mass,
        col,
        vis,
        basePosition=(x, y, z),
        baseOrientation=p.getQuaternionFromEuler((roll, pitch, yaw)),
        physicsClientId=client,
    )
    return body
