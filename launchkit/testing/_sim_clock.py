"""``launch(..., lockstep=True)``: the test holds the launch's simulated clock.

The launch runs with its time paused (``--lockstep-paused``); :class:`SimClock` is a lockstep
participant of the test process: :meth:`SimClock.advance` asks the time authority for more time
and returns once the launch is quiet at the new instant, so what the test published before has
been handled and what it subscribes to has arrived.
"""

from __future__ import annotations

import json
import threading
from collections.abc import Callable
from typing import Any

from launchkit.testing._deadline import Deadline

_NS = 1_000_000_000


class SimClockTimeout(Exception):
    """The launch did not reach the asked simulated time before the wall deadline."""


class SimClock:
    """The test's node on a lockstep launch: time control, publishing, the latest messages."""

    def __init__(self, router: str, domain_id: int) -> None:
        import launchkit.ros as ros
        from launchkit.ros.lockstep.participant import Participant
        from launchkit.ros.lockstep.report import CONTROL_KEY, STATUS_KEY

        self._ros = ros
        self.context = ros.Context(router=router, start_router=False)
        self.context.init([], domain_id)
        self.participant = self.context.lockstep = Participant(self.context, "the test")
        self.node = ros.Node("launchkit_test_clock", context=self.context, enable_rosout=False)
        self._status: dict[str, Any] = {"time_ns": 0, "quiescent": False, "target_ns": 0}
        self._changed = threading.Condition()
        self._control_key = CONTROL_KEY.format(domain=domain_id)
        session = self.context.session
        self._status_sub = session.declare_subscriber(
            STATUS_KEY.format(domain=domain_id), self._on_status
        )
        self._publishers: dict[str, Any] = {}
        self._latest: dict[str, Any] = {}
        self._executor = ros.SingleThreadedExecutor(context=self.context)
        self._executor.add_node(self.node)
        self._thread = threading.Thread(target=self._spin, name="launchkit-sim-clock", daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        while self.context.ok():
            try:
                self._executor.spin_once(timeout_sec=0.1)
            except Exception:  # the context shut down under the spin
                return

    def _on_status(self, sample: Any) -> None:
        with self._changed:
            self._status = json.loads(sample.payload.to_bytes())
            self._changed.notify_all()

    @property
    def sim_time(self) -> float:
        """The launch's simulated time, in seconds."""
        with self._changed:
            return int(self._status["time_ns"]) / _NS

    def advance(self, seconds: float, deadline: Deadline) -> float:
        """Run the simulated time ``seconds`` forward and wait until the launch is quiet there;
        the new time."""
        with self._changed:
            start = max(int(self._status["time_ns"]), int(self._status.get("target_ns") or 0))
        target = start + round(seconds * _NS)
        self.participant.on_idle()  # what the test published is counted before time moves
        self.context.session.put(self._control_key, json.dumps({"run_until_ns": target}))

        def reached() -> bool:
            return bool(self._status["time_ns"] >= target and self._status["quiescent"])

        with self._changed:
            while not reached():
                if deadline.remaining() <= 0:
                    raise SimClockTimeout(
                        f"the simulated time stands at {self._status['time_ns'] / _NS:.3f} s, "
                        f"short of {target / _NS:.3f} s"
                    )
                self._changed.wait(timeout=min(0.2, deadline.remaining()))
                if not reached():
                    # ask again: a control message sent before the clock listened is lost
                    self.context.session.put(
                        self._control_key, json.dumps({"run_until_ns": target})
                    )
        return target / _NS

    def publish(self, topic: str, message: Any) -> None:
        """Publish ``message`` on ``topic`` (its type from the message); handled by the launch's
        nodes before the time next moves."""
        publisher = self._publishers.get(topic)
        if publisher is None:
            publisher = self.node.create_publisher(type(message), topic, 10)
            self._publishers[topic] = publisher
        publisher.publish(message)
        self.participant.on_idle()

    def subscribe(self, topic: str, msg_type: Any) -> None:
        """Keep the latest message on ``topic`` (see :meth:`latest`)."""
        if topic not in self._latest:
            self._latest[topic] = None

            def keep(message: Any) -> None:
                self._latest[topic] = message

            self.node.create_subscription(msg_type, topic, keep, 10)

    def latest(self, topic: str) -> Any:
        """The last message :meth:`subscribe` kept on ``topic`` (None: none yet)."""
        return self._latest.get(topic)

    def wait_until(
        self, condition: Callable[[], bool], within: float, step: float, deadline: Deadline
    ) -> float:
        """Advance by ``step`` until ``condition()`` holds, at most ``within`` simulated
        seconds; the simulated time it held at (``SimClockTimeout`` otherwise)."""
        end = self.sim_time + within
        while not condition():
            if self.sim_time >= end - 1e-9:
                raise SimClockTimeout(f"the condition did not hold within {within:g} s (simulated)")
            self.advance(min(step, end - self.sim_time), deadline)
        return self.sim_time

    def close(self) -> None:
        """Leave the launch's network."""
        self._status_sub.undeclare()  # type: ignore[no-untyped-call]
        self._executor.shutdown(timeout_sec=1.0)
        self.context.try_shutdown()
        self._thread.join(timeout=2.0)
