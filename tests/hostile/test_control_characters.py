"""Issue #17, point 7: control characters a launch file puts in names, commands or arguments
are printed escaped in launchkit's own lines (errors, ``--print``, ``[INFO]`` lines, a child's
``[name-N]`` prefix), so a file cannot clear the screen or forge a line. A child's own output
is passed on as it is."""

from __future__ import annotations

from pathlib import Path

from launchkit.errors import printable
from tests.hostile.helpers import launchkit

#: A YAML launch file can hold any character in a double-quoted string.
FILE = r"""launch:
- arg: {name: broken, default: "false"}
- executable:
    cmd: "printf 'plain output\\n'"
    name: "evil\e[2J\rname"
    output: screen
- executable:
    cmd: "/nonexistent\e[31m-program"
    name: "second\x00\n[INFO] forged"
    if: "$(var broken)"
"""


def write(tmp_path: Path) -> Path:
    path = tmp_path / "controls.launch.yaml"
    path.write_text(FILE)
    return path


def test_printable_escapes_every_control_character_but_tab() -> None:
    assert printable("a\x1b[2J\r\n\x00\tb\x7f\x9b") == "a\\x1b[2J\\r\\n\\0\tb\\x7f\\x9b"
    assert printable("café ✓") == "café ✓"


def test_a_run_prints_names_escaped(tmp_path: Path) -> None:
    result = launchkit("run", write(tmp_path), cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "[evil\\x1b[2J\\rname-1] plain output" in result.stdout
    assert "[INFO] [evil\\x1b[2J\\rname-1]: process started" in result.stdout
    assert "\x1b" not in result.stdout + result.stderr
    assert "\r" not in result.stdout + result.stderr


def test_print_and_errors_escape_what_the_file_wrote(tmp_path: Path) -> None:
    printed = launchkit("run", write(tmp_path), "broken:=true", "--print", cwd=tmp_path)
    failed = launchkit("run", write(tmp_path), "broken:=true", cwd=tmp_path)
    for result in (printed, failed):
        output = result.stdout + result.stderr
        assert "\x1b" not in output and "\x00" not in output and "\r" not in output, output
        assert not any(line.startswith("[INFO] forged") for line in output.splitlines())
    assert "second\\0\\n[INFO] forged" in printed.stdout
    assert failed.returncode == 2
    assert "program '/nonexistent\\x1b[31m-program'" in failed.stderr
