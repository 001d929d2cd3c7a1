"""Gazebo world files (SDF), read by our own parser and built with ``createMultiBody``.

``p.loadSDF`` ignores ``<static>`` and link poses, skips ``model://`` includes and can crash the
process (docs/simulation.md, "The server"), so worlds are parsed here. Supported: ``<include>`` of
``model://ground_plane`` (and ``model://sun``, which has nothing to simulate), and ``<model>`` with
``<static>``, ``<pose>`` and links whose collision/visual geometry is a box, cylinder or sphere.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

from launchkit.stock.gazebo_ros.sim.model import ModelError

WORLDS_DIR = Path(__file__).resolve().parent.parent / "share" / "worlds"

Pose = tuple[float, float, float, float, float, float]


@dataclass(frozen=True)
class Shape:
    """One solid of a world: geometry, pose (x y z roll pitch yaw), colour, mass (0 = static)."""

    model: str
    kind: str  # box | cylinder | sphere
    size: tuple[float, ...]  # box: (x, y, z); cylinder: (radius, length); sphere: (radius,)
    pose: Pose
    rgba: tuple[float, float, float, float]
    mass: float


@dataclass(frozen=True)
class WorldSpec:
    """A world: whether it has the ground plane, and its shapes."""

    name: str
    ground_plane: bool
    shapes: tuple[Shape, ...]


def resolve_world(name: str) -> Path:
    """A world argument as a file: a path, or the name of a shipped world (``obstacles``)."""
    candidate = Path(name)
    if candidate.is_file():
        return candidate
    for shipped in (WORLDS_DIR / name, WORLDS_DIR / f"{name}.world"):
        if shipped.is_file():
            return shipped
    known = ", ".join(sorted(p.stem for p in WORLDS_DIR.glob("*.world")))
    raise ModelError(f"world '{name}' not found (expected a .world file or one of: {known})")


def load_world(path: Path) -> WorldSpec:
    """Parse an SDF world file; :class:`ModelError` names what is wrong."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise ModelError(f"{path}: cannot read the world: {exc}") from None
    world = root.find("world") if root.tag == "sdf" else None
    if world is None:
        raise ModelError(f"{path}: no <sdf><world> (expected an SDF world file)")
    ground = False
    shapes: list[Shape] = []
    for include in world.findall("include"):
        uri = (include.findtext("uri") or "").strip()
        if uri == "model://ground_plane":
            ground = True
        elif uri != "model://sun":
            raise ModelError(
                f"{path}: <include> of {uri!r} is not supported "
                "(expected model://ground_plane or model://sun)"
            )
    for model in world.findall("model"):
        shapes.extend(_model_shapes(path, model))
    return WorldSpec(world.get("name", path.stem), ground, tuple(shapes))


def _pose(path: Path, element: ET.Element | None) -> Pose:
    text = "" if element is None else (element.findtext("pose") or "").strip()
    if not text:
        return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    try:
        values = tuple(float(v) for v in text.split())
    except ValueError:
        values = ()
    if len(values) != 6:
        raise ModelError(
            f"{path}: <pose>{text}</pose> (expected six numbers: x y z roll pitch yaw)"
        )
    return values


def _compose(a: Pose, b: Pose) -> Pose:
    """Pose ``b`` given in frame ``a``, in a's parent frame (yaw-only rotation of the offset)."""
    yaw = a[5]
    c, s = math.cos(yaw), math.sin(yaw)
    x = a[0] + c * b[0] - s * b[1]
    y = a[1] + s * b[0] + c * b[1]
    return (x, y, a[2] + b[2], a[3] + b[3], a[4] + b[4], a[5] + b[5])


def _geometry(path: Path, element: ET.Element) -> tuple[str, tuple[float, ...]]:
    geometry = element.find("geometry")
    if geometry is not None:
        box = geometry.find("box")
        try:
            if box is not None:
                size = tuple(float(v) for v in (box.findtext("size") or "").split())
                if len(size) == 3:
                    return "box", size
            cylinder = geometry.find("cylinder")
            if cylinder is not None:
                radius = float(cylinder.findtext("radius") or "nan")
                length = float(cylinder.findtext("length") or "nan")
                return "cylinder", (radius, length)
            sphere = geometry.find("sphere")
            if sphere is not None:
                return "sphere", (float(sphere.findtext("radius") or "nan"),)
        except ValueError:
            pass
    raise ModelError(
        f"{path}: a <collision> without a usable geometry "
        "(expected <box><size>, <cylinder><radius><length> or <sphere><radius>)"
    )


def _model_shapes(path: Path, model: ET.Element) -> list[Shape]:
    name = model.get("name", "model")
    static = (model.findtext("static") or "false").strip().lower() in ("true", "1")
    model_pose = _pose(path, model)
    shapes: list[Shape] = []
    for link in model.findall("link"):
        link_pose = _compose(model_pose, _pose(path, link))
        mass = 0.0 if static else float(link.findtext("inertial/mass") or "1")
        rgba = (0.7, 0.7, 0.7, 1.0)
        diffuse = link.findtext("visual/material/diffuse")
        if diffuse:
            values = [float(v) for v in diffuse.split()]
            rgba = (values + [1.0] * 4)[:4]  # type: ignore[assignment]
        for collision in link.findall("collision"):
            kind, size = _geometry(path, collision)
            shapes.append(
                Shape(name, kind, size, _compose(link_pose, _pose(path, collision)), rgba, mass)
            )
    return shapes
