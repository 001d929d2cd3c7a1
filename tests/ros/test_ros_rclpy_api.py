"""rclpy's API on launchkit.ros, in one process: events, logger services, parameter client,
wait_for_message, serialization, guard conditions, tasks and futures, graph queries, clocks,
and an executor shut down from outside."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

import pytest
from launchkit.ros.msgs.rcl_interfaces.msg import LoggerLevel
from launchkit.ros.msgs.rcl_interfaces.srv import GetLoggerLevels, SetLoggerLevels
from launchkit.ros.msgs.std_msgs.msg import String
from ros_helpers import spin_until

from launchkit.ros import Node
from launchkit.ros.clock import ClockChange, JumpThreshold, ROSClock, Time
from launchkit.ros.context import Context
from launchkit.ros.event_handler import PublisherEventCallbacks, QoSMatchedInfo
from launchkit.ros.executor import ExternalShutdownException
from launchkit.ros.executors import SingleThreadedExecutor
from launchkit.ros.logging import LoggingSeverity, get_logger_level
from launchkit.ros.node_graph import NodeNameNonExistentError
from launchkit.ros.parameter_client import AsyncParameterClient
from launchkit.ros.params import Parameter
from launchkit.ros.serialization import deserialize_message, serialize_message
from launchkit.ros.task import Future
from launchkit.ros.wait_for_message import wait_for_message

PATIENCE = 30.0


def test_a_publishers_matched_event_counts_subscriptions(contexts: Callable[[], Context]) -> None:
    node = Node("matcher", context=contexts())
    heard: list[QoSMatchedInfo] = []
    node.create_publisher(
        String, "matched_topic", 10, event_callbacks=PublisherEventCallbacks(matched=heard.append)
    )
    other = Node("subscriber", context=contexts())
    subscription = other.create_subscription(String, "/matched_topic", lambda m: None, 10)
    spin_until(node, lambda: bool(heard), PATIENCE, "the matched event")
    assert (heard[0].current_count, heard[0].current_count_change, heard[0].total_count) == (
        1,
        1,
        1,
    )
    other.destroy_subscription(subscription)
    spin_until(node, lambda: len(heard) > 1, PATIENCE, "the unmatched event")
    assert (heard[-1].current_count, heard[-1].current_count_change) == (0, -1)


def test_logger_levels_over_the_logger_services(contexts: Callable[[], Context]) -> None:
    node = Node("leveled", context=contexts(), enable_logger_service=True)
    tool = Node("tool", context=contexts())
    setter = tool.create_client(SetLoggerLevels, "/leveled/set_logger_levels")
    getter = tool.create_client(GetLoggerLevels, "/leveled/get_logger_levels")
    assert setter.wait_for_service(PATIENCE) and getter.wait_for_service(PATIENCE)
    future = setter.call_async(
        SetLoggerLevels.Request(levels=[LoggerLevel(name="leveled", level=30)])
    )
    spin_until(node, future.done, PATIENCE, "the set_logger_levels answer")
    assert [r.successful for r in future.result().results] == [True]
    assert get_logger_level("leveled") == LoggingSeverity.WARN
    asked = getter.call_async(GetLoggerLevels.Request(names=["leveled"]))
    spin_until(node, asked.done, PATIENCE, "the get_logger_levels answer")
    assert [(lv.name, lv.level) for lv in asked.result().levels] == [("leveled", 30)]


def test_a_parameter_client_lists_gets_and_sets(contexts: Callable[[], Context]) -> None:
    remote = Node("remote", context=contexts())
    remote.declare_parameter("rate", 10)
    stop = threading.Event()
    spinner = threading.Thread(target=lambda: _spin(remote, stop), daemon=True)
    spinner.start()
    try:
        local = Node("local", context=contexts())
        client = AsyncParameterClient(local, "remote")
        assert client.wait_for_services(PATIENCE)
        names = client.list_parameters()
        spin_until(local, names.done, PATIENCE, "list_parameters")
        assert names.result().result.names == ["use_sim_time", "rate"]
        changed = client.set_parameters([Parameter("rate", value=20)])
        spin_until(local, changed.done, PATIENCE, "set_parameters")
        assert changed.result().results[0].successful
        values = client.get_parameters(["rate"])
        spin_until(local, values.done, PATIENCE, "get_parameters")
        assert values.result().values[0].integer_value == 20
    finally:
        stop.set()
        spinner.join(10)


def test_wait_for_message_needs_no_spinning(contexts: Callable[[], Context]) -> None:
    node = Node("waiter", context=contexts())
    talker = Node("talker", context=contexts())
    publisher = talker.create_publisher(String, "/news", 10)

    def publish_when_matched() -> None:
        publisher.wait_for_subscriptions(1, PATIENCE)
        publisher.publish(String(data="extra"))

    thread = threading.Thread(target=publish_when_matched, daemon=True)
    thread.start()
    ok, msg = wait_for_message(String, node, "/news", time_to_wait=PATIENCE)
    thread.join(10)
    assert ok and msg.data == "extra"
    assert wait_for_message(String, node, "/quiet", time_to_wait=0.2) == (False, None)


def test_serialization_round_trips_with_the_cdr_header() -> None:
    data = serialize_message(String(data="hi"))
    assert data[:4] == b"\x00\x01\x00\x00" and deserialize_message(data, String).data == "hi"


def test_a_guard_condition_runs_its_callback_once_per_trigger(
    contexts: Callable[[], Context],
) -> None:
    node = Node("guarded", context=contexts())
    calls: list[int] = []
    guard = node.create_guard_condition(lambda: calls.append(1))
    guard.trigger()
    guard.trigger()  # before it was taken: one call, as rclpy
    spin_until(node, lambda: bool(calls), PATIENCE, "the guard condition's callback")
    executor = SingleThreadedExecutor(context=node.context)
    executor.add_node(node)
    executor.spin_once(timeout_sec=0.1)
    assert calls == [1]


def test_a_coroutine_task_resumes_when_the_future_it_awaits_completes(
    contexts: Callable[[], Context],
) -> None:
    executor = SingleThreadedExecutor(context=contexts())
    waited: Future = Future()
    steps: list[str] = []

    async def work() -> str:
        steps.append("started")
        value = await waited
        steps.append(f"got {value}")
        return "finished"

    task = executor.create_task(work)
    executor.spin_once(timeout_sec=0.1)
    assert steps == ["started"] and not task.done()
    threading.Timer(0.05, lambda: waited.set_result(7)).start()
    executor.spin_until_future_complete(task, timeout_sec=PATIENCE)
    assert steps == ["started", "got 7"] and task.result() == "finished"


def test_futures_as_rclpy_has_them() -> None:
    future: Future = Future()
    seen: list[Any] = []
    future.add_done_callback(lambda f: seen.append(f.cancelled()))
    future.cancel()
    assert future.cancelled() and not future.done() and seen == [True]
    failed: Future = Future()
    failed.set_exception(ValueError("bad"))
    assert failed.done()
    with pytest.raises(ValueError, match="bad"):
        failed.result()


def test_graph_queries_by_node_and_by_topic(contexts: Callable[[], Context]) -> None:
    node = Node("asker", context=contexts())
    other = Node("server_node", namespace="ns", context=contexts())
    other.create_publisher(String, "out", 10)

    def found() -> bool:
        return bool(node.get_publishers_info_by_topic("/ns/out"))

    spin_until(node, found, PATIENCE, "the publisher in the graph")
    (info,) = node.get_publishers_info_by_topic("/ns/out")
    assert (info.node_name, info.node_namespace, info.topic_type) == (
        "server_node",
        "/ns",
        "std_msgs/msg/String",
    )
    services = dict(node.get_service_names_and_types_by_node("server_node", "/ns"))
    assert services["/ns/server_node/get_parameters"] == ["rcl_interfaces/srv/GetParameters"]
    with pytest.raises(NodeNameNonExistentError):
        node.get_publisher_names_and_types_by_node("nobody", "/")


def test_a_ros_clock_jumps_when_ros_time_is_switched_on() -> None:
    clock = ROSClock()
    jumps: list[ClockChange] = []
    threshold = JumpThreshold(min_forward=None, min_backward=None, on_clock_change=True)
    handle = clock.create_jump_callback(
        threshold, post_callback=lambda j: jumps.append(j.clock_change)
    )
    clock._set_ros_time_is_active(True)
    clock.set_ros_time_override(Time(seconds=5))
    assert clock.now() == Time(seconds=5, clock_type=clock.clock_type)
    clock._set_ros_time_is_active(False)
    handle.unregister()
    assert jumps == [ClockChange.ROS_TIME_ACTIVATED, ClockChange.ROS_TIME_DEACTIVATED]


def test_an_executor_raises_when_its_context_is_shut_down_from_outside(
    contexts: Callable[[], Context],
) -> None:
    context = contexts()
    node = Node("spinner", context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    threading.Timer(0.2, context.shutdown).start()
    started = time.monotonic()
    with pytest.raises(ExternalShutdownException):
        executor.spin()
    assert time.monotonic() - started < PATIENCE


def _spin(node: Node, stop: threading.Event) -> None:
    from launchkit.ros import spin_once

    while not stop.is_set():
        spin_once(node, timeout_sec=0.05)
