"""rclpy's signal handlers: SIGINT and SIGTERM shut every context down, then the handler that
was there before runs.

So Ctrl-C shuts ROS down *and* raises ``KeyboardInterrupt`` in the main thread (Python's own
SIGINT handler, called after ours), as in rclpy; SIGTERM only shuts down, and a spinning
executor raises ``ExternalShutdownException``. ``init()`` installs them for the default context
and ``shutdown()`` puts the previous handlers back.
"""

from __future__ import annotations

import enum
import signal
import threading
from types import FrameType
from typing import Any

from launchkit.ros.context import interrupt_all


class SignalHandlerOptions(enum.IntEnum):
    """Which signal handlers ``init()`` installs."""

    NO = 0
    SIGINT = 1
    SIGTERM = 2
    ALL = 3

    def __str__(self) -> str:
        return f"SignalHandlerOptions.{self.name}"


_SIGNALS = {
    SignalHandlerOptions.SIGINT: (signal.SIGINT,),
    SignalHandlerOptions.SIGTERM: (signal.SIGTERM,),
    SignalHandlerOptions.ALL: (signal.SIGINT, signal.SIGTERM),
    SignalHandlerOptions.NO: (),
}
_current = SignalHandlerOptions.NO
_previous: dict[int, Any] = {}


def _on_signal(signum: int, frame: FrameType | None) -> None:
    interrupt_all()
    previous = _previous.get(signum)
    if callable(previous):
        previous(signum, frame)  # Python's SIGINT handler raises KeyboardInterrupt here


def install_signal_handlers(options: SignalHandlerOptions = SignalHandlerOptions.ALL) -> None:
    """Install the handlers ``options`` names (in the main thread only; elsewhere Python
    cannot, and nothing is installed)."""
    global _current
    options = SignalHandlerOptions(options)
    if threading.current_thread() is not threading.main_thread():
        return
    uninstall_signal_handlers()
    for signum in _SIGNALS[options]:
        if signal.getsignal(signum) == signal.SIG_IGN:
            continue  # ignored on purpose (a shell's background job): it stays ignored
        _previous[signum] = signal.signal(signum, _on_signal)
    _current = options


def uninstall_signal_handlers() -> None:
    """Put back the handlers that were there before :func:`install_signal_handlers`."""
    global _current
    if threading.current_thread() is not threading.main_thread():
        return
    for signum, previous in list(_previous.items()):
        if signal.getsignal(signum) is _on_signal:
            signal.signal(signum, previous if previous is not None else signal.SIG_DFL)
        del _previous[signum]
    _current = SignalHandlerOptions.NO


def get_current_signal_handlers_options() -> SignalHandlerOptions:
    """Which handlers are installed."""
    return _current
