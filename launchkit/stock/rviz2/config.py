"""Reading an rviz2 display configuration (``.rviz`` YAML): the fixed frame and the displays.

Only what a Foxglove layout can use is kept: the fixed frame, and each display's class, name,
whether it is enabled and the topic it shows (``Topic: {Value: ...}`` or, for RobotModel,
``Description Topic``).
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


@dataclass(frozen=True)
class RvizConfig:
    """What launchkit's rviz2 reads from a config file."""

    fixed_frame: str = "map"
    displays: list[Display] = field(default_factory=list)

    @property
    def topics(self) -> list[str]:
        """The topics the enabled displays show, in config order, without repeats."""
        seen: list[str] = []
        for display in self.displays:
            if display.enabled and display.topic and display.topic not in seen:
                seen.append(display.topic)
        return seen


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
    options = manager.get("Global Options") or {}
    fixed_frame = str(options.get("Fixed Frame", "map")) if isinstance(options, dict) else "map"
    displays = [_display(d) for d in _walk(manager.get("Displays") or [])]
    return RvizConfig(fixed_frame, displays)


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
    return Display(
        str(entry.get("Class", "")),
        str(entry.get("Name", "")),
        bool(entry.get("Enabled", True)),
        topic,
    )
