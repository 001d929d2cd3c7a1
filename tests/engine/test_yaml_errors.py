"""Bad YAML launch files: one located line per mistake (file:line:col naming the key or what
is wrong), exit status 2, no traceback, nothing started. Hostile input (alias bombs, deep
nesting, bytes that are not UTF-8) gets the same treatment, fast."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from launchkit import safe_yaml as document
from launchkit.errors import LaunchFileError
from launchkit.frontend.launch_loader import LaunchLoader
from tests.engine.launcher import run_rejected

#: Every file begins with this, so a process would leave a marker if anything started.
PROLOGUE = "launch:\n- executable: {{cmd: 'touch {marker}'}}\n"

BOMB = "".join(
    f"- let: &l{i} {{name: x, value: [{', '.join([f'*l{i - 1}' if i else 'a'] * 10)}]}}\n"
    for i in range(7)
)

#: case -> (text after the prologue, line, column, what the message says)
CASES: dict[str, tuple[str, int, int, str]] = {
    "unknown key": ("- log:\n    message: hi\n    colour: red\n", 5, 5, "unknown key 'colour'"),
    "unknown tag": ("- nod: {pkg: a, exec: b}\n", 3, 3, "unknown tag 'nod'"),
    "text key given a number": (
        "- let: {name: x, value: 1.5}\n",
        3,
        25,
        "key 'value' of 'let' is the float 1.5",
    ),
    "text key given a list": (
        "- let: {name: [a], value: b}\n",
        3,
        15,
        "key 'name' of 'let' is a list",
    ),
    "text key given a mapping": (
        "- let: {name: x, value: {a: b}}\n",
        3,
        25,
        "key 'value' of 'let' is a mapping",
    ),
    "text key given null": ("- let: {name: ~, value: b}\n", 3, 3, "'let' is missing key 'name'"),
    "float key given an integer": (
        "- timer: {period: 5, children: []}\n",
        3,
        19,
        "key 'period' of 'timer' is the integer 5",
    ),
    "yes is a boolean in YAML": (
        "- arg: {name: use_sim, default: yes}\n",
        3,
        33,
        "key 'default' of 'arg' is the boolean yes",
    ),
    "bad indentation": (
        "- log:\n    message: hi\n   level: INFO\n",
        5,
        4,
        "malformed YAML",
    ),
    "tab indentation": ("- log:\n\tmessage: hi\n", 4, 1, "malformed YAML"),
    "two tags in one item": (
        "- log: {message: a}\n  let: {name: b, value: c}\n",
        4,
        3,
        "holds several tags ('log', 'let')",
    ),
    "duplicate key": ("- log: {message: a, message: b}\n", 3, 21, "key 'message' is written twice"),
    "missing required key": ("- let: {name: x}\n", 3, 3, "'let' is missing key 'value'"),
    "unknown substitution": (
        '- log: {message: "a $(find-pkg robot)"}\n',
        3,
        21,
        "unknown substitution $(find-pkg)",
    ),
    "sub-entity that is not a mapping": (
        "- executable: {cmd: 'true', env: [{name: A, value: b}, C=d]}\n",
        3,
        56,
        "an item of 'env' in 'executable' is the text 'C=d'",
    ),
    "empty sub-entity list": (
        "- executable: {cmd: 'true', env: []}\n",
        3,
        29,
        "key 'env' of 'executable' is an empty list",
    ),
    "mixed list parameter": (
        "- node: {pkg: p, exec: e, param: [{name: l, value: [1, a]}]}\n",
        3,
        56,
        "item 2 of key 'value' of 'param' is the text 'a'",
    ),
    "second document": ("---\nlaunch: []\n", 3, 1, "more than one YAML document"),
    "unsupported tag": ("- log: !!python/name:os.system {message: x}\n", 3, 8, "YAML tag"),
    "alias bomb": (BOMB, 7, 55, "aliases expand to more than"),
    "recursive alias": ("- group: &g [{group: *g}]\n", 3, 22, "inside the node it names"),
    "deep nesting": ("- log: " + "[" * 200 + "]" * 200 + "\n", 3, 105, "nests more than 100"),
}


@pytest.fixture(params=["libyaml", "pure Python"])
def parser(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> str:
    """Each case with libyaml's parser and with PyYAML's own (used where libyaml is missing)."""
    if request.param == "pure Python":
        monkeypatch.setattr(document, "_Loader", yaml.SafeLoader)
    elif not getattr(yaml, "__with_libyaml__", False):
        pytest.skip("PyYAML was built without libyaml")
    return str(request.param)


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_yaml_is_one_located_error(tmp_path: Path, case: str, parser: str) -> None:
    body, line, col, what = CASES[case]
    path = tmp_path / "bad.launch.yaml"
    path.write_text(PROLOGUE.format(marker=tmp_path / "started") + body)
    with pytest.raises(LaunchFileError) as caught:
        LaunchLoader().load(path)
    error = caught.value
    assert what in error.message, error.format()
    assert (error.location.file, error.location.line, error.location.col) == (  # type: ignore[union-attr]
        str(path),
        line,
        col,
    ), error.format()


def test_bytes_that_are_not_utf8_are_located(tmp_path: Path) -> None:
    path = tmp_path / "latin1.launch.yaml"
    path.write_bytes(b"launch:\n- log: {message: 'caf\xe9'}\n")
    with pytest.raises(LaunchFileError) as caught:
        LaunchLoader().load(path)
    assert caught.value.format() == (
        f"{path}:2:22: error: the file is not UTF-8 text (byte 0xe9) "
        "(expected a UTF-8 encoded YAML file)"
    )


@pytest.mark.parametrize(
    "case", ["unknown key", "text key given a number", "bad indentation", "alias bomb"]
)
def test_launchkit_run_exits_2_and_starts_nothing(tmp_path: Path, case: str) -> None:
    body, line, col, what = CASES[case]
    path = tmp_path / "bad.launch.yaml"
    first, _ = run_rejected(path, PROLOGUE, body)
    assert first.startswith(f"{path}:{line}:{col}: error: ") and what in first, first


def test_empty_and_rootless_files(tmp_path: Path) -> None:
    cases = {
        "": "the YAML file is empty",
        "# nothing\n": "the YAML file is empty",
        "- log: {message: hi}\n": "the YAML document is a list",
        "lunch: []\n": "the top-level key is the text 'lunch'",
        "launch: []\nother: 1\n": "a second top-level key",
        "launch:\n": "'launch' is empty",
    }
    for text, message in cases.items():
        path = tmp_path / "x.launch.yaml"
        path.write_text(text)
        with pytest.raises(LaunchFileError, match=message):
            LaunchLoader().load(path)
