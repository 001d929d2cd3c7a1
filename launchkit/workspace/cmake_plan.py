"""What an ``ament_cmake`` package's CMakeLists.txt installs, when it needs no compiler.

A package qualifies when its CMakeLists.txt only declares interfaces
(``rosidl_generate_interfaces``), installs files (``install(FILES|PROGRAMS|DIRECTORY ...)``),
and otherwise uses commands that do nothing without compiled targets (``project``,
``find_package``, ``set``, ``add_compile_options``, ``ament_package``, ...). Commands inside
``if(BUILD_TESTING)`` are not run (no tests are built); the branches of any other ``if`` are
all read, without evaluating their conditions. Anything else (``add_executable``,
``add_library``, ``install(TARGETS ...)``, ``foreach``, a command this module does not know)
raises :class:`NeedsRos`: such a package needs CMake and a ROS install.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from launchkit.errors import Location, UserError
from launchkit.workspace.cmake_lexer import Argument, Command, read_commands
from launchkit.workspace.cmake_rules import InstallRule, install_rule

#: Commands that have no effect on what is installed when there are no compiled targets.
HARMLESS = frozenset(
    {
        "cmake_minimum_required",
        "cmake_policy",
        "find_package",
        "message",
        "add_compile_options",
        "add_definitions",
        "add_compile_definitions",
        "include_directories",
        "include",
        "option",
        "ament_export_dependencies",
        "ament_export_include_directories",
        "ament_lint_auto_find_test_dependencies",
        "ament_package",
    }
)
#: Commands that build C++ (or other compiled) targets.
COMPILING = frozenset(
    {
        "add_executable",
        "add_library",
        "add_custom_target",
        "add_custom_command",
        "ament_auto_add_executable",
        "ament_auto_add_library",
        "ament_auto_package",
        "ament_target_dependencies",
        "target_link_libraries",
        "target_include_directories",
        "target_compile_options",
        "target_compile_definitions",
        "target_compile_features",
        "rclcpp_components_register_node",
        "rclcpp_components_register_nodes",
        "ament_python_install_package",
    }
)
_VARIABLE = re.compile(r"\$(ENV|CACHE)?\{([^${}]*)\}")
_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", ";": "\0"}  # \; stays one item: \0 till split
_ROSIDL_OPTIONS = ("ADD_LINTER_TESTS", "SKIP_INSTALL", "SKIP_GROUP_MEMBERSHIP_CHECK")
_ROSIDL_KEYWORDS = ("DEPENDENCIES", "LIBRARY_NAME", *_ROSIDL_OPTIONS)


class NeedsRos(Exception):
    """The package needs CMake and a ROS install; ``reason`` says why, with a location."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


class CMakeError(UserError):
    """The CMakeLists.txt asks for something CMake itself would refuse (a missing file)."""


@dataclass(frozen=True)
class InterfaceFile:
    """An interface file and where it goes under ``share/PKG/`` (``msg/Foo.msg``)."""

    source: Path
    installed_as: str


@dataclass(frozen=True)
class CMakePlan:
    """What the package installs: interface files (``None`` when it declares none, or
    declares them with ``SKIP_INSTALL``) and ``install()`` rules, in the file's order."""

    interfaces: tuple[InterfaceFile, ...] | None
    group_check: bool
    installs: tuple[InstallRule, ...]


def plan_cmake_package(folder: Path, shown_folder: str) -> CMakePlan:
    """The plan of the package in ``folder``; :class:`NeedsRos` when it needs CMake,
    :class:`CMakeError` (or a syntax error) for a file CMake would also refuse."""
    cmake_file = folder / "CMakeLists.txt"
    shown = os.path.join(shown_folder, "CMakeLists.txt")
    if not cmake_file.is_file():
        raise CMakeError(
            "an ament_cmake package without a CMakeLists.txt", Location(shown), expected="one"
        )
    return _Interpreter(folder).run(read_commands(cmake_file, shown))


