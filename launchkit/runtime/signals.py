"""Signals to the launcher, delivered to the supervisor's loop as data on a pipe.

``signal.set_wakeup_fd`` writes each signal's number to a pipe that the loop's selector watches,
so a signal is handled on the loop, in order with the children's output and exits, never in the
middle of something else. The Python-level handlers do nothing, except while the launcher
evaluates launch file actions (:meth:`SignalPipe.interrupting`): evaluation can block for as long
as a ``$(command)`` runs, so there a signal raises :class:`Interrupted` to abandon it; the
signal's number is in the pipe all the same, and the loop handles it as usual afterwards.
"""

from __future__ import annotations

import os
import signal
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager, contextmanager

#: What the launcher handles: each starts an orderly shutdown, a second one escalates.
HANDLED_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


class Interrupted(KeyboardInterrupt):
    """A handled signal arrived while the launcher was evaluating: what it evaluated is
    abandoned (a ``$(command)`` it waited for is killed, with its process group).

    A ``KeyboardInterrupt``, so that no ``except Exception`` on the way swallows it."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def exit_status(signum: int) -> int:
    """The launcher's exit status after a shutdown that ``signum`` started: 0 for SIGINT (as
    ``ros2 launch`` after Ctrl-C), else 128 + the signal's number, as a shell reports a
    program that a signal ended (``ros2 launch`` dies of SIGTERM and SIGHUP: 143 and 129)."""
    return 0 if signum == signal.SIGINT else 128 + signum


@contextmanager
def raising() -> Iterator[None]:
    """Within the body, each of :data:`HANDLED_SIGNALS` raises :class:`Interrupted` (for work
    without a supervisor loop, such as ``--print``: a ``$(command)`` it runs is then killed
    rather than orphaned by SIGTERM's default action), except inside :func:`held`, where it
    is raised at that body's end. Main thread only."""
    previous = {signum: signal.signal(signum, _raise) for signum in HANDLED_SIGNALS}
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


class SignalHold:
    """A body that a signal must not cut in half (a ``$(command)`` or a process being started,
    a shutdown being sent): a handler that is told of a signal arriving in it keeps the first
    one, and :meth:`body` raises :class:`Interrupted` for it at the body's end."""

    def __init__(self) -> None:
        self.active = False
        self.signum: int | None = None

    def keep(self, signum: int) -> bool:
        """Whether ``signum`` is kept for the end of the body (one is in force)."""
        if self.active:
            self.signum = self.signum or signum
        return self.active

    @contextmanager
    def body(
        self, armed: Callable[[], bool] = lambda: True, disarm: Callable[[], None] = lambda: None
    ) -> Iterator[None]:
        """Hold signals in the body (when ``armed()``; nested bodies hold for the outermost),
        then raise the first one if still ``armed()``, after ``disarm()``."""
        if self.active or not armed():
            yield
            return
        self.active = True
        try:
            yield
        finally:
            self.active = False
            signum, self.signum = self.signum, None
        if signum is not None and armed():
            disarm()
            raise Interrupted(signum)


_HOLD = SignalHold()
#: Within :func:`raising`: hold signals in the body (see :class:`SignalHold`).
held = _HOLD.body


def _raise(signum: int, frame: object) -> None:
    if not _HOLD.keep(signum):
        raise Interrupted(signum)


class SignalPipe:
    """The wakeup pipe and the handlers installed while a launch runs."""

    def __init__(self) -> None:
        self._read_fd, self._write_fd = os.pipe()
        self._previous: dict[int, signal._HANDLER] = {}
        self._raising = False
        self._hold = SignalHold()

    @property
    def fd(self) -> int:
        """The end the loop watches for readability."""
        return self._read_fd

    def install(self) -> None:
        """Route :data:`HANDLED_SIGNALS` to the pipe (main thread only)."""
        os.set_blocking(self._read_fd, False)
        os.set_blocking(self._write_fd, False)
        signal.set_wakeup_fd(self._write_fd, warn_on_full_buffer=False)
        for signum in HANDLED_SIGNALS:
            self._previous[signum] = signal.signal(signum, self._handle)

    @contextmanager
    def interrupting(self) -> Iterator[None]:
        """Within the body, a handled signal raises :class:`Interrupted` (once: the cleanup
        that follows is not interrupted again; later signals only reach the pipe)."""
        self._raising = True
        try:
            yield
        finally:
            self._raising = False

    def deferred(self) -> AbstractContextManager[None]:
        """Within :meth:`interrupting`, a body that must not be cut in half (a process being
        started, a shutdown being sent): a signal arriving in it raises at its end instead
        (once, as in :meth:`interrupting`)."""
        return self._hold.body(lambda: self._raising, self._stop_raising)

    def _stop_raising(self) -> None:
        self._raising = False

    def pending(self) -> list[int]:
        """The signals received since the last call, in order."""
        try:
            return list(os.read(self._read_fd, 512))
        except BlockingIOError:
            return []

    def close(self) -> None:
        """Put the previous handlers back (if :meth:`install` ran), then close the pipe."""
        if self._previous:
            for signum, handler in self._previous.items():
                signal.signal(signum, handler)
            self._previous.clear()
            signal.set_wakeup_fd(-1)
        os.close(self._read_fd)
        os.close(self._write_fd)

    def _handle(self, signum: int, frame: object) -> None:
        """Python-level handler: the wakeup fd carries the signal to the loop; while
        evaluating, also abandon the evaluation."""
        if not self._raising or self._hold.keep(signum):
            return
        self._raising = False
        raise Interrupted(signum)


def first_signal_message(signum: int) -> str:
    """What the launcher says when a signal first asks it to stop (ROS's words for Ctrl-C)."""
    if signum == signal.SIGINT:
        return "user interrupted with ctrl-c (SIGINT)"
    return f"received {signal.Signals(signum).name}"
