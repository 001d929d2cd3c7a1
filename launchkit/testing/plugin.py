"""The pytest plugin (entry point ``pytest11: launchkit``): the ``launch`` and
``launch_module`` fixtures, per-process output in failing reports, and backstops that stop
every launch when the session ends or is interrupted."""

from __future__ import annotations

import atexit
import os
from collections.abc import Generator, Iterator, Mapping
from pathlib import Path

import pytest

from launchkit.testing._deadline import TIMEOUT_SCALE_ENV, timeout_scale
from launchkit.testing._errors import LaunchTestError
from launchkit.testing._handle import DEFAULT_READY_TIMEOUT, LIVE, LaunchHandle, format_items

# the launches a pytest session started (a pytester run inside a test is a session of its own)
_LAUNCHES = pytest.StashKey[set[LaunchHandle]]()


class LaunchFactory:
    """What the ``launch`` fixtures give a test: call it to start a launch.

    ``launch("robot_wheel", "hello.launch.xml", args={"count": 2})`` (a package and a file),
    or ``launch("launch/talker.launch.xml")`` (a path: absolute, relative to the test file's
    folder, or relative to the current directory). Returns a ready :class:`LaunchHandle`.
    """

    def __init__(self, request: pytest.FixtureRequest, tmp: pytest.TempPathFactory) -> None:
        self._tmp = tmp
        self._session_launches = request.config.stash.setdefault(_LAUNCHES, set())
        self._here = Path(request.path).parent
        self.handles: list[LaunchHandle] = []

    def __call__(
        self,
        target: str | os.PathLike[str],
        file: str | None = None,
        *,
        args: Mapping[str, object] | None = None,
        env: Mapping[str, str] | None = None,
        cwd: str | os.PathLike[str] | None = None,
        ready_timeout: float = DEFAULT_READY_TIMEOUT,
    ) -> LaunchHandle:
        """Start the launch in the background and return once it is ready (it raises
        :class:`launchkit.testing.LaunchFailed` with launchkit's message if it fails first)."""
        __tracebackhide__ = True
        name = self._resolve(target) if file is None else str(target)
        title = Path(name).name if file is None else f"{name} {file}"
        handle = LaunchHandle(
            format_items(name, file, args),
            log_dir=self._tmp.mktemp("launch", numbered=True),
            title=title,
            env=env,
            cwd=cwd,
        )
        self.handles.append(handle)
        self._session_launches.add(handle)
        handle.wait_ready(ready_timeout)
        return handle

    def _resolve(self, target: str | os.PathLike[str]) -> str:
        path = Path(target)
        if path.is_absolute():
            return str(path)
        for base in (self._here, Path.cwd()):
            if (base / path).is_file():
                return str((base / path).resolve())
        return str(target)  # a file name launchkit looks up in the packages

    def stop_all(self) -> None:
        """Stop every launch this factory started (newest first); raise the first failure
        after all are stopped."""
        __tracebackhide__ = True
        failures: list[LaunchTestError] = []
        for handle in reversed(self.handles):
            try:
                handle.stop()
            except LaunchTestError as failure:
                failures.append(failure)
        if failures:
            raise failures[0]


@pytest.fixture
def launch(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[LaunchFactory]:
    """Start launches for one test; they are stopped, and checked for survivors, after it."""
    factory = LaunchFactory(request, tmp_path_factory)
    yield factory
    factory.stop_all()


@pytest.fixture(scope="module")
def launch_module(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[LaunchFactory]:
    """Like ``launch``, for launches shared by every test of a module (expensive ones)."""
    factory = LaunchFactory(request, tmp_path_factory)
    yield factory
    factory.stop_all()


def pytest_configure(config: pytest.Config) -> None:
    """Check ``LAUNCHKIT_TIMEOUT_SCALE`` once, up front."""
    try:
        timeout_scale()
    except ValueError as error:
        raise pytest.UsageError(str(error)) from None
    config.addinivalue_line(
        "markers", f"launchkit: process tests (deadlines scale with {TIMEOUT_SCALE_ENV})"
    )


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(
    item: pytest.Item, call: pytest.CallInfo[None]
) -> Generator[None, pytest.TestReport, pytest.TestReport]:
    """Attach each process's output to the report of a failing test."""
    report: pytest.TestReport = yield
    if report.failed:
        funcargs = getattr(item, "funcargs", {})
        for value in funcargs.values():
            if isinstance(value, LaunchFactory):
                for handle in value.handles:
                    for title, text in handle.report_sections():
                        report.sections.append((f"launchkit {title}", text))
    return report


def _stop_everything(config: pytest.Config) -> None:
    launches: set[LaunchHandle] = config.stash.get(_LAUNCHES, set())
    for handle in list(launches):
        try:
            handle.stop()
        except LaunchTestError:
            pass


def pytest_sessionfinish(session: pytest.Session) -> None:
    """Backstop: stop any launch of this session still running at its end."""
    _stop_everything(session.config)


def pytest_keyboard_interrupt(excinfo: pytest.ExceptionInfo[BaseException]) -> None:
    """Backstop: stop every launch on Ctrl-C."""
    for handle in list(LIVE):
        try:
            handle.stop()
        except LaunchTestError:
            pass


@atexit.register
def _kill_everything() -> None:
    for handle in list(LIVE):
        handle.kill()
