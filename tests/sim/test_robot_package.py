"""The robot package's files: the xacro variant expands to the seed robot; launch files check."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import xacro

from launchkit.stock.gazebo_ros.sim.model import parse_model

ROOT = Path(__file__).resolve().parents[2]


def _structure(text: str) -> dict[str, object]:
    root = ET.fromstring(text)

    def numbers(element: ET.Element | None, attribute: str) -> tuple[float, ...]:
        value = "" if element is None else element.get(attribute, "")
        return tuple(float(v) for v in value.split())

    joints = {}
    for joint in root.findall("joint"):
        origin = joint.find("origin")
        joints[joint.get("name")] = (
            joint.get("type"),
            joint.find("parent").get("link"),  # type: ignore[union-attr]
            joint.find("child").get("link"),  # type: ignore[union-attr]
            numbers(origin, "xyz"),
            numbers(origin, "rpy"),
            numbers(joint.find("axis"), "xyz"),
        )
    links = {}
    for link in root.findall("link"):
        mass = link.find("inertial/mass")
        shape = link.find("collision/geometry")
        assert mass is not None and shape is not None
        links[link.get("name")] = (
            float(mass.get("value", "nan")),
            [(g.tag, {k: numbers(g, k) for k in g.attrib}) for g in shape],
        )
    return {"links": links, "joints": joints}


def test_xacro_variant_expands_to_the_same_robot() -> None:
    expanded = xacro.process_file(str(ROOT / "urdf" / "three_wheeled_robot.urdf.xacro")).toxml()
    seed = (ROOT / "urdf" / "three_wheeled_robot.urdf").read_text()
    assert _structure(expanded) == _structure(seed)
    a, b = parse_model(expanded), parse_model(seed)
    assert a.materials == b.materials
    assert [(p.name, p.tags) for p in a.plugins] == [(p.name, p.tags) for p in b.plugins]
    assert [s.name for s in a.sensors] == [s.name for s in b.sensors]


@pytest.mark.parametrize(
    "name", ["gazebo_and_rviz.launch.xml", "gazebo.launch.xml", "display.launch.xml"]
)
def test_robot_launch_files_pass_the_checks(name: str) -> None:
    from launchkit.cli import main

    assert main(["check", str(ROOT / "launch_xml" / name)]) == 0
