"""`launchkit build` on a workspace of a plain Python package, an interface package, a package
using both, and a C++ package: what it says, and the ament layout it installs."""

from __future__ import annotations

import os

from conftest import INTERFACES, Built

#: An upper bound for the whole build (two packages built by pip) on a busy machine.
BUILD_SECONDS = 120


def test_the_build_finishes_what_pip_can_build_and_skips_cpp_with_the_reason(built: Built) -> None:
    out = built.result.stdout
    assert built.result.returncode == 0, out + built.result.stderr
    assert "Summary: 3 packages finished" in out
    assert (
        "Skipped  --- demo_cpp: needs a ROS install (build it with colcon): it builds C++ "
        "(add_executable at src/cpp/demo_cpp/CMakeLists.txt:6:1)"
    ) in out
    assert "Skipped  --- demo_cpp_user: depends on demo_cpp, which was skipped" in out
    assert "  2 packages skipped: demo_cpp, demo_cpp_user" in out
    assert not (built.install / "demo_cpp").exists()
    assert built.seconds < BUILD_SECONDS


def test_a_package_starts_only_after_what_it_depends_on_finished(built: Built) -> None:
    lines = built.result.stdout.splitlines()
    started = lines.index("Starting >>> demo_user")
    finished = [i for i, line in enumerate(lines) if line.startswith("Finished <<< ")]
    done_before = {lines[i].split()[2] for i in finished if i < started}
    assert {"talker_py", "demo_interfaces"} <= done_before


def test_a_python_package_lands_in_the_ament_layout(built: Built) -> None:
    prefix = built.install / "talker_py"
    talk = prefix / "lib" / "talker_py" / "talk"
    assert talk.is_file() and os.access(talk, os.X_OK)
    assert not (prefix / "bin").exists()  # setup.cfg's install_scripts moved the script
    assert (prefix / "share/ament_index/resource_index/packages/talker_py").is_file()
    assert (prefix / "share/talker_py/package.xml").read_text().count("<name>talker_py</name>")
    assert (prefix / "share/talker_py/launch/talk.launch.xml").is_file()
    assert "hi from the params file" in (prefix / "share/talker_py/config/talk.yaml").read_text()
    (site,) = prefix.glob("lib/python3.*/site-packages")
    assert (site / "talker_py" / "talk.py").is_file()
    assert not (site / "test").exists()  # find_packages(exclude=['test'])
    run_deps = prefix / "share/colcon-core/packages/talker_py"
    assert run_deps.read_text() == "rclpy:std_msgs"


def test_an_interface_package_installs_its_files_and_index_without_a_compiler(
    built: Built,
) -> None:
    prefix = built.install / "demo_interfaces"
    share = prefix / "share" / "demo_interfaces"
    for name, text in INTERFACES.items():
        assert (share / name).read_text() == text
    assert (share / "README.md").is_file()  # install(FILES README.md DESTINATION share/...)
    index = prefix / "share/ament_index/resource_index"
    assert (index / "packages/demo_interfaces").is_file()
    assert (index / "rosidl_interfaces/demo_interfaces").read_text() == (
        "action/Count.action\nmsg/Num.msg\nsrv/AddThree.srv"
    )
    assert not (prefix / "lib").exists()


def test_the_source_stays_clean_and_pip_output_is_logged(built: Built) -> None:
    src = built.root / "src" / "talker_py"
    assert not list(src.glob("*.egg-info")) and not (src / "build").exists()
    assert (built.root / "build" / "talker_py" / "setup.py").is_file()  # pip's working copy
    log = built.root / "log" / "latest_build" / "talker_py" / "stdout_stderr.log"
    assert "Successfully installed talker_py" in log.read_text()
    for folder in ("build", "install", "log"):
        assert (built.root / folder / "COLCON_IGNORE").is_file()


def test_nothing_is_written_to_the_home_folder(built: Built) -> None:
    # pip describes itself to indexes with `rustc --version` (even offline), and rustup's
    # `rustc` writes its settings on a first run: rustup's doing, where it is installed
    assert sorted(p.name for p in built.home.iterdir()) in ([], [".rustup"])
