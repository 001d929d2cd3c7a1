"""What launchkit reads of an ament_cmake package's CMakeLists.txt: the interface files and
install() rules of a package that needs no compiler, and why another one needs CMake."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.workspace.cmake_lexer import CMakeSyntaxError, read_commands
from launchkit.workspace.cmake_plan import CMakeError, NeedsRos, plan_cmake_package


def _package(tmp_path: Path, cmake: str, files: tuple[str, ...] = ()) -> Path:
    folder = tmp_path / "pkg"
    folder.mkdir(exist_ok=True)
    (folder / "CMakeLists.txt").write_text(cmake)
    for name in files:
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(name)
    return folder


def test_arguments_are_read_as_cmake_writes_them(tmp_path: Path) -> None:
    text = (
        "# a comment\n"
        "#[[ a bracket\ncomment ]]\n"
        'set(A "quoted ${X} \\"q\\"" [=[bracket ${X}]=] un\\;quoted)  # trailing\n'
        "if(NOT (A AND B))\nendif()\n"
    )
    (folder := tmp_path / "c").mkdir()
    (folder / "CMakeLists.txt").write_text(text)
    commands = read_commands(folder / "CMakeLists.txt", "CMakeLists.txt")
    assert [c.name for c in commands] == ["set", "if", "endif"]
    assert [(a.text, a.kind) for a in commands[0].arguments] == [
        ("A", "unquoted"),
        ('quoted ${X} \\"q\\"', "quoted"),
        ("bracket ${X}", "bracket"),
        ("un\\;quoted", "unquoted"),
    ]
    assert str(commands[0].location) == "CMakeLists.txt:4:1"
    assert [a.text for a in commands[1].arguments] == ["NOT", "(", "A", "AND", "B", ")"]


def test_an_unclosed_command_is_located(tmp_path: Path) -> None:
    folder = _package(tmp_path, 'project(x)\n\nset(A "b"\n')
    with pytest.raises(CMakeSyntaxError) as raised:
        plan_cmake_package(folder, "src/pkg")
    assert str(raised.value.location) == "src/pkg/CMakeLists.txt:3:1"


def test_interfaces_from_variables_lists_and_globs(tmp_path: Path) -> None:
    cmake = """\
project(demo)
set(msgs "msg/A.msg" msg/B.msg)
list(APPEND msgs "msg/C.msg")
file(GLOB services RELATIVE "${CMAKE_CURRENT_SOURCE_DIR}" "srv/*.srv")
rosidl_generate_interfaces(${PROJECT_NAME}
  ${msgs} ${services}
  "${CMAKE_CURRENT_SOURCE_DIR}:action/Go.action"
  "idl/deep/Thing.idl"
  DEPENDENCIES std_msgs builtin_interfaces
  LIBRARY_NAME lib
  ADD_LINTER_TESTS
)
"""
    files = ("msg/A.msg", "msg/B.msg", "msg/C.msg", "srv/S.srv", "srv/T.srv", "action/Go.action")
    folder = _package(tmp_path, cmake, (*files, "idl/deep/Thing.idl"))
    plan = plan_cmake_package(folder, "src/pkg")
    assert plan.interfaces is not None and plan.group_check
    assert [i.installed_as for i in plan.interfaces] == [
        "msg/A.msg",
        "msg/B.msg",
        "msg/C.msg",
        "srv/S.srv",
        "srv/T.srv",
        "action/Go.action",
        "idl/deep/Thing.idl",  # an .idl file keeps its folder, as rosidl installs it
    ]
    assert plan.interfaces[0].source == folder / "msg" / "A.msg"


def test_skip_install_and_the_group_check_option(tmp_path: Path) -> None:
    folder = _package(
        tmp_path, "rosidl_generate_interfaces(x msg/A.msg SKIP_INSTALL)\n", ("msg/A.msg",)
    )
    assert plan_cmake_package(folder, "src/pkg").interfaces is None
    folder = _package(
        tmp_path, "rosidl_generate_interfaces(x msg/A.msg SKIP_GROUP_MEMBERSHIP_CHECK)\n"
    )
    assert not plan_cmake_package(folder, "src/pkg").group_check


def test_a_missing_interface_file_is_an_error_at_the_call(tmp_path: Path) -> None:
    folder = _package(tmp_path, "project(x)\nrosidl_generate_interfaces(x\n  msg/Gone.msg)\n")
    with pytest.raises(CMakeError) as raised:
        plan_cmake_package(folder, "src/pkg")
    assert str(raised.value.location) == "src/pkg/CMakeLists.txt:2:1"
    assert "'msg/Gone.msg' does not exist" in raised.value.message


def test_install_rules(tmp_path: Path) -> None:
    cmake = """\
project(desc)
install(DIRECTORY launch urdf/ DESTINATION share/${PROJECT_NAME}
  FILES_MATCHING PATTERN "*.xml" PATTERN "*.urdf" PATTERN "old" EXCLUDE)
install(PROGRAMS scripts/run.py DESTINATION lib/${PROJECT_NAME} RENAME run)
install(FILES maybe.yaml DESTINATION share/${PROJECT_NAME} OPTIONAL COMPONENT x)
"""
    folder = _package(tmp_path, cmake)
    directory, programs, files = plan_cmake_package(folder, "src/pkg").installs
    assert directory.kind == "DIRECTORY" and directory.sources == ("launch", "urdf/")
    assert directory.destination == "share/desc" and directory.files_matching
    assert directory.patterns == (("*.xml", False), ("*.urdf", False), ("old", True))
    assert (programs.rename, programs.executable) == ("run", True)
    assert files.optional and not files.executable


def test_commands_inside_build_testing_are_not_run(tmp_path: Path) -> None:
    cmake = """\
project(x)
if(BUILD_TESTING)
  find_package(ament_cmake_gtest REQUIRED)
  ament_add_gtest(test_x test/test_x.cpp)
else()
  install(FILES a.txt DESTINATION share/x)
endif()
"""
    folder = _package(tmp_path, cmake, ("a.txt",))
    (rule,) = plan_cmake_package(folder, "src/pkg").installs
    assert rule.sources == ("a.txt",)


@pytest.mark.parametrize(
    ("line", "reason"),
    [
        ("add_executable(talker src/talker.cpp)", "it builds C++ (add_executable at "),
        ("install(TARGETS talker DESTINATION lib/x)", "it builds C++ (install(TARGETS ...) at "),
        ("ament_python_install_package(x)", "it builds C++ (ament_python_install_package at "),
        ("foreach(a b c)", "it uses CMake's foreach() at "),
        ("install(DIRECTORY d DESTINATION /opt/x)", "outside the install prefix"),
        ("install(DIRECTORY d DESTINATION share REGEX x)", "install(... REGEX ...)"),
        ("list(REMOVE_ITEM a b)", "it uses CMake's list() at "),
    ],
)
def test_what_needs_cmake_says_why_and_where(tmp_path: Path, line: str, reason: str) -> None:
    folder = _package(tmp_path, f"project(x)\n{line}\n")
    with pytest.raises(NeedsRos) as raised:
        plan_cmake_package(folder, "src/pkg")
    assert reason in raised.value.reason
    assert "src/pkg/CMakeLists.txt:2:1" in raised.value.reason
