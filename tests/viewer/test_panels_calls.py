"""The service caller and the topic publisher panels in a real browser: a call built in the
form returns the service's response, shown; a message built in the form reaches a subscriber,
once or at a rate until stopped."""

from __future__ import annotations

import json
from typing import Any

from tests.viewer.conftest import keep_screenshot, open_panel


def test_a_service_call_from_the_form_shows_the_response(
    panels_launch: Any, open_viewer: Any
) -> None:
    viewer = open_panel(open_viewer, panels_launch.viewer_url, "services")
    viewer.wait(
        "[...document.querySelectorAll('#call-service option')]"
        ".some((o) => o.value === '/tuner/shout')",
        "/tuner/shout listed",
    )
    viewer.page.locator("#call-service").select_option("/tuner/shout")
    viewer.wait("!document.querySelector('#call-button').disabled", "the request form")
    # the form has the request's one field, a bool
    assert viewer.page.locator("#call-form input[data-path]").count() == 1
    viewer.page.locator('#call-form input[data-path="data"]').check()
    viewer.page.locator("#call-button").click()
    viewer.wait("v.tools.services.calls >= 1", "the first response")
    shown = viewer.page.locator("#call-response")
    assert shown.get_attribute("data-state") == "ok"
    assert json.loads(shown.inner_text()) == {"success": True, "message": "shouting: on"}
    keep_screenshot(viewer, "panel-services")
    viewer.page.locator('#call-form input[data-path="data"]').uncheck()
    viewer.page.locator("#call-button").click()
    viewer.wait("v.tools.services.calls >= 2", "the second response")
    assert json.loads(shown.inner_text())["message"] == "shouting: off"
    assert not viewer.problems, viewer.problems


def test_a_message_from_the_form_reaches_a_subscriber(panels_launch: Any, open_viewer: Any) -> None:
    viewer = open_panel(open_viewer, panels_launch.viewer_url, "publisher")
    viewer.page.locator("#pub-topic").fill("/robot1/say")
    type_box = viewer.page.locator("#pub-type")
    type_box.fill("std_msgs/msg/String")
    type_box.press("Enter")
    viewer.wait("!document.querySelector('#pub-once').disabled", "the message form")
    viewer.page.locator('#pub-form input[data-path="data"]').fill("from the form")
    viewer.page.locator("#pub-rate").fill("5")
    viewer.page.locator("#pub-start").click()
    got = panels_launch.expect_topic(
        "/robot1/say", min_messages=3, within=30, where=lambda m: m.data == "from the form"
    )
    assert all(m.data == "from the form" for m in got)
    keep_screenshot(viewer, "panel-publisher")
    # stopped: the list empties and nothing more is sent
    viewer.page.locator('#pub-running li[data-topic="/robot1/say"] button').click()
    sent = viewer.page.evaluate("window.__viewer.tools.publisher.sent")
    viewer.page.wait_for_timeout(600)  # two periods at 5 Hz, to see that none more are sent
    assert viewer.page.evaluate("window.__viewer.tools.publisher.sent") == sent
    assert viewer.page.locator("#pub-running li").count() == 0

    # a topic of the graph brings its type; a field that does not fit its type is named, and
    # nothing is sent
    viewer.page.locator("#pub-topic").fill("/robot1/cmd")
    viewer.page.locator("#pub-topic").press("Enter")
    viewer.wait(
        "document.querySelector('#pub-form input[data-path=\"linear.x\"]') && "
        "!document.querySelector('#pub-once').disabled",
        "the Twist form",
    )
    assert type_box.input_value() == "geometry_msgs/msg/Twist"
    viewer.page.locator("#pub-topic").fill("/robot1/joints")
    type_box.fill("sensor_msgs/msg/JointState")
    type_box.press("Enter")
    viewer.wait(
        "document.querySelector('#pub-form input[data-path=\"position\"]') && "
        "!document.querySelector('#pub-once').disabled",
        "the JointState form",
    )
    viewer.page.locator('#pub-form input[data-path="position"]').fill("[1.0, 2.0")
    viewer.page.locator("#pub-once").click()
    assert "position" in viewer.page.locator("#pub-status").inner_text()
    assert viewer.page.evaluate("window.__viewer.tools.publisher.sent") == sent
    assert not viewer.problems, viewer.problems
