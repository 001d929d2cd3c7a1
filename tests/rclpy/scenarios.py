"""The scenarios of the rclpy tests: which node files run together, how they are stopped, and
what of their output is compared (one function each, returning that output)."""

from __future__ import annotations

import signal

from rclpy_runs import Runs


def talker_listener(runs: Runs) -> str:
    """A listener hears five messages of a talker (which waits for it), then exits; the
    talker is stopped with Ctrl-C."""
    return _ends_then_stops(runs, ("listener", "listener.py"), ("talker", "talker.py"))


def service_and_client(runs: Runs) -> str:
    """A client calls a service with call_async and spin_until_future_complete, then from a
    coroutine callback that awaits the call; the server is stopped with Ctrl-C."""
    return _ends_then_stops(runs, ("caller", "caller.py"), ("server", "adder.py"))


def _ends_then_stops(runs: Runs, ends: tuple[str, str], stopped: tuple[str, str]) -> str:
    """Run ``stopped`` and ``ends``; once ``ends`` has ended by itself, Ctrl-C ``stopped``."""
    lasting = runs.start(stopped[1])
    ending = runs.start(ends[1])
    ended = ending.finish()
    return _both((ends[0], ended), (stopped[0], lasting.finish(signal.SIGINT)))


def callback_groups(runs: Runs) -> str:
    """A MultiThreadedExecutor honours a mutually exclusive and a reentrant group (what it
    prints; rclpy's stderr may also complain of callbacks left when the node is destroyed)."""
    status, out, _ = runs.start("groups.py").finish()
    return f"status {status}\n{out}"


def parameters(runs: Runs) -> str:
    """Descriptors, callbacks, the errors, and the /parameter_events they publish."""
    return _both(("parameters", runs.start("parameters.py").finish()))


def rosout(runs: Runs) -> str:
    """A node's log lines reach /rosout and another node."""
    return _both(("rosout", runs.start("rosout.py").finish()))


def stopped(runs: Runs, stop: int) -> str:
    """A spinning node stopped with ``stop`` (SIGINT: Ctrl-C; SIGTERM: a shutdown from
    outside)."""
    node = runs.start("stoppable.py")
    node.expect("spinning")
    node.wait_until_idle()
    return _both(("stoppable", node.finish(stop)))


def uncaught_ctrl_c(runs: Runs) -> str:
    """Ctrl-C of a node that catches nothing: the status and the last line of its traceback
    (the frames in between are each rclpy's own)."""
    node = runs.start("uncaught.py")
    node.expect("spinning")
    node.wait_until_idle()
    status, out, err = node.finish(signal.SIGINT)
    lines = err.splitlines()
    return f"status {status}\n{out}first: {lines[0]}\nlast: {lines[-1]}\n"


def actions(runs: Runs) -> str:
    """A client sends goals to an action server: feedback and result, a rejected goal, a
    canceled one, an aborted one; the server is stopped with Ctrl-C."""
    server = runs.start("fibonacci_server.py")
    server.expect("serving")
    ended = runs.start("fibonacci_client.py").finish()
    return _both(("client", ended), ("server", server.finish(signal.SIGINT)))


def two_action_clients(runs: Runs) -> str:
    """Two clients send goals to one server at once; each follows its own goal (the server's
    lines interleave, so only its status is compared)."""
    server = runs.start("fibonacci_server.py")
    server.expect("serving")
    racers = [runs.start("fibonacci_racer.py", order) for order in ("6", "9")]
    ended = [racer.finish() for racer in racers]
    status, _, _ = server.finish(signal.SIGINT)
    return _both(("racer 6", ended[0]), ("racer 9", ended[1])) + f"server status {status}\n"


def _both(*runs: tuple[str, tuple[int, str, str]]) -> str:
    return "".join(
        f"== {name} (status {status})\n{out}-- stderr\n{err}" for name, (status, out, err) in runs
    )
