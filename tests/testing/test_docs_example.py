"""The complete example of docs/testing.md (keep the two the same)."""

import re

import pytest


def test_the_talker_greets_then_the_launch_ends(launch):
    handle = launch(
        "robot_wheel",
        "hello.launch.xml",
        args={"greeting": "Salut", "count": 2, "verbose": True},
    )
    talker = handle.process("talker")
    talker.wait_output("Salut number 1", timeout=5)
    talker.wait_output(re.compile(r"number [0-9]+$"), timeout=5)

    chatty = handle.process("chatty")
    assert chatty.wait_exit(timeout=5) == 0
    assert chatty.output == ["Salut, again from a scoped group"]

    # the talker has on_exit="shutdown": when it is done, the whole launch stops
    assert talker.wait_exit(timeout=5) == 0
    result = handle.stop()
    result.assert_exit_codes({"talker": 0, "chatty": 0})


@pytest.fixture(scope="module")
def quiet_hello(launch_module):
    """One launch shared by the tests of this module (for expensive launches)."""
    return launch_module("robot_wheel", "hello.launch.xml", args={"count": 1})


def test_a_shared_launch_is_the_same_in_every_test(quiet_hello):
    assert quiet_hello.process("talker").wait_output("Hello number 1", timeout=5)


def test_a_shared_launch_keeps_its_output(quiet_hello):
    assert quiet_hello.process("talker").wait_exit(timeout=5) == 0
    assert quiet_hello.process("talker").output == ["Hello number 1"]


def test_the_docs_show_this_file():
    """docs/testing.md's complete example is this file, from ``import re`` to the line above
    this test."""
    from tests.support import assert_docs_show

    assert_docs_show(__file__, "import re", "testing.md")
