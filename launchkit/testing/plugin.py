"""The pytest plugin (entry point ``pytest11: launchkit``): the ``launch`` and
``launch_module`` fixtures, per-process output in failing reports, and backstops that stop
every launch when the session ends or is interrupted."""

from __future__ import annotations

import atexit
from collections.abc import Generator, Iterator
from pathlib import Path

import pytest

from launchkit.testing._deadline import timeout_scale
from launchkit.testing._errors import LaunchTestError
from launchkit.testing._factory import LaunchFactory
from launchkit.testing._handle import LIVE, LaunchHandle

# the launches a pytest session started (a pytester run inside a test is a session of its own)
_LAUNCHES = pytest.StashKey[set[LaunchHandle]]()


def _factory(request: pytest.FixtureRequest, tmp: pytest.TempPathFactory) -> LaunchFactory:
    session = request.session
    return LaunchFactory(
        Path(request.path).parent,
        lambda: tmp.mktemp("launch", numbered=True),
        request.config.stash.setdefault(_LAUNCHES, set()),
        lambda: int(session.testsfailed),
    )


@pytest.fixture
def launch(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[LaunchFactory]:
    """Start launches for one test; they are stopped, and checked for survivors and for deaths
    the test never took note of, after it."""
    factory = _factory(request, tmp_path_factory)
    yield factory
    factory.stop_all()


@pytest.fixture(scope="module")
def launch_module(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[LaunchFactory]:
    """Like ``launch``, for launches shared by every test of a module (expensive ones)."""
    factory = _factory(request, tmp_path_factory)
    yield factory
    factory.stop_all()


def pytest_configure(config: pytest.Config) -> None:
    """Check ``LAUNCHKIT_TIMEOUT_SCALE`` once, up front: a bad value stops the run."""
    try:
        timeout_scale()
    except ValueError as error:
        raise pytest.UsageError(str(error)) from None


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
