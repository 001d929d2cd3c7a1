"""`launchkit build`'s mistakes and failures: what it says and its exit status (2 for a mistake
found before building, 1 for a failed package), and the package selection options. Most
workspaces here hold interface packages only, which build without pip."""

from __future__ import annotations

from pathlib import Path

import pytest
from workspaces import (
    environment,
    interface_package,
    launchkit_build,
    package_xml,
    python_package,
    write_package,
)

NUM = {"msg/Num.msg": "int64 num\n"}


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    """An empty workspace root (src/ made)."""
    (tmp_path / "ws" / "src").mkdir(parents=True)
    return tmp_path / "ws"


def _build(workspace: Path, *args: str) -> tuple[int, str, str]:
    result = launchkit_build(workspace, *args, env=environment(workspace.parent))
    return result.returncode, result.stdout, result.stderr


def _interfaces(workspace: Path, name: str, depends: list[str] | None = None) -> None:
    files = interface_package(name, NUM)
    if depends:
        files["package.xml"] = files["package.xml"].replace(
            "  <member_of_group>",
            "".join(f"  <depend>{d}</depend>\n" for d in depends) + "  <member_of_group>",
        )
    write_package(workspace / "src", name, files)


def test_no_src_folder_is_a_mistake(tmp_path: Path) -> None:
    status, _, err = _build(tmp_path)
    assert status == 2
    assert err.startswith(f"error: no 'src' folder in {tmp_path} (expected a workspace root")
    assert not (tmp_path / "install").exists()


def test_a_malformed_package_xml_is_reported_at_its_line(workspace: Path) -> None:
    _interfaces(workspace, "good_msgs")
    bad = workspace / "src" / "bad_pkg" / "package.xml"
    bad.parent.mkdir()
    bad.write_text(
        '<?xml version="1.0"?>\n<package format="3">\n  <name>bad_pkg</name>\n'
        "  <version>1\n</package>\n"
    )
    status, out, err = _build(workspace)
    assert status == 2, out
    assert err.startswith(
        "src/bad_pkg/package.xml:5:11: error: not well-formed XML: Opening and ending tag mismatch"
    )
    assert "Traceback" not in err
    assert not (workspace / "install").exists()  # found before anything was built


def test_a_package_xml_without_a_name_is_reported_at_its_root(workspace: Path) -> None:
    bad = workspace / "src" / "nameless" / "package.xml"
    bad.parent.mkdir()
    bad.write_text(
        '<?xml version="1.0"?>\n<package format="2">\n  <version>1.0.0</version>\n</package>\n'
    )
    status, _, err = _build(workspace)
    assert status == 2
    assert err.startswith("src/nameless/package.xml:2:1: error: no <name> (expected <name>")


def test_a_dependency_cycle_is_named(workspace: Path) -> None:
    _interfaces(workspace, "a_msgs", ["b_msgs"])
    _interfaces(workspace, "b_msgs", ["c_msgs"])
    _interfaces(workspace, "c_msgs", ["a_msgs"])
    status, out, err = _build(workspace)
    assert status == 2, out
    first = err.splitlines()[0]
    assert first.startswith("src/a_msgs/package.xml:")
    assert ": error: dependency cycle: a_msgs -> b_msgs -> c_msgs -> a_msgs" in first
    assert not (workspace / "install").exists()


def test_two_packages_of_one_name_are_a_mistake(workspace: Path) -> None:
    write_package(workspace / "src", "one/same_msgs", interface_package("same_msgs", NUM))
    write_package(workspace / "src", "two/same_msgs", interface_package("same_msgs", NUM))
    status, _, err = _build(workspace)
    assert status == 2
    assert "error: two packages are named 'same_msgs'" in err


def test_a_missing_dependency_names_the_package_that_wants_it(workspace: Path) -> None:
    _interfaces(workspace, "base_msgs")
    _interfaces(workspace, "wants_msgs", ["base_msgs", "no_such_pkg"])
    _interfaces(workspace, "after_msgs", ["wants_msgs"])
    status, out, _ = _build(workspace)
    assert status == 1, out
    assert "Failed   <<< wants_msgs: missing dependency: no_such_pkg" in out
    assert (
        "  src/wants_msgs/package.xml:14:3: error: package 'wants_msgs' depends on "
        "'no_such_pkg', which is not in the workspace, not installed and not provided by "
        "launchkit"
    ) in out
    assert "Skipped  --- after_msgs: depends on wants_msgs, which failed" in out
    assert "Finished <<< base_msgs" in out  # the rest is built
    assert "Summary: 1 package finished" in out
    assert "  1 package failed: wants_msgs" in out
    assert not (workspace / "install" / "wants_msgs").exists()


def test_well_known_and_installed_dependencies_are_not_missing(workspace: Path) -> None:
    files = interface_package("deps_msgs", NUM)
    known = [
        "rclpy",  # launchkit's own
        "python3-numpy",  # a rosdep key of a pip package
        "geometry_msgs",  # in the type store
        "robot_state_publisher",  # a stock package
        "yaml",  # an importable Python package
    ]
    files["package.xml"] = files["package.xml"].replace(
        "  <member_of_group>",
        "".join(f"  <exec_depend>{d}</exec_depend>\n" for d in known)
        + "  <test_depend>not_checked_test_dep</test_depend>\n  <member_of_group>",
    )
    write_package(workspace / "src", "deps_msgs", files)
    status, out, _ = _build(workspace)
    assert status == 0, out


def _three(workspace: Path) -> None:
    _interfaces(workspace, "base_msgs")
    _interfaces(workspace, "top_msgs", ["base_msgs"])
    _interfaces(workspace, "other_msgs")


