"""The package index: where a package's share directory and executables are.

Three sources, searched in this order:

1. Python distributions that register a :class:`PythonPackage` in the ``launchkit.packages``
   entry-point group (``robot_wheel`` and a user's own packages come this way);
2. ``AMENT_PREFIX_PATH`` prefixes laid out as ROS lays them out
   (``PREFIX/share/ament_index/resource_index/packages/PKG``, ``PREFIX/share/PKG``,
   ``PREFIX/lib/PKG/EXEC``), so a real ROS 2 install or a built workspace works unchanged;
3. launchkit's stand-ins for ROS packages (``stand_in=True``, registered the same way as 1.),
   which serve where no real package of the name is installed.

``$LAUNCHKIT_STANDINS`` changes 3.'s place: ``prefer`` puts the stand-ins first (before 1. and
2.), ``never`` leaves them out; ``auto`` (the default) is the order above.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from dataclasses import KW_ONLY, dataclass, field
from pathlib import Path

from launchkit.envvars import STANDINS
from launchkit.errors import LaunchArgumentError, PackageNotFoundError

ENTRY_POINT_GROUP = "launchkit.packages"

#: Folders of a share directory searched for launch files, in order.
LAUNCH_FOLDERS = ("", "launch", "launch_xml")

#: The values of ``$LAUNCHKIT_STANDINS``: where launchkit's stand-ins come among the sources.
STANDIN_POLICIES = ("auto", "prefer", "never")


def is_file(path: Path) -> bool:
    """Whether ``path`` is a file; False too when the system refuses to look (a name too long,
    which :meth:`Path.is_file` raises for)."""
    try:
        return path.is_file()
    except OSError:
        return False


def exists(path: Path) -> bool:
    """Whether ``path`` exists; False too when the system refuses to look."""
    try:
        return path.exists()
    except OSError:
        return False


@dataclass(frozen=True)
class PythonPackage:
    """A ROS-style package provided by a Python distribution.

    ``executables`` maps an executable name (what ``<node exec=...>`` names) to the Python
    module that runs it as ``python -m MODULE``. ``programs`` maps a program launch files call
    by bare name (``gazebo``, ``rviz2``) to the executable that stands in for it when no such
    program is on the PATH. ``stand_in``: launchkit's stand-in for a ROS package, which a real
    package of the same name wins over (see the module).
    """

    name: str
    share: Path
    executables: Mapping[str, str] = field(default_factory=dict)
    programs: Mapping[str, str] = field(default_factory=dict)
    _: KW_ONLY
    stand_in: bool = False


@dataclass(frozen=True)
class FoundPackage:
    """A package as the index found it: where it lives and which source it came from."""

    name: str
    prefix: Path
    share: Path
    source: str
    python: PythonPackage | None = None


class PackageIndex:
    """Answers "share dir of PKG", "executable EXEC of PKG" and "which launch file is FILE"."""

    def __init__(
        self,
        ament_prefix_path: str | None = None,
        python_packages: Mapping[str, PythonPackage] | None = None,
        stand_ins: str | None = None,
    ) -> None:
        if ament_prefix_path is None:
            ament_prefix_path = os.environ.get("AMENT_PREFIX_PATH", "")
        self._prefixes = [Path(p) for p in ament_prefix_path.split(os.pathsep) if p]
        self._python = python_packages
        self._cache: dict[str, FoundPackage | None] = {}
        self.stand_ins = stand_in_policy(stand_ins)

    # -- sources -----------------------------------------------------------------------------

    def python_packages(self) -> Mapping[str, PythonPackage]:
        """Packages registered by installed Python distributions (loaded once, lazily)."""
        if self._python is None:
            self._python = _load_entry_points()
        return self._python

    def _ament_package(self, name: str) -> FoundPackage | None:
        for prefix in self._prefixes:
            marker = prefix / "share" / "ament_index" / "resource_index" / "packages" / name
            if exists(marker):
                return FoundPackage(name, prefix, prefix / "share" / name, f"ament:{prefix}")
        return None

    # -- queries -----------------------------------------------------------------------------

    def ament_package(self, name: str) -> FoundPackage | None:
        """The package ``name`` if an ``AMENT_PREFIX_PATH`` prefix has it (no Python
        distribution's registrations are read: cheap enough for an import hook)."""
        return self._ament_package(name)

    def find(self, name: str) -> FoundPackage:
        """The package ``name``; :class:`PackageNotFoundError` listing where it looked."""
        if name not in self._cache:
            self._cache[name] = self._lookup(name)
        found = self._cache[name]
        if found is None:
            raise PackageNotFoundError(
                f"package '{name}' not found",
                expected="a package registered by an installed Python distribution "
                "or present in AMENT_PREFIX_PATH",
                hint="searched " + self.describe_search_path(),
            )
        return found

    def _lookup(self, name: str) -> FoundPackage | None:
        python = self.python_packages().get(name)
        stand_in = None
        if python is not None and python.stand_in:
            python, stand_in = None, python
            if self.stand_ins == "never":
                stand_in = None
        if stand_in is not None and self.stand_ins == "prefer":
            return FoundPackage(name, stand_in.share, stand_in.share, "stand-in", stand_in)
        if python is not None:
            return FoundPackage(name, python.share, python.share, "python", python)
        found = self._ament_package(name)
        if found is None and stand_in is not None:
            return FoundPackage(name, stand_in.share, stand_in.share, "stand-in", stand_in)
        return found

    def describe_search_path(self) -> str:
        """Human-readable list of the places packages are searched for."""
        places = [f"entry points '{ENTRY_POINT_GROUP}' ({len(self.python_packages())} packages)"]
        if self._prefixes:
            places.append("AMENT_PREFIX_PATH=" + os.pathsep.join(map(str, self._prefixes)))
        else:
            places.append("AMENT_PREFIX_PATH (not set)")
        if self.stand_ins == "never":
            places.append(f"not launchkit's stand-ins ({STANDINS}=never)")
        return ", ".join(places)

    def names(self) -> list[str]:
        """Every known package name, sorted."""
        names = {
            name
            for name, package in self.python_packages().items()
            if not (package.stand_in and self.stand_ins == "never")
        }
        for prefix in self._prefixes:
            index = prefix / "share" / "ament_index" / "resource_index" / "packages"
            if index.is_dir():
                names.update(p.name for p in index.iterdir())
        return sorted(names)

    def share_dir(self, name: str) -> Path:
        """What ``$(find-pkg-share NAME)`` returns."""
        return self.find(name).share

    def prefix(self, name: str) -> Path:
        """What ``$(find-pkg-prefix NAME)`` and ``launchkit pkg prefix`` return."""
        return self.find(name).prefix

    def executable(self, package: str, executable: str) -> list[str]:
        """The argv prefix that runs ``executable`` of ``package``."""
        found = self.find(package)
        if found.python is not None:
            module = found.python.executables.get(executable)
            if module is not None:
                return [sys.executable, "-m", module]
            known = ", ".join(sorted(found.python.executables)) or "none"
            raise PackageNotFoundError(
                f"executable '{executable}' not found in package '{package}'",
                expected=f"one of: {known}",
            )
        libdir = found.prefix / "lib" / package
        candidate = libdir / executable
        if is_file(candidate) and os.access(candidate, os.X_OK):
            return [str(candidate)]
        raise PackageNotFoundError(
            f"executable '{executable}' not found in package '{package}'",
            expected=f"an executable file {candidate}",
        )

    def stand_in(self, program: str) -> tuple[str, list[str]] | None:
        """The package and argv prefix of launchkit's stand-in for bare program name
        ``program`` (``gazebo`` -> gazebo_ros's server), or None (always with
        ``$LAUNCHKIT_STANDINS=never``)."""
        if self.stand_ins == "never":
            return None
        for name, package in sorted(self.python_packages().items()):
            executable = package.programs.get(program)
            if executable is not None:
                return name, self.executable(name, executable)
        return None

    def executables(self, package: str) -> list[str]:
        """Names of the executables ``package`` provides."""
        found = self.find(package)
        if found.python is not None:
            return sorted(found.python.executables)
        libdir = found.prefix / "lib" / package
        if not libdir.is_dir():
            return []
        return sorted(p.name for p in libdir.iterdir() if os.access(p, os.X_OK) and p.is_file())

    def launch_file(self, package: str, filename: str) -> Path:
        """``launchkit run PKG FILE``: FILE in the package's share dir or its launch folders."""
        share = self.share_dir(package)
        for candidate in _launch_candidates(share, filename):
            if is_file(candidate):
                return candidate
        if filename in self.executables(package):
            raise PackageNotFoundError(
                f"'{filename}' is an executable of package '{package}', not a launch file",
                expected="PKG FILE with a launch file of the package",
                hint=f"run one executable with `launchkit exec {package} {filename}` "
                "(what `ros2 run` does)",
            )
        raise PackageNotFoundError(
            f"launch file '{filename}' not found in package '{package}'",
            expected="a file in "
            + ", ".join(str(share / f) for f in LAUNCH_FOLDERS if f)
            + f" or {share}",
        )

    def find_launch_file(self, filename: str) -> list[Path]:
        """Every known package's launch file named ``filename`` (bare-name ``launchkit run``)."""
        matches: list[Path] = []
        for name in self.names():
            try:
                share = self.share_dir(name)
            except PackageNotFoundError:
                continue
            for candidate in _launch_candidates(share, filename):
                if is_file(candidate):
                    matches.append(candidate)
                    break
        return matches


def stand_in_policy(value: str | None = None) -> str:
    """``value`` (by default ``$LAUNCHKIT_STANDINS``) checked: one of :data:`STANDIN_POLICIES`."""
    if value is None:
        value = os.environ.get(STANDINS, "") or "auto"
    if value not in STANDIN_POLICIES:
        raise LaunchArgumentError(
            f"{STANDINS} is {value!r}", expected="one of " + ", ".join(STANDIN_POLICIES)
        )
    return value


def _launch_candidates(share: Path, filename: str) -> list[Path]:
    return [share / folder / filename if folder else share / filename for folder in LAUNCH_FOLDERS]


#: The packages :func:`_load_entry_points` found, per ``sys.path`` and the times its folders
#: last changed (an install or uninstall changes its folder's): ``launchkit run`` makes a
#: package index to find the file and another to run it, and reading every installed
#: distribution's entry points costs 30-70 ms each time.
_FOUND: dict[tuple[tuple[str, int], ...], dict[str, PythonPackage]] = {}


def _load_entry_points() -> dict[str, PythonPackage]:
    key = tuple((entry, _changed(entry)) for entry in sys.path)
    if key not in _FOUND:
        _FOUND.clear()
        _FOUND[key] = _read_entry_points()
    return dict(_FOUND[key])


def _changed(folder: str) -> int:
    try:
        return os.stat(folder or ".").st_mtime_ns
    except OSError:
        return 0


def _read_entry_points() -> dict[str, PythonPackage]:
    # imported here, not with the module: every process on launchkit's rclpy loads this module
    # (its import hook looks for interface packages on AMENT_PREFIX_PATH), and most never read
    # an entry point; importing importlib.metadata (and email) is 50 ms of a node's start
    from importlib.metadata import entry_points

    found: dict[str, PythonPackage] = {}
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        if ep.name in found:
            continue  # first registration wins, as on a path
        package = ep.load()
        if isinstance(package, PythonPackage):
            found[ep.name] = package
    return found
