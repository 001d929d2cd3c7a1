"""What a URDF asks of Gazebo: its ``<gazebo>`` blocks (materials, plugins, sensors), read as text.

PyBullet ignores these blocks and URDF round-trips drop them, so they are read here from the
original text with the standard library. Nothing here touches PyBullet.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field


class ModelError(ValueError):
    """A URDF that cannot be simulated (not XML, no ``<robot>``, a broken ``<gazebo>`` block)."""


@dataclass(frozen=True)
class RosOptions:
    """A plugin's ``<ros>`` block: namespace, remappings (``from:=to``) and extra arguments."""

    namespace: str = ""
    remappings: tuple[tuple[str, str], ...] = ()

    def remapped(self, name: str) -> str:
        """``name`` after the block's remappings (``~/out`` style names included)."""
        for source, target in self.remappings:
            if source == name:
                return target
        return name


@dataclass(frozen=True)
class PluginSpec:
    """One ``<plugin>``: its library, its instance name (the ROS node name), its tags as text."""

    filename: str
    name: str
    tags: dict[str, str]
    ros: RosOptions = RosOptions()
    #: Every value of each tag, in order, for the tags a plugin may repeat (``<joint_name>``).
    repeated: dict[str, tuple[str, ...]] = field(default_factory=dict)

    @property
    def library(self) -> str:
        """The library's base name without ``lib`` and ``.so`` (``gazebo_ros_diff_drive``)."""
        base = self.filename.rsplit("/", 1)[-1]
        base = base.removeprefix("lib")
        return base.removesuffix(".so")


@dataclass(frozen=True)
class SensorSpec:
    """One ``<sensor>`` under ``<gazebo reference=LINK>``; ``element`` keeps its full XML."""

    name: str
    type: str
    link: str
    update_rate: float
    element: ET.Element
    plugins: tuple[PluginSpec, ...] = ()

    def find_text(self, path: str, default: str) -> str:
        """Text of the element at ``path`` below the sensor (``default`` when absent)."""
        found = self.element.find(path)
        if found is None or found.text is None:
            return default
        return found.text.strip()

    def find_float(self, path: str, default: float) -> float:
        """Like :meth:`find_text`, as a number; a malformed number is a :class:`ModelError`."""
        text = self.find_text(path, "")
        if not text:
            return default
        try:
            return float(text)
        except ValueError:
            raise ModelError(
                f"sensor '{self.name}': <{path}> is {text!r} (expected a number)"
            ) from None


@dataclass(frozen=True)
class ModelSpec:
    """A robot as the simulator sees it: link names, joints and its Gazebo extensions."""

    name: str
    links: tuple[str, ...]
    root_link: str
    materials: dict[str, str] = field(default_factory=dict)
    friction: dict[str, float] = field(default_factory=dict)
    plugins: tuple[PluginSpec, ...] = ()
    sensors: tuple[SensorSpec, ...] = ()


def parse_model(urdf_text: str) -> ModelSpec:
    """Read a URDF's structure and ``<gazebo>`` blocks; :class:`ModelError` on bad input."""
    try:
        root = ET.fromstring(urdf_text)
    except ET.ParseError as exc:
        raise ModelError(f"the robot description is not valid XML: {exc}") from None
    if root.tag != "robot":
        raise ModelError(f"the robot description's root is <{root.tag}> (expected <robot>)")
    links = tuple(link.get("name", "") for link in root.findall("link"))
    if not links or not all(links):
        raise ModelError("the robot description has no named <link> (expected at least one)")
    children = {j.findtext("child") or "" for j in root.findall("joint")}
    for joint in root.findall("joint"):
        child = joint.find("child")
        if child is not None:
            children.add(child.get("link", ""))
    roots = [name for name in links if name not in children]
    if len(roots) != 1:
        raise ModelError(
            f"the robot description has {len(roots)} root links {roots} (expected exactly one)"
        )
    materials: dict[str, str] = {}
    plugins: list[PluginSpec] = []
    sensors: list[SensorSpec] = []
    for block in root.findall("gazebo"):
        reference = block.get("reference")
        material = block.findtext("material")
        if reference and material:
            materials[reference] = material.strip()
        if reference is None:
            plugins.extend(_plugin(p) for p in block.findall("plugin"))
        for sensor in block.findall("sensor"):
            sensors.append(_sensor(sensor, reference or roots[0]))
    return ModelSpec(
        name=root.get("name", "model"),
        links=links,
        root_link=roots[0],
        materials=materials,
        friction=_friction(root),
        plugins=tuple(plugins),
        sensors=tuple(sensors),
    )


def _friction(root: ET.Element) -> dict[str, float]:
    """``<contact_coefficients mu=...>`` per link (PyBullet ignores the tag)."""
    found: dict[str, float] = {}
    for link in root.findall("link"):
        for coefficients in link.iter("contact_coefficients"):
            mu = coefficients.get("mu")
            if mu is None:
                continue
            try:
                found[link.get("name", "")] = float(mu)
            except ValueError:
                raise ModelError(
                    f"link '{link.get('name')}': contact_coefficients mu={mu!r} (expected a number)"
                ) from None
    return found


def _plugin(element: ET.Element) -> PluginSpec:
    tags: dict[str, str] = {}
    repeated: dict[str, tuple[str, ...]] = {}
    for child in element:
        if child.tag == "ros":
            continue
        text = (child.text or "").strip()
        # Repeated tags (several wheel pairs) keep the first, the pair launchkit drives.
        tags.setdefault(child.tag, text)
        repeated[child.tag] = (*repeated.get(child.tag, ()), text)
    ros = element.find("ros")
    options = RosOptions()
    if ros is not None:
        remaps: list[tuple[str, str]] = []
        for remap in ros.findall("remapping"):
            text = (remap.text or "").strip()
            if ":=" not in text:
                raise ModelError(
                    f"plugin '{element.get('name')}': <remapping>{text}</remapping> "
                    "(expected FROM:=TO)"
                )
            source, target = text.split(":=", 1)
            remaps.append((source.strip(), target.strip()))
        options = RosOptions((ros.findtext("namespace") or "").strip(), tuple(remaps))
    return PluginSpec(element.get("filename", ""), element.get("name", ""), tags, options, repeated)


def _sensor(element: ET.Element, link: str) -> SensorSpec:
    name = element.get("name", "")
    rate_text = (element.findtext("update_rate") or "0").strip()
    try:
        rate = float(rate_text)
    except ValueError:
        raise ModelError(
            f"sensor '{name}': <update_rate> is {rate_text!r} (expected a number)"
        ) from None
    return SensorSpec(
        name=name,
        type=element.get("type", ""),
        link=link,
        update_rate=rate,
        element=element,
        plugins=tuple(_plugin(p) for p in element.findall("plugin")),
    )
