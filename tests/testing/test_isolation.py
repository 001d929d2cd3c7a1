"""Launches never share a router or a ROS domain, in one test or across xdist workers."""

from __future__ import annotations

import pytest

from launchkit.testing._deadline import TIMEOUT_SCALE_ENV, Deadline, scaled, timeout_scale


def _printed(handle, variable: str) -> str:
    line = handle.process("env").wait_output(f"{variable}=", timeout=5)
    return line.split("=", 1)[1]


def test_two_launches_in_parallel_stay_separate(launch):
    first = launch("launch/isolation.launch.xml")
    second = launch("launch/isolation.launch.xml")

    assert _printed(first, "LAUNCHKIT_ROUTER") == first.router
    assert _printed(second, "LAUNCHKIT_ROUTER") == second.router
    assert first.router != second.router
    assert first.router.startswith("tcp/127.0.0.1:")
    assert _printed(first, "ROS_DOMAIN_ID") == str(first.domain_id)
    assert _printed(second, "ROS_DOMAIN_ID") == str(second.domain_id)
    assert first.domain_id != second.domain_id
    assert first.process("env").pid != second.process("env").pid
    assert first.output.keys() == second.output.keys() == {"env-1"}
    assert first.ros_env == {
        "LAUNCHKIT_ROUTER": first.router,
        "ROS_DOMAIN_ID": str(first.domain_id),
    }


# a few runs in the suite; stress_waits.py repeats a launch hundreds of times, by hand
@pytest.mark.parametrize("run", range(3))
def test_the_same_launch_passes_every_time(launch, run):
    handle = launch("launch/talker.launch.xml", args={"count": 1})
    handle.process("talker").wait_output("talker waiting", timeout=10)
    handle.process("python3").wait_output("listener waiting", timeout=10)
    handle.stop().assert_exit_codes({"*": 0})


def test_the_timeout_scale_multiplies_every_deadline(monkeypatch):
    monkeypatch.setenv(TIMEOUT_SCALE_ENV, "2.5")
    assert timeout_scale() == 2.5
    assert scaled(4) == 10.0
    assert Deadline(4).seconds == 10.0
    monkeypatch.setenv(TIMEOUT_SCALE_ENV, "fast")
    with pytest.raises(ValueError, match="expected a positive number"):
        timeout_scale()
    monkeypatch.delenv(TIMEOUT_SCALE_ENV)
    assert scaled(4) == 4.0


def test_a_domain_a_dds_participant_uses_is_passed_over(monkeypatch):
    # another test run's real DDS nodes hold a domain's RTPS ports (7400 + 250·d and after):
    # hold every domain's but one, as such nodes would; the next launch must get that one
    import socket

    from launchkit.testing._isolation import domain_id

    # the suite gives each worker a private domain of its own: it may be the free one
    monkeypatch.setenv("ROS_DOMAIN_ID", "0")

    held = []
    try:
        for domain in range(1, 102):
            if domain == 57:
                continue
            udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            try:
                udp.bind(("127.0.0.1", 7400 + 250 * domain + 7))
            except OSError:
                udp.close()  # bound already by someone: busy all the same
                continue
            held.append(udp)
        assert domain_id() == 57
    finally:
        for udp in held:
            udp.close()


def test_the_domain_the_shell_names_is_never_chosen(monkeypatch):
    # a ROS user's shell exports the domain their own robot runs on: a test's launch must not
    # join it, whichever domain the counter and the worker would have picked
    from launchkit.testing._isolation import domain_id

    monkeypatch.setenv("ROS_DOMAIN_ID", "7")
    chosen = {domain_id() for _ in range(202)}
    assert chosen and 7 not in chosen


def test_free_ports_are_picked_where_outgoing_connections_never_take_theirs():
    # binding port 0 picks from the kernel's ephemeral range, which outgoing connections also
    # take their local ports from: a connection took a viewer's port before rviz2 bound it
    from launchkit.testing._isolation import first_ephemeral_port, free_loopback_port

    low = first_ephemeral_port()
    if low < 22000:
        pytest.skip(f"this machine's ephemeral ports start at {low}: no room below them")
    ports = {free_loopback_port() for _ in range(20)}
    assert all(20000 <= port < low for port in ports), ports
    assert len(ports) > 1  # picked at random, not a fixed sequence every worker repeats


def test_consecutive_launches_get_different_domains():
    from launchkit.testing._isolation import domain_id

    first, second = domain_id(), domain_id()
    assert first != second
