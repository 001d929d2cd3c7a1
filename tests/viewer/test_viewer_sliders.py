"""display.launch.xml in a real browser: joint_state_publisher_gui's sliders are in the page,
and the page reconnects by itself when the launch is stopped and started again.

display.launch.xml has no simulator: nothing publishes the config's fixed frame ``odom``, so the
page shows the robot in its root frame ``base`` and says so, as rviz2 would complain of it.
"""

from __future__ import annotations

from typing import Any


def left_wheel(message: Any) -> float:
    """wheel_left_joint's position in a JointState."""
    return float(dict(zip(message.name, message.position, strict=True))["wheel_left_joint"])


def test_sliders_move_the_joints_and_the_page_survives_a_restart(
    launch: Any, open_viewer: Any
) -> None:
    first = launch("robot_wheel", "display.launch.xml")
    port = first.viewer_port
    first.process("rviz2").wait_output("Foxglove WebSocket on", timeout=60)  # serving
    viewer = open_viewer(f"http://127.0.0.1:{port}/")
    viewer.wait("s.connected && s.robotLinks >= 6", "the robot drawn")
    stats = viewer.stats()
    assert stats["fixedFrame"] == "base", stats
    warning = viewer.page.locator("#frame-warning").inner_text()
    assert "Frame [odom] does not exist: showing in [base]" in warning

    # one slider per moving joint, while joint_state_publisher_gui runs
    viewer.wait("s.sliders === 3", "three joint sliders")
    slider = viewer.page.locator('input[data-joint="wheel_left_joint"]')
    slider.fill("1.5")
    first.expect_topic("/joint_states", within=30, where=lambda m: abs(left_wheel(m) - 1.5) < 0.01)
    viewer.page.get_by_role("button", name="Center").click()
    first.expect_topic("/joint_states", within=30, where=lambda m: abs(left_wheel(m)) < 0.01)

    # the launch goes: the page says so and keeps trying ...
    first.stop().assert_exit_codes({"*": 0})
    viewer.wait("!s.connected", "the page to notice the launch is gone")
    assert viewer.page.locator("#banner").is_visible()
    before = viewer.stats()["tfMessages"]

    # ... and when it is started again the page is back by itself, robot and all
    second = launch("robot_wheel", "display.launch.xml", env={"LAUNCHKIT_VIEWER_PORT": str(port)})
    viewer.wait(
        f"s.connected && s.connections >= 2 && s.tfMessages > {before} && s.robotLinks >= 6",
        "the page back after the restart, the robot drawn from the new launch's transforms",
    )
    assert not viewer.page.locator("#banner").is_visible()
    second.stop().assert_exit_codes({"*": 0})
