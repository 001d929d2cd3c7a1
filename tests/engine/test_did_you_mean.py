"""A misspelt key, attribute, tag or substitution: the error says what was expected and what
the user most likely meant, the same way in YAML and XML."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.errors import LaunchFileError
from launchkit.frontend.launch_loader import LaunchLoader
from tests.engine.launcher import run_launchkit as launchkit

#: case -> (YAML text, XML text, line, column of the YAML text's mistake, error text)
CASES: dict[str, tuple[str, str, int, str]] = {
    "exe for exec": (
        "launch:\n- node:\n    pkg: robot_wheel\n    exe: talker\n",
        '<launch>\n  <node pkg="robot_wheel" exe="talker"/>\n</launch>\n',
        4,
        "unknown {key} 'exe' on {node} (expected exec=\"EXECUTABLE\")\n"
        "  hint: did you mean 'exec'?",
    ),
    "levl for level": (
        "launch:\n- log:\n    message: hi\n    levl: INFO\n",
        '<launch>\n  <log message="hi" levl="INFO"/>\n</launch>\n',
        4,
        "unknown {key} 'levl' on {log} (expected one of: if, level, message, unless)\n"
        "  hint: did you mean 'level'?",
    ),
    "nod for node": (
        "launch:\n- nod:\n    pkg: robot_wheel\n",
        '<launch>\n  <nod pkg="robot_wheel"/>\n</launch>\n',
        2,
        "unknown tag {nod} (expected one of: ",
    ),
}

SYNTAX = {
    ".yaml": {"key": "key", "node": "'node'", "log": "'log'", "nod": "'nod'"},
    ".xml": {"key": "attribute", "node": "<node>", "log": "<log>", "nod": "<nod>"},
}


@pytest.mark.parametrize("suffix", sorted(SYNTAX))
@pytest.mark.parametrize("case", sorted(CASES))
def test_a_misspelt_name_says_what_was_expected_and_meant(
    tmp_path: Path, case: str, suffix: str
) -> None:
    yaml_text, xml_text, yaml_line, said = CASES[case]
    path = tmp_path / f"typo.launch{suffix}"
    path.write_text(yaml_text if suffix == ".yaml" else xml_text)
    with pytest.raises(LaunchFileError) as caught:
        LaunchLoader().load(path)
    text = caught.value.format()
    assert f": error: {said.format(**SYNTAX[suffix])}" in text, text
    if suffix == ".yaml":  # located at the key that is wrong
        assert text.startswith(f"{path}:{yaml_line}:"), text
    if case == "nod for node":
        assert text.endswith("\n  hint: did you mean 'node'?"), text


def test_a_misspelt_substitution_says_what_was_meant(tmp_path: Path) -> None:
    path = tmp_path / "typo.launch.xml"
    path.write_text('<launch><log message="$(find-pkg robot_wheel)"/></launch>')
    result = launchkit("check", str(path), cwd=tmp_path)
    assert result.returncode == 2
    assert "error: unknown substitution $(find-pkg) (expected one of: " in result.stderr
    assert result.stderr.endswith("\n  hint: did you mean 'find-pkg-share'?\n")
