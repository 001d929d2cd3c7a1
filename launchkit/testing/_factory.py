"""The factory the ``launch`` fixtures hand to tests: it starts launches and stops them all."""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from pathlib import Path

from launchkit.testing._errors import LaunchTestError
from launchkit.testing._handle import DEFAULT_READY_TIMEOUT, LaunchHandle
from launchkit.testing._waits import AllowExit


class LaunchFactory:
    """What the ``launch`` fixtures give a test: call it to start a launch.

    ``launch("robot_wheel", "hello.launch.xml", args={"count": 2})`` (a package and a file),
    or ``launch("launch/talker.launch.xml")`` (a path: absolute, relative to the test file's
    folder, or relative to the current directory). Returns a ready :class:`LaunchHandle`.
    """

    def __init__(
        self,
        here: Path,
        make_dir: Callable[[], Path],
        registry: set[LaunchHandle],
        failures: Callable[[], int] = lambda: 0,
    ) -> None:
        self._here = here  # the test file's folder
        self._make_dir = make_dir  # a new folder for each launch's logs
        self._registry = registry  # the session's running launches (for its backstop)
        self._failures = failures  # how many tests of the session have failed so far
        self._failures_before = failures()
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
        allow_exit: AllowExit | None = None,
        lockstep: bool = False,
    ) -> LaunchHandle:
        """Start the launch in the background and return once it is ready (it raises
        :class:`launchkit.testing.LaunchFailed` with launchkit's message if it fails first).

        ``allow_exit`` declares exits the test expects and will not check: process names
        (any exit code) or ``{name: code or codes}``; ``"*"`` names every process. Any other
        unexpected death the test never takes note of fails it at teardown.

        ``lockstep=True`` runs the launch on a simulated clock that stands still until the
        test moves it (``handle.advance(seconds)``; see ``docs/testing.md``).
        """
        __tracebackhide__ = True
        name = self._resolve(target) if file is None else str(target)
        title = Path(name).name if file is None else f"{name} {file}"
        handle = LaunchHandle(
            format_items(name, file, args),
            log_dir=self._make_dir(),
            title=title,
            env=env,
            cwd=cwd,
            allow_exit=allow_exit,
            lockstep=lockstep,
        )
        self.handles.append(handle)
        self._registry.add(handle)
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
        """Stop every launch this factory started (newest first), then check that the test
        took note of every unexpected death; raise the first failure after all are stopped.

        Deaths are not held against a test that has already failed (its report shows every
        process's status).
        """
        __tracebackhide__ = True
        failures: list[LaunchTestError] = []
        for handle in reversed(self.handles):
            try:
                handle.stop()
            except LaunchTestError as failure:
                failures.append(failure)
            finally:
                self._registry.discard(handle)
        if not failures and self._failures() == self._failures_before:
            for handle in self.handles:
                try:
                    handle.check_exits_noted()
                except LaunchTestError as failure:
                    failures.append(failure)
        if failures:
            raise failures[0]


def format_items(target: str, file: str | None, args: Mapping[str, object] | None) -> list[str]:
    """``launchkit run`` positional items: ``[PKG] FILE name:=value ...``."""
    items = [target] if file is None else [target, file]
    for name, value in (args or {}).items():
        text = ("true" if value else "false") if isinstance(value, bool) else str(value)
        items.append(f"{name}:={text}")
    return items
