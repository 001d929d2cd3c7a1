"""What every fuzzed input must come to: success, or launchkit's one located error type
(:class:`launchkit.errors.LaunchkitError`), within a time bound. Anything else (another
exception, a hang) fails the example, and hypothesis shrinks it to a small file."""

from __future__ import annotations

import signal
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from types import FrameType

from launchkit import api
from launchkit.errors import LaunchkitError
from launchkit.ros.params import load_params_file
from launchkit.testing._deadline import scaled

#: The most one example may take (a check of a small file takes milliseconds; the issue's
#: hangs took seconds to forever).
TIME_BOUND = 5.0


class Hung(BaseException):
    """An example ran past the time bound (a BaseException: no ``except Exception`` in
    launchkit may turn it into a user error)."""


@contextmanager
def time_bound(seconds: float) -> Iterator[None]:
    """Raise :class:`Hung` in the body once ``seconds`` (scaled for slow machines) passed, or
    after it where the alarm landed in code that swallows exceptions (a garbage collector
    callback reports it as "unraisable" and carries on)."""
    expired: list[bool] = []

    def expire(_signum: int, _frame: FrameType | None) -> None:
        expired.append(True)
        raise Hung(f"still running after {seconds:g} s")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, scaled(seconds))
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    if expired:
        raise Hung(f"ran past {seconds:g} s (the alarm was swallowed where it fired)")


def must_be_success_or_located_error(action: Callable[[], object]) -> LaunchkitError | None:
    """Run ``action``: None when it succeeds, the error when it raises a LaunchkitError whose
    message is one line naming a file; any other exception, or a hang, propagates."""
    try:
        with time_bound(TIME_BOUND):
            action()
    except LaunchkitError as error:
        first = error.format().splitlines()[0]
        assert error.location is not None, f"an error without a location: {first}"
        assert error.location.file, first
        return error
    return None


def check_file(name: str, data: bytes) -> LaunchkitError | None:
    """``launchkit check`` (in this process) of a file called ``name`` holding ``data``."""
    with tempfile.TemporaryDirectory(prefix="lk-fuzz-") as folder:
        path = Path(folder) / name
        path.write_bytes(data)
        return must_be_success_or_located_error(lambda: api.check_report(path, {}))


def load_params(data: bytes) -> LaunchkitError | None:
    """The params-file loader (what every node runs on ``--params-file``) on ``data``."""
    with tempfile.TemporaryDirectory(prefix="lk-fuzz-") as folder:
        path = Path(folder) / "params.yaml"
        path.write_bytes(data)
        return must_be_success_or_located_error(lambda: load_params_file(path, "/ns/node"))