def test_packages_select_builds_only_those(workspace: Path) -> None:
    _three(workspace)
    status, out, _ = _build(workspace, "--packages-select", "top_msgs")
    assert status == 0, out
    assert sorted(p.name for p in (workspace / "install").iterdir() if p.is_dir()) == ["top_msgs"]
    assert "Summary: 1 package finished" in out


def test_packages_up_to_builds_them_and_their_dependencies(workspace: Path) -> None:
    _three(workspace)
    status, out, _ = _build(workspace, "--packages-up-to", "top_msgs")
    assert status == 0, out
    installed = sorted(p.name for p in (workspace / "install").iterdir() if p.is_dir())
    assert installed == ["base_msgs", "top_msgs"]
    setup = (workspace / "install" / "local_setup.sh").read_text()
    assert "base_msgs" in setup and "other_msgs" not in setup


def test_an_unknown_selected_package_is_a_mistake(workspace: Path) -> None:
    _interfaces(workspace, "base_msgs")
    status, _, err = _build(workspace, "--packages-select", "nope")
    assert status == 2
    assert err.startswith(
        "error: --packages-select: no package named 'nope' in the workspace "
        "(expected one of: base_msgs)"
    )


def test_an_interface_package_outside_the_interface_group_fails_as_rosidl_does(
    workspace: Path,
) -> None:
    files = interface_package("lonely_msgs", NUM)
    files["package.xml"] = files["package.xml"].replace(
        "  <member_of_group>rosidl_interface_packages</member_of_group>\n", ""
    )
    write_package(workspace / "src", "lonely_msgs", files)
    status, out, _ = _build(workspace)
    assert status == 1
    assert "<member_of_group>rosidl_interface_packages</member_of_group>" in out


def test_cmake_beyond_what_launchkit_runs_is_skipped_with_where(workspace: Path) -> None:
    files = interface_package("loop_msgs", NUM)
    files["CMakeLists.txt"] = files["CMakeLists.txt"].replace(
        "ament_package()", "foreach(f a b)\nendforeach()\nament_package()"
    )
    write_package(workspace / "src", "loop_msgs", files)
    status, out, _ = _build(workspace)
    assert status == 0, out
    assert (
        "Skipped  --- loop_msgs: needs a ROS install (build it with colcon): it uses CMake's "
        "foreach() at src/loop_msgs/CMakeLists.txt:23:1, which launchkit build does not run"
    ) in out


def test_a_pip_failure_shows_pips_error_not_a_traceback_of_ours(workspace: Path) -> None:
    files = python_package("broken_py", {"run": "def main():\n    pass\n"})
    files["setup.py"] = files["setup.py"].replace("setup(\n", "setup(\n    oops here\n", 1)
    write_package(workspace / "src", "broken_py", files)
    _interfaces(workspace, "fine_msgs")
    status, out, err = _build(workspace)
    assert status == 1, out + err
    lines = out.splitlines()
    failed = next(i for i, line in enumerate(lines) if line.startswith("Failed   <<< broken_py ["))
    assert lines[failed].endswith(": pip exited with status 1")
    shown = "\n".join(lines[failed + 1 :])
    assert "  | error: subprocess-exited-with-error" in shown  # pip's first error line
    assert "SyntaxError" in shown  # from pip's last lines
    assert "stdout_stderr.log" in shown  # where the whole output is
    assert "launchkit/workspace" not in out + err
    assert "Finished <<< fine_msgs" in out
    assert "  1 package failed: broken_py" in out


def test_a_format_1_package_and_conditions_are_read(workspace: Path) -> None:
    files = interface_package("old_msgs", NUM)
    xml = package_xml("old_msgs", "ament_cmake", {"build_depend": ["std_msgs"]}, fmt=1)
    xml = xml.replace(
        "  <export>",
        "  <run_depend>rosidl_default_runtime</run_depend>\n"
        "  <member_of_group>rosidl_interface_packages</member_of_group>\n  <export>",
    )
    files["package.xml"] = xml
    write_package(workspace / "src", "old_msgs", files)
    cond = interface_package("cond_msgs", NUM)
    cond["package.xml"] = cond["package.xml"].replace(
        "  <member_of_group>",
        '  <depend condition="$ROS_VERSION == 1">roscpp_only_on_ros1</depend>\n'
        '  <depend condition="$ROS_VERSION == 2 and $ROS_DISTRO != humble">old_msgs</depend>\n'
        "  <member_of_group>",
    )
    write_package(workspace / "src", "cond_msgs", cond)
    status, out, _ = _build(workspace)
    assert status == 0, out
    assert out.index("Finished <<< old_msgs") < out.index("Starting >>> cond_msgs")


def test_base_paths_and_install_base_put_the_workspace_elsewhere(tmp_path: Path) -> None:
    root = tmp_path / "ws"  # no src/: the packages are in two other folders
    write_package(root / "repos" / "one", "one_msgs", interface_package("one_msgs", NUM))
    write_package(root / "more", "two_msgs", interface_package("two_msgs", NUM))
    status, out, _ = _build(
        root, "--base-paths", "repos", "more", "--install-base", "out/inst", "--log-base", "logs"
    )
    assert status == 0, out
    assert "Summary: 2 packages finished" in out
    installed = root / "out" / "inst"
    assert sorted(p.name for p in installed.iterdir() if p.is_dir()) == ["one_msgs", "two_msgs"]
    assert str(installed / "two_msgs") in (installed / "local_setup.sh").read_text()
    assert (root / "logs" / "latest_build").is_symlink() and not (root / "install").exists()
