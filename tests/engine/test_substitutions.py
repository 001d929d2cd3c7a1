"""Parse-level tests, one or more per substitution, and the quoting rules of the grammar."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from launchkit.errors import LaunchFileError, LaunchkitError
from launchkit.packages import PackageIndex, PythonPackage
from tests.conftest import EvaluateXml
from tests.support import ament_package


def say(evaluate_xml: EvaluateXml, value: str, **kwargs: object) -> str:
    """What ``<log message=VALUE/>`` prints."""
    result = evaluate_xml(f'<launch><log message="{value}"/></launch>', **kwargs)
    return result.messages()[0]


def test_var_with_and_without_default(evaluate_xml: EvaluateXml) -> None:
    assert say(evaluate_xml, "$(var missing 'fallback')") == "fallback"
    assert say(evaluate_xml, "$(var x)", args={"x": "given"}) == "given"
    with pytest.raises(LaunchkitError, match="launch configuration 'missing' is not defined"):
        say(evaluate_xml, "$(var missing)")


def test_env_with_and_without_default(evaluate_xml: EvaluateXml) -> None:
    assert say(evaluate_xml, "$(env HOME)", env={"HOME": "/home/r"}) == "/home/r"
    assert say(evaluate_xml, "[$(env NOPE '')]", env={}) == "[]"
    with pytest.raises(LaunchkitError, match="environment variable 'NOPE' is not set"):
        say(evaluate_xml, "$(env NOPE)", env={})


def test_eval_does_math(evaluate_xml: EvaluateXml) -> None:
    assert say(evaluate_xml, "$(eval '2 * 21')") == "42"
    assert say(evaluate_xml, "$(eval 'round(math.pi, 2)')") == "3.14"
    assert say(evaluate_xml, "$(eval '$(var n) + 1')", args={"n": "4"}) == "5"


@pytest.mark.parametrize(
    "expression",
    [
        "open('/etc/passwd').read()",
        "__import__('os').system('true')",
        "().__class__.__bases__[0].__subclasses__()",
        "exec('1')",
        "globals()",
    ],
)
def test_eval_cannot_reach_files_imports_or_the_process(
    evaluate_xml: EvaluateXml, expression: str
) -> None:
    with pytest.raises(LaunchkitError):
        say(evaluate_xml, f'$(eval "{expression}")')


def test_command_captures_stdout(evaluate_xml: EvaluateXml) -> None:
    assert say(evaluate_xml, "$(command 'echo hello')") == "hello\n"


def test_command_failure_modes(evaluate_xml: EvaluateXml) -> None:
    noisy = "sh -c \\&quot;echo out; echo err >&amp;2\\&quot;"
    with pytest.raises(LaunchkitError, match="wrote to stderr: err"):
        say(evaluate_xml, f"$(command '{noisy}')")
    with pytest.raises(LaunchkitError, match="wrote to stderr: err"):
        say(evaluate_xml, f"$(command '{noisy}' fail)")
    assert say(evaluate_xml, f"$(command '{noisy}' ignore)") == "out\n"
    warned = evaluate_xml(f"<launch><log message=\"$(command '{noisy}' warn)\"/></launch>")
    assert warned.logs[0].startswith("[WARNING]") and "err" in warned.logs[0]
    assert warned.messages()[1] == "out\n"
    assert say(evaluate_xml, f"$(command '{noisy}' capture)") == "out\nerr\n"


@pytest.mark.parametrize("on_stderr", ["fail", "ignore", "warn", "capture"])
def test_command_exit_status_fails_in_every_mode(evaluate_xml: EvaluateXml, on_stderr: str) -> None:
    with pytest.raises(LaunchkitError, match="failed with exit code 3: oops"):
        say(
            evaluate_xml,
            f"$(command 'sh -c \\&quot;echo oops >&amp;2; exit 3\\&quot;' {on_stderr})",
        )


def test_a_failing_command_is_quoted_by_its_last_error_lines(
    evaluate_xml: EvaluateXml, tmp_path: Path
) -> None:
    script = tmp_path / "gen.py"
    script.write_text("def deep(n):\n    return deep(n - 1) if n else 1 / 0\n\ndeep(20)\n")
    with pytest.raises(LaunchkitError) as caught:
        say(evaluate_xml, f"$(command '{sys.executable} {script}')")
    message = caught.value.format()
    lines = message.splitlines()
    assert "failed with exit code 1; the last 4 of its" in lines[0]
    assert len(lines) == 5  # the headline and 4 quoted lines, not the whole traceback
    assert lines[-1] == "  | ZeroDivisionError: division by zero"
    assert "Traceback (most recent call last)" not in message


def test_command_of_missing_program_fails(evaluate_xml: EvaluateXml) -> None:
    with pytest.raises(LaunchkitError, match="no-such-program"):
        say(evaluate_xml, "$(command 'no-such-program-xyz')")


def test_find_exec(evaluate_xml: EvaluateXml) -> None:
    assert say(evaluate_xml, "$(find-exec sh)", env={"PATH": "/bin:/usr/bin"}).endswith("/sh")
    with pytest.raises(LaunchkitError, match="no-such-program"):
        say(evaluate_xml, "$(find-exec no-such-program)")


@pytest.fixture
def packages(tmp_path: Path) -> PackageIndex:
    """An index with one Python package and one AMENT_PREFIX_PATH package."""
    share = tmp_path / "py_pkg_share"
    share.mkdir()
    prefix = ament_package(tmp_path / "ament", "amentpkg", {"tool": "#!/bin/sh\n"})
    return PackageIndex(
        python_packages={"py_pkg": PythonPackage("py_pkg", share, {"talker": "py_pkg.talker"})},
        ament_prefix_path=str(prefix),
    )


def test_package_substitutions(evaluate_xml: EvaluateXml, packages: PackageIndex, tmp_path) -> None:
    assert say(evaluate_xml, "$(find-pkg-share py_pkg)", packages=packages) == str(
        tmp_path / "py_pkg_share"
    )
    assert say(evaluate_xml, "$(find-pkg-share amentpkg)", packages=packages) == str(
        tmp_path / "ament" / "share" / "amentpkg"
    )
    assert say(evaluate_xml, "$(find-pkg-prefix amentpkg)", packages=packages) == str(
        tmp_path / "ament"
    )
    assert say(evaluate_xml, "$(exec-in-pkg tool amentpkg)", packages=packages) == str(
        tmp_path / "ament" / "lib" / "amentpkg" / "tool"
    )
    python_exec = say(evaluate_xml, "$(exec-in-pkg talker py_pkg)", packages=packages)
    assert python_exec == f"{sys.executable} -m py_pkg.talker"


def test_unknown_package_lists_where_it_looked(
    evaluate_xml: EvaluateXml, packages: PackageIndex
) -> None:
    with pytest.raises(LaunchkitError, match="nopkg") as caught:
        say(evaluate_xml, "$(find-pkg-share nopkg)", packages=packages)
    assert "ament" in caught.value.format()


def test_dirname_and_filename(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    assert say(evaluate_xml, "$(dirname)") == str(tmp_path)
    assert say(evaluate_xml, "$(filename)") == str(tmp_path / "test.launch.xml")


def test_dirname_follows_includes(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "child.launch.xml").write_text(
        '<launch><log message="$(dirname)"/></launch>'
    )
    xml = '<launch><include file="$(dirname)/sub/child.launch.xml"/></launch>'
    assert evaluate_xml(xml).messages() == [str(tmp_path / "sub")]


def test_anon_is_stable_within_a_run_and_unique(evaluate_xml: EvaluateXml) -> None:
    result = evaluate_xml(
        '<launch><log message="$(anon n)"/><log message="$(anon n)"/>'
        '<log message="$(anon m)"/></launch>'
    )
    first, again, other = result.messages()
    assert first == again and first.startswith("n_") and other != first


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        ("$(not true)", "false"),
        ("$(not false)", "true"),
        ("$(and true false)", "false"),
        ("$(and true 1)", "true"),
        ("$(or false 0)", "false"),
        ("$(or false true)", "true"),
        ("$(any false false true)", "true"),
        ("$(any false false)", "false"),
        ("$(all true true true)", "true"),
        ("$(all true false true)", "false"),
        ("$(equals a a)", "true"),
        ("$(equals a b)", "false"),
        ("$(not-equals a b)", "true"),
        ("$(if true yes no)", "yes"),
        ("$(if false yes no)", "no"),
        ("$(if $(equals 1 1) yes)", "yes"),
    ],
)
def test_logic_substitutions(evaluate_xml: EvaluateXml, value: str, expected: str) -> None:
    assert say(evaluate_xml, value) == expected


def test_logic_rejects_non_booleans(evaluate_xml: EvaluateXml) -> None:
    with pytest.raises(LaunchkitError, match="maybe"):
        say(evaluate_xml, "$(not maybe)")


def test_file_content(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    (tmp_path / "text.txt").write_text("from a file")
    assert say(evaluate_xml, "$(file-content $(dirname)/text.txt)") == "from a file"


def test_log_dir(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    assert say(evaluate_xml, "$(log_dir)") == str(tmp_path / "log")


def test_param_reads_a_global_parameter(evaluate_xml: EvaluateXml) -> None:
    xml = '<launch><set_parameter name="rate" value="5"/><log message="$(param rate)"/></launch>'
    assert evaluate_xml(xml).messages() == ["5"]


def test_nesting_and_quotes(evaluate_xml: EvaluateXml) -> None:
    args = {"name": "world", "who": "name"}
    assert say(evaluate_xml, "$(var $(var who))", args=args) == "world"
    assert say(evaluate_xml, "$(var x 'a b c')") == "a b c"
    assert say(evaluate_xml, "$(var x \\'q\\')") == "'q'"
    assert say(evaluate_xml, "pre-$(var name)-post", args=args) == "pre-world-post"


def test_escaped_dollar_is_literal(evaluate_xml: EvaluateXml) -> None:
    assert say(evaluate_xml, "\\$(var x)") == "$(var x)"


@pytest.mark.parametrize(
    ("value", "what"),
    [
        ("$(var x", "unterminated"),
        ("$(nosuch x)", r"unknown substitution \$\(nosuch\)"),
        ("$(var)", "var"),
        ("$(dirname extra)", "dirname"),
        ("$(env A B C)", "env"),
        ("$(var 'unclosed)", "quote"),
    ],
)
def test_malformed_substitutions_are_caught_at_parse_time(
    evaluate_xml: EvaluateXml, value: str, what: str
) -> None:
    with pytest.raises(LaunchFileError, match=what) as caught:
        evaluate_xml(f'<launch>\n  <log message="ok"/>\n  <log message="{value}"/>\n</launch>')
    location = caught.value.location
    assert location is not None and location.line == 3
