"""Two node processes talk through a router; remapping and namespaces apply across processes."""

from __future__ import annotations

from ros_helpers import NODES_DIR, Child


def test_talker_and_listener_processes_talk(router: str, children: list[Child]) -> None:
    listener = Child([str(NODES_DIR / "listener.py")])
    children.append(listener)
    talker = Child([str(NODES_DIR / "talker.py")])
    children.append(talker)
    line = listener.expect("heard: hello", timeout=15)
    assert line.startswith("heard: hello ")
    assert talker.stop() == 0
    assert listener.stop() == 0


def test_remapped_topic_across_processes(router: str, children: list[Child]) -> None:
    listener = Child(
        [str(NODES_DIR / "listener.py"), "--ros-args", "-r", "__ns:=/robot", "-r", "chatter:=/news"]
    )
    children.append(listener)
    talker = Child([str(NODES_DIR / "talker.py"), "--ros-args", "-r", "chatter:=news"])
    children.append(talker)
    assert listener.expect("heard: hello", timeout=15)


def test_node_exits_promptly_on_sigint(router: str, children: list[Child]) -> None:
    talker = Child([str(NODES_DIR / "talker.py")])
    children.append(talker)
    talker.expect("talker ready", timeout=15)
    # a generous bound (a busy machine): what is checked is that SIGINT ends spin() and the node
    # shuts down cleanly (status 0, not a SIGKILL's); how fast is bench/stop_latency.py's job
    assert talker.stop(timeout=20) == 0, talker.stderr[-2000:]
    assert any("talker done" in line for line in talker.out.drain())
