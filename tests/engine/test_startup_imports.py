"""Start-up does only what the command needs: the modules a command imports are its own.

No timing here (that is bench/launch_overhead.py's job): these check which libraries a command
loads, which is what makes it slow or not, and which does not depend on the machine's load.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

HEAVY = ("numpy", "rosbags", "yaml", "lxml", "zenoh", "pybullet", "launchkit.ros.node")

_PROBE = """
import json, sys
from launchkit.cli import main
status = main(sys.argv[1:])
loaded = sorted(m for m in sys.modules if m in {heavy!r} or m.startswith({prefixes!r}))
print("LOADED " + json.dumps(loaded), file=sys.stderr)
"""

#: launchkit's description and tag modules: a file imports those of the tags it uses.
DESCRIPTION = ("launchkit.description.", "launchkit.frontend.tags.")


def loaded_by(*argv: str, prefixes: tuple[str, ...] = ()) -> list[str]:
    """The heavy libraries (and modules starting with one of ``prefixes``) ``launchkit ARGV``
    imported (run to completion in a fresh process)."""
    probe = _PROBE.format(heavy=HEAVY, prefixes=prefixes)
    result = subprocess.run(
        [sys.executable, "-c", probe, *argv],
        capture_output=True,
        text=True,
        timeout=120,
    )
    line = [x for x in result.stderr.splitlines() if x.startswith("LOADED ")]
    assert line, result.stderr
    return list(json.loads(line[-1][len("LOADED ") :]))


def test_running_an_xml_file_loads_no_yaml_ros_or_simulation(tmp_path: Path) -> None:
    # nor lxml: expat reads a plain file (launchkit/frontend/xml/expat_tree.py)
    launch = tmp_path / "empty.launch.xml"
    launch.write_text("<launch>\n  <executable cmd='true'/>\n</launch>\n")
    assert loaded_by("run", str(launch)) == []


def test_an_xml_file_expat_does_not_read_loads_lxml(tmp_path: Path) -> None:
    launch = tmp_path / "entities.launch.xml"
    launch.write_text(
        '<!DOCTYPE launch [<!ENTITY e "v">]>\n<launch><let name="&e;" value="1"/></launch>\n'
    )
    assert loaded_by("run", str(launch)) == ["lxml"]


def test_running_a_yaml_file_loads_no_lxml(tmp_path: Path) -> None:
    launch = tmp_path / "empty.launch.yaml"
    launch.write_text("launch:\n- executable: {cmd: 'true'}\n")
    assert loaded_by("run", str(launch)) == ["yaml"]


def test_an_empty_launch_creates_no_dataclasses(tmp_path: Path) -> None:
    # dataclasses imports inspect (ast, dis, tokenize) and compiles each class's methods at
    # import: the modules every launch needs declare plain classes (launchkit._record). (lxml
    # imports inspect too: a plain XML file is read with expat.)
    xml = tmp_path / "empty.launch.xml"
    xml.write_text("<launch/>\n")
    assert loaded_by("run", str(xml), prefixes=("dataclasses", "inspect")) == []
    yaml = tmp_path / "empty.launch.yaml"
    yaml.write_text("launch: []\n")
    assert loaded_by("run", str(yaml), prefixes=("dataclasses", "inspect")) == ["yaml"]


def description_modules(tmp_path: Path, text: str) -> set[str]:
    """The description and tag modules ``launchkit run`` of an XML file ``text`` imported."""
    launch = tmp_path / "file.launch.xml"
    launch.write_text(text)
    return {m for m in loaded_by("run", str(launch), prefixes=DESCRIPTION) if m != "lxml"}


def test_an_empty_file_imports_no_tag_action_or_substitution_modules(tmp_path: Path) -> None:
    # What reading, checking and running any file needs; every tag's parser and action, and
    # every $(...) kind, is imported when a file first uses it.
    assert description_modules(tmp_path, "<launch/>\n") == {
        "launchkit.description.actions",
        "launchkit.description.actions.arg",
        "launchkit.description.actions.base",
        "launchkit.description.actions.group",
        "launchkit.description.actions.include",
        "launchkit.description.conditions",
        "launchkit.description.events",
        "launchkit.description.launch_context",
        "launchkit.description.launch_description",
        "launchkit.description.process_spec",
        "launchkit.description.ros_link",
        "launchkit.description.substitutions",
        "launchkit.description.substitutions.base",
        "launchkit.description.substitutions.grammar",
        "launchkit.description.substitutions.package",
        "launchkit.description.substitutions.paths",
        "launchkit.description.substitutions.configuration",
        "launchkit.description.truth",
    }


def test_a_file_imports_the_tag_modules_it_uses(tmp_path: Path) -> None:
    executable = description_modules(
        tmp_path, "<launch><executable cmd='true' if='$(env HOME)'/></launch>\n"
    )
    assert "launchkit.frontend.tags.launch" in executable
    assert "launchkit.description.actions.executable" in executable
    assert "launchkit.description.substitutions.environment" in executable
    assert "launchkit.frontend.tags.ros" not in executable
    assert "launchkit.description.actions.node" not in executable
    assert "launchkit.description.substitutions.command" not in executable
    node = description_modules(tmp_path, "<launch><node pkg='p' exec='e' if='false'/></launch>\n")
    assert "launchkit.frontend.tags.ros" in node
    assert "launchkit.description.actions.composition" in node  # <node> reads containers
