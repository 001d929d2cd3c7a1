"""Reading an rviz2 display configuration (``.rviz`` YAML): the fixed frame and the displays.

What the browser viewer uses is kept: ``Global Options`` (fixed frame, frame rate, background
colour), and each display's class, name, whether it is enabled, the topic it shows
(``Topic: {Value: ...}`` or, for RobotModel, ``Description Topic``) and its scalar options
(``Size (m)``, ``Color``, ``Keep``, ``Cell Size``...). Without a config file the viewer shows
what rviz2 would plus the robot: a grid, the robot model from ``/robot_description`` and TF.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from launchkit.errors import Location, UserError


@dataclass(frozen=True)
class Display:
    """One display of the config: ``rviz_default_plugins/LaserScan`` on ``/scan``, say."""

    class_name: str
    name: str
    enabled: bool = True
    topic: str | None = None
    options: dict[str, str | int | float | bool] = field(default_factory=dict, compare=False)

    def to_page(self) -> dict[str, Any]:
        """The display as the page reads it (class without its plugin package)."""
        return {
            "class": self.class_name.rsplit("/", 1)[-1],
            "name": self.name,
            "enabled": self.enabled,
            "topic": self.topic,
            "options": dict(self.options),
        }


@dataclass(frozen=True)
class RvizConfig:
    """What launchkit's rviz2 reads from a config file."""

    fixed_frame: str = "map"
    displays: list[Display] = field(default_factory=list)
    frame_rate: float = 30.0
    background: tuple[int, int, int] = (48, 48, 48)

    @property
    def topics(self) -> list[str]:
        """The topics the enabled displays show, in config order, without repeats."""
        seen: list[str] = []
        for display in self.displays:
            if display.enabled and display.topic and display.topic not in seen:
                seen.append(display.topic)
        return seen

    def to_page(self) -> dict[str, Any]:
        """What the page needs to build its view."""
        return {
            "fixedFrame": self.fixed_frame,
            "frameRate": self.frame_rate,
            "background": list(self.background),
            "displays": [d.to_page() for d in self.displays],
        }


#: What the viewer shows without a config file.
DEFAULT_DISPLAYS = [
    Display("rviz_default_plugins/Grid", "Grid"),
    Display("rviz_default_plugins/RobotModel", "RobotModel", True, "/robot_description"),
    Display("rviz_default_plugins/TF", "TF"),
]


def default_config() -> RvizConfig:
    """The view without ``-d``: rviz2's fixed frame ``map`` (the viewer falls back to the robot's
    root frame while ``map`` does not exist), a grid, the robot model and TF."""
    return RvizConfig("map", list(DEFAULT_DISPLAYS))


def load_config(path: Path) -> RvizConfig:
    """Read ``path``; a missing, unreadable or malformed file is a :class:`UserError`."""
    try:
        text = path.read_text()
    except OSError as exc:
        raise UserError(
            f"cannot read the display config: {exc.strerror}",
            Location(str(path)),
            expected="an .rviz file (YAML)",
        ) from None
    return parse_config(text, str(path))


def parse_config(text: str, source: str = "<config>") -> RvizConfig:
    """Parse the YAML text of an ``.rviz`` file."""
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = Location(source, mark.line + 1, mark.column + 1) if mark else Location(source)
        problem = getattr(exc, "problem", None) or "invalid YAML"
        raise UserError(
            f"the display config is not valid YAML: {problem}",
            where,
            expected="an .rviz file (YAML)",
        ) from None
    manager = data.get("Visualization Manager") if isinstance(data, dict) else None
    if not isinstance(manager, dict):
        raise UserError(
            "the display config has no 'Visualization Manager' mapping",
            Location(source),
            expected="an .rviz file as rviz2 saves it",
        )
    options = manager.get("Global Options")
    options = options if isinstance(options, dict) else {}
    fixed_frame = str(options.get("Fixed Frame", "map"))
    displays = [_display(d) for d in _walk(manager.get("Displays") or [])]
    rate = options.get("Frame Rate", 30)
    frame_rate = float(rate) if isinstance(rate, (int, float)) and 1 <= rate <= 240 else 30.0
    background = _colour(options.get("Background Color")) or (48, 48, 48)
    return RvizConfig(fixed_frame, displays, frame_rate, background)


def _colour(value: Any) -> tuple[int, int, int] | None:
    """rviz's ``"R; G; B"`` colour text as a tuple; None when it is not one."""
    parts = str(value).split(";") if value is not None else []
    try:
        rgb = tuple(int(p.strip()) for p in parts)
    except ValueError:
        return None
    if len(rgb) != 3 or not all(0 <= c <= 255 for c in rgb):
        return None
    return (rgb[0], rgb[1], rgb[2])


def _walk(entries: Any) -> list[dict[str, Any]]:
    """Every display, with the ones inside ``rviz_common/Group`` displays flattened."""
    out: list[dict[str, Any]] = []
    if not isinstance(entries, list):
        return out
    for entry in entries:
        if not isinstance(entry, dict):
            continue
        out.append(entry)
        out.extend(_walk(entry.get("Displays")))
    return out


def _display(entry: dict[str, Any]) -> Display:
    topic = None
    for key in ("Topic", "Description Topic"):
        value = entry.get(key)
        if isinstance(value, dict) and value.get("Value"):
            topic = str(value["Value"])
            break
    options = {
        str(key): value
        for key, value in entry.items()
        if key not in ("Class", "Name", "Enabled", "Displays")
        and isinstance(value, (str, int, float, bool))
    }
    return Display(
        str(entry.get("Class", "")),
        str(entry.get("Name", "")),
        bool(entry.get("Enabled", True)),
        topic,
        options,
    )