class _Interpreter:
    def __init__(self, folder: Path) -> None:
        source = str(folder)
        self.folder = folder
        self.variables = {
            "CMAKE_CURRENT_SOURCE_DIR": source,
            "CMAKE_CURRENT_LIST_DIR": source,
            "CMAKE_SOURCE_DIR": source,
            "PROJECT_SOURCE_DIR": source,
            "CMAKE_INSTALL_BINDIR": "bin",
            "CMAKE_INSTALL_LIBDIR": "lib",
            "CMAKE_INSTALL_DATADIR": "share",
            "CMAKE_INSTALL_INCLUDEDIR": "include",
        }
        self.interfaces: list[InterfaceFile] | None = None
        self.group_check = False
        self.installs: list[InstallRule] = []
        self.testing: list[bool] = []  # per open if(): True while in if(BUILD_TESTING)'s body

    def run(self, commands: list[Command]) -> CMakePlan:
        handlers: dict[str, Callable[[Command, list[str]], None]] = {
            "project": self._project,
            "set": self._set,
            "unset": self._unset,
            "list": self._list,
            "file": self._file,
            "rosidl_generate_interfaces": self._interfaces,
            "install": self._install,
        }
        for command in commands:
            if self._flow(command) or any(self.testing):
                continue
            if command.name in HARMLESS:
                continue
            handler = handlers.get(command.name)
            if handler is None:
                raise NeedsRos(self._why(command))
            handler(command, self._arguments(command.arguments))
        interfaces = None if self.interfaces is None else tuple(self.interfaces)
        return CMakePlan(interfaces, self.group_check, tuple(self.installs))

    @staticmethod
    def _why(command: Command) -> str:
        if command.name in COMPILING:
            return f"it builds C++ ({command.name} at {command.location})"
        return (
            f"it uses CMake's {command.name}() at {command.location}, "
            "which launchkit build does not run"
        )

    def _flow(self, command: Command) -> bool:
        """Follows if/else/endif; True when ``command`` was one of them."""
        if command.name == "if":
            words = [a.text for a in command.arguments]
            self.testing.append(words in (["BUILD_TESTING"], ["${BUILD_TESTING}"]))
        elif command.name in ("else", "elseif") and self.testing:
            self.testing[-1] = False
        elif command.name == "endif" and self.testing:
            self.testing.pop()
        else:
            return False
        return True

    # -- arguments -------------------------------------------------------------------------

    def _arguments(self, arguments: tuple[Argument, ...]) -> list[str]:
        values: list[str] = []
        for argument in arguments:
            if argument.kind == "bracket":
                values.append(argument.text)
                continue
            text = self._expand(_unescape(argument.text))
            if argument.kind == "quoted":
                values.append(text.replace("\0", ";"))
            else:
                values.extend(i.replace("\0", ";") for i in text.split(";") if i)
        return values

    def _expand(self, text: str) -> str:
        for _ in range(16):  # nested references expand inside out
            expanded = _VARIABLE.sub(self._value, text)
            if expanded == text:
                break
            text = expanded
        return text

    def _value(self, match: re.Match[str]) -> str:
        if match.group(1) == "ENV":
            return os.environ.get(match.group(2), "")
        return self.variables.get(match.group(2), "")

    # -- commands --------------------------------------------------------------------------

    def _project(self, command: Command, args: list[str]) -> None:
        if args:
            self.variables["PROJECT_NAME"] = args[0]
            self.variables[f"{args[0]}_SOURCE_DIR"] = str(self.folder)

    def _set(self, command: Command, args: list[str]) -> None:
        if args:
            values = [a for a in args[1:] if a not in ("PARENT_SCOPE",)]
            if "CACHE" in values:
                values = values[: values.index("CACHE")]
            self.variables[args[0]] = ";".join(values)

    def _unset(self, command: Command, args: list[str]) -> None:
        if args:
            self.variables.pop(args[0], None)

    def _list(self, command: Command, args: list[str]) -> None:
        if len(args) < 2 or args[0] != "APPEND":
            raise NeedsRos(self._why(command))
        items = [i for i in self.variables.get(args[1], "").split(";") if i]
        self.variables[args[1]] = ";".join(items + args[2:])

    def _file(self, command: Command, args: list[str]) -> None:
        if len(args) < 2 or args[0] != "GLOB":
            raise NeedsRos(self._why(command))
        relative: Path | None = None
        patterns = args[2:]
        if patterns[:1] == ["RELATIVE"] and len(patterns) > 1:
            relative, patterns = Path(patterns[1]), patterns[2:]
        found: list[str] = []
        for pattern in patterns:
            base = pattern if os.path.isabs(pattern) else str(self.folder / pattern)
            for path in sorted(Path("/").glob(base.lstrip("/"))):
                found.append(os.path.relpath(path, relative) if relative else str(path))
        self.variables[args[1]] = ";".join(found)

    def _interfaces(self, command: Command, args: list[str]) -> None:
        files: list[str] = []
        keyword = ""
        options: set[str] = set()
        for arg in args[1:]:  # the first argument is the target's name
            if arg in _ROSIDL_KEYWORDS:
                keyword = "" if arg in _ROSIDL_OPTIONS else arg
                options.add(arg)
            elif keyword == "LIBRARY_NAME":
                keyword = ""  # it takes one value; more are files again
            elif keyword == "":
                files.append(arg)
        if not files:
            raise CMakeError(
                "rosidl_generate_interfaces() without interface files",
                command.location,
                expected='files such as "msg/Foo.msg"',
            )
        if "SKIP_INSTALL" in options:
            return
        self.group_check = "SKIP_GROUP_MEMBERSHIP_CHECK" not in options
        found = [] if self.interfaces is None else self.interfaces
        found.extend(self._interface_file(command, name) for name in files)
        self.interfaces = found

    def _interface_file(self, command: Command, name: str) -> InterfaceFile:
        if os.path.isabs(name):
            base, colon, relative = name.rpartition(":")
            if not colon:
                raise CMakeError(
                    f"rosidl_generate_interfaces(): the absolute file '{name}' is not given "
                    "as BASE:RELATIVE",
                    command.location,
                    expected="a path relative to the package, or /base/path:msg/Foo.msg",
                )
            source = Path(base) / relative
        else:
            source, relative = self.folder / name, name
        if not source.is_file():
            raise CMakeError(
                f"rosidl_generate_interfaces(): '{name}' does not exist",
                command.location,
                expected="a file relative to the package's folder",
            )
        path = Path(relative)
        # rosidl: .idl files keep their relative folder, others go by their parent's name
        folder = path.parent if path.suffix == ".idl" else Path(path.parent.name)
        return InterfaceFile(source, (folder / path.name).as_posix())

    def _install(self, command: Command, args: list[str]) -> None:
        rule = install_rule(command.location, args)
        if isinstance(rule, str):
            raise NeedsRos(rule)
        self.installs.append(rule)


def _unescape(text: str) -> str:
    out: list[str] = []
    position = 0
    while position < len(text):
        char = text[position]
        if char == "\\" and position + 1 < len(text):
            following = text[position + 1]
            out.append(_ESCAPES.get(following, following) if following != "\n" else "")
            position += 2
        else:
            out.append(char)
            position += 1
    return "".join(out)
