"""The suite's environment (see tests/suite_env.py) and shared fixtures: evaluate inline launch
XML without starting anything."""

from __future__ import annotations

import os
import shutil
import signal
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from launchkit.checks import check_tree
from launchkit.description.launch_context import LaunchContext
from launchkit.description.process_spec import ProcessSpec
from launchkit.envvars import ROUTER
from launchkit.frontend.launch_loader import LaunchLoader
from launchkit.packages import PackageIndex
from launchkit.runtime.recorder import Recorded, Recorder
from tests import suite_env
from tests.support import hosted_router

pytest_plugins = ["tests.cpu_report"]

# The suite's environment (tests/suite_env.py): set before pytest starts its xdist workers,
# which inherit it; the private defaults again for each process (each worker its own: what its
# module fixtures start and what its tests start must meet at the same router and domain).
_RUN_DIR, _OWN_RUN_DIR = suite_env.run_dir()
_SUITE_ENVIRONMENT = suite_env.suite_environment(os.environ, _RUN_DIR)
os.environ.clear()
os.environ.update(_SUITE_ENVIRONMENT)
os.environ.update(suite_env.private_defaults())


@dataclass
class Evaluated:
    """What a launch file would do, as recorded without running it."""

    items: list[Recorded]
    context: LaunchContext
    logs: list[str] = field(default_factory=list)
    processes: list[ProcessSpec] = field(default_factory=list)

    def process(self, name: str) -> ProcessSpec:
        """The one recorded process called ``name``."""
        found = [p for p in self.processes if p.name == name]
        assert len(found) == 1, (
            f"expected one process {name!r}, got {[p.name for p in self.processes]}"
        )
        return found[0]

    def messages(self) -> list[str]:
        """The user log messages, without their level and logger."""
        return [line.split("]: ", 1)[1] for line in self.logs]


def _flatten(items: list[Recorded], into: Evaluated) -> None:
    for item in items:
        if item.kind == "log":
            into.logs.append(item.text)
        elif item.kind == "process" and item.spec is not None:
            into.processes.append(item.spec)
        _flatten(item.inner, into)


EvaluateXml = Callable[..., Evaluated]


def pytest_configure(config: pytest.Config) -> None:
    """Give the processes the tests start the usual Ctrl-C: a suite started as a background job
    of a non-interactive shell (``python -m pytest ... &``) inherits SIGINT ignored, and so would
    every command a test stops with SIGINT (a Python program then never sees KeyboardInterrupt)."""
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The tests marked ``long`` first, in their order: xdist hands out tests in collection
    order, and a minute-long test handed out last keeps one worker busy while the other idles
    (the tutorial's test ran last and stretched the suite's end by its whole length)."""
    items.sort(key=lambda item: item.get_closest_marker("long") is None)


def pytest_unconfigure(config: pytest.Config) -> None:
    """Remove the run's folder (see above), once its last process is done with it."""
    if _OWN_RUN_DIR:
        shutil.rmtree(_RUN_DIR, ignore_errors=True)


@pytest.fixture(autouse=True)
def _own_log_folder(
    monkeypatch: pytest.MonkeyPatch, tmp_path_factory: pytest.TempPathFactory
) -> None:
    """Each test its own log folder, so ``latest`` is its own run (unless a fixture of a wider
    scope gave its tests one to share)."""
    if os.environ.get("ROS_LOG_DIR") == _SUITE_ENVIRONMENT["ROS_LOG_DIR"]:
        monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path_factory.mktemp("ros_log")))


@pytest.fixture
def router(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """A router hosted by the test process on a free loopback port; the processes the test
    starts are told of it (``LAUNCHKIT_ROUTER``)."""
    with hosted_router() as endpoint:
        monkeypatch.setenv(ROUTER, endpoint)
        yield endpoint


@pytest.fixture
def evaluate_xml(tmp_path: Path) -> EvaluateXml:
    """Write launch XML to a file in ``tmp_path``, check it and evaluate it with a recorder.

    Timers fire at once in their captured scope (that is what the recorder does), so their
    actions show up in the result too.
    """
    contexts: list[LaunchContext] = []

    def evaluate(
        xml: str,
        args: Mapping[str, str] | None = None,
        *,
        name: str = "test.launch.xml",
        env: Mapping[str, str] | None = None,
        packages: PackageIndex | None = None,
    ) -> Evaluated:
        path = tmp_path / name
        path.write_text(xml)
        loader = LaunchLoader()
        index = packages or PackageIndex()
        tree = check_tree(path, args or {}, loader, index)
        recorder = Recorder()
        context = LaunchContext(
            packages=index,
            runner=recorder,
            loader=loader.load,
            environment=dict(env if env is not None else {"PATH": "/usr/bin:/bin"}),
            log_dir=lambda: tmp_path / "log",
            configurations=dict(args or {}),
        )
        recorder.context = context
        contexts.append(context)
        with context.in_file(tree.top.path):
            for action in tree.top.actions:
                action.visit(context)
        result = Evaluated(recorder.items, context)
        _flatten(recorder.items, result)
        return result

    yield evaluate  # type: ignore[misc]
    for context in contexts:
        context.cleanup()
