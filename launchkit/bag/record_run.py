"""Running ``launchkit bag record`` until Ctrl-C: node, writer thread, discovery, clean close."""

from __future__ import annotations

import time
from pathlib import Path

from launchkit.bag.recorder import Recorder, RecorderOptions
from launchkit.bag.signals import POLL, stop_on_signals
from launchkit.bag.storage import BagWriter, WriterOptions
from launchkit.bag.writer_thread import WriterThread
from launchkit.errors import RuntimeLaunchError
from launchkit.ros.context import Context
from launchkit.ros.executor import Executor
from launchkit.ros.executors import SingleThreadedExecutor
from launchkit.ros.logging import get_logger
from launchkit.ros.node import Node
from launchkit.ros.session import router_endpoint
from launchkit.ros.shared_router import ensure_router

#: Consecutive empty looks at the executor after which the last deliveries count as written.
_DRAINED_AFTER = 5


def open_context(router: str | None) -> Context:
    """An initialized ROS context on ``router`` (else ``$LAUNCHKIT_ROUTER``), found as every
    launchkit command finds its router: the shared background router is started when none
    answers on loopback, else the command waits for one, saying so once."""
    endpoint = router_endpoint(router)
    ensure_router(
        endpoint, wait=True, say=lambda level, text: getattr(get_logger("bag"), level)(text)
    )
    context = Context(router=endpoint, start_router=False)
    context.init([])
    return context


def run_record(
    path: Path,
    writer_options: WriterOptions,
    recorder_options: RecorderOptions,
    *,
    max_cache_size: int,
    node_name: str,
    router: str | None,
) -> int:
    """Record until SIGINT/SIGTERM (or a write error); the bag is always closed properly."""
    context = open_context(router)
    try:
        node = Node(node_name, context=context, start_parameter_services=False)
        log = node.get_logger()
        executor = SingleThreadedExecutor(context=context)
        executor.add_node(node)
        bag = BagWriter(path, writer_options)
        failures: list[BaseException] = []

        def on_error(error: BaseException) -> None:
            failures.append(error)
            executor.wake()

        writer = WriterThread(bag, max_cache_size, on_error)
        recorder = Recorder(node, writer, recorder_options)
        log.info(f"Writing to '{path}' ({writer_options.storage})")
        log.info("Listening for topics...")
        with stop_on_signals() as stop:
            next_poll = 0.0
            log.info("Recording...")
            while not stop.is_set() and not failures:
                now = time.monotonic()
                if recorder.discovering and (recorder.discovery_due() or now >= next_poll):
                    recorder.discover()
                    next_poll = now + recorder_options.polling_interval
                wait = max(0.0, next_poll - now) if recorder.discovering else POLL
                executor.spin_once(timeout_sec=min(wait, POLL))
            recorder.stop()
            _drain(recorder, executor)
            summary = writer.close()
        for line in recorder.report():
            log.info(line)
        if failures or summary is None:
            raise RuntimeLaunchError(f"writing the bag '{path}' failed: {failures[0]}")
        log.info(f"Recording stopped: {summary.message_count} messages in '{path}'")
        return 0
    finally:
        context.try_shutdown()


def _drain(recorder: Recorder, executor: Executor) -> None:
    """Run the deliveries still queued after unsubscribing, so they reach the bag.

    The executor has no "queue empty" call; a look that delivers nothing several times in a row
    (a wake-up item delivers nothing once) means every message is handed to the writer.
    """
    quiet = 0
    while quiet < _DRAINED_AFTER:
        before = sum(recorder.received.values())
        executor.spin_once(timeout_sec=0)
        quiet = quiet + 1 if sum(recorder.received.values()) == before else 0
