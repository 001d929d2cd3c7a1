"""The viewer page in a real headless Chromium (Debian's ``chromium``, driven by playwright).

``browser`` is one Chromium per test module (module, not session: playwright's sync API keeps
an event loop running in the test's thread while it is open, and ``asyncio.run`` in any later
test of the worker would then fail); ``open_viewer(url)`` opens a
page on it and gives a :class:`Viewer`, whose waits are on the page's own state
(``window.__viewer.stats``) with deadlines that say what was awaited. When a test fails, every
page it opened is photographed into the test's temporary folder and the path is shown in the
report, so the picture stays after the run.

WebGL works in headless Chromium here without a GPU: Chromium falls back to SwiftShader (its
software renderer) by itself; no flag is needed.
"""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

CHROMIUM_FLAGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
VIEWPORT = {"width": 1100, "height": 700}
DEADLINE_MS = 60_000
PAGES = pytest.StashKey[list["Viewer"]]()


def chromium_path() -> str | None:
    """Debian's chromium, or $LAUNCHKIT_CHROMIUM."""
    configured = os.environ.get("LAUNCHKIT_CHROMIUM")
    return configured or shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """A headless Chromium for the session (skipped, saying why, only where none is installed).
    Playwright starts it with a fresh temporary profile of its own."""
    executable = chromium_path()
    if executable is None:
        pytest.skip("no chromium installed (.ci/run installs Debian's: apt-get install chromium)")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        launched = playwright.chromium.launch(executable_path=executable, args=CHROMIUM_FLAGS)
        try:
            yield launched
        finally:
            launched.close()


class Viewer:
    """One open viewer page."""

    def __init__(self, page: Any, shots: Path) -> None:
        self.page = page
        self.shots = shots
        self.problems: list[str] = []
        page.on("pageerror", lambda error: self.problems.append(f"page error: {error}"))
        page.on(
            "console",
            lambda m: (
                self.problems.append(f"console {m.type}: {m.text}") if m.type == "error" else None
            ),
        )

    def stats(self) -> dict[str, Any]:
        """The page's ``window.__viewer.stats``."""
        return dict(self.page.evaluate("window.__viewer ? window.__viewer.stats : {}"))

    def wait(self, expression: str, what: str, timeout_ms: int = DEADLINE_MS) -> Any:
        """Wait until the JavaScript ``expression`` is truthy (``v`` is window.__viewer, ``s`` its
        stats); its value. Fails naming ``what``, with the page's stats and problems."""
        script = (
            "() => { const v = window.__viewer; if (!v) return null; const s = v.stats; "
            f"return ({expression}) || null; }}"
        )
        try:
            return self.page.wait_for_function(script, timeout=timeout_ms).json_value()
        except Exception as error:  # playwright's TimeoutError, or the page died
            raise AssertionError(
                f"timed out after {timeout_ms / 1000:g} s waiting for {what} "
                f"({expression}); page stats: {json.dumps(self.stats())}; "
                f"problems: {self.problems}; {type(error).__name__}"
            ) from None

    def screenshot(self, name: str) -> Path:
        """A picture of the page in the test's folder."""
        path = self.shots / f"{name}.png"
        self.page.screenshot(path=str(path))
        return path


@pytest.fixture
def open_viewer(
    browser: Any, request: pytest.FixtureRequest, tmp_path: Path
) -> Iterator[Callable[[str], Viewer]]:
    """Open the viewer at a URL in a new browser context; closed after the test."""
    contexts: list[Any] = []
    request.node.stash[PAGES] = []

    def open_page(url: str) -> Viewer:
        context = browser.new_context(viewport=VIEWPORT)
        contexts.append(context)
        viewer = Viewer(context.new_page(), tmp_path)
        request.node.stash[PAGES].append(viewer)
        viewer.page.goto(url)
        return viewer

    try:
        yield open_page
    finally:
        for context in contexts:
            context.close()


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]) -> Any:
    """Photograph the open pages of a failing test; the report names the pictures."""
    report = yield
    if report.when == "call" and report.failed:
        for index, viewer in enumerate(item.stash.get(PAGES, [])):
            try:
                if not viewer.page.is_closed():
                    path = viewer.screenshot(f"failure-{index}")
                    report.sections.append(("viewer screenshot", f"kept at {path}"))
            except Exception as error:  # the browser went away: report that instead
                report.sections.append(("viewer screenshot", f"none: {error}"))
    return report


@pytest.fixture(scope="module")
def panels_launch(launch_module: Any) -> Any:
    """panels.launch.py (rviz2 on a free port and the nodes of panel_nodes.py), serving."""
    from launchkit.testing._isolation import free_loopback_port

    port = free_loopback_port()
    handle = launch_module("panels.launch.py", args={"viewer_port": str(port)}, ready_timeout=60)
    handle.process("rviz2").wait_output("Foxglove WebSocket on", timeout=60)
    for role in ("talker", "listener", "driver", "follower", "logger", "tuner"):
        handle.process(role).wait_output(f"{role} ready", timeout=60)
    handle.viewer_url = f"http://127.0.0.1:{port}/"
    return handle


def open_panel(open_viewer: Callable[[str], Viewer], url: str, panel: str) -> Viewer:
    """The viewer at ``url`` with ``panel`` shown (its tab clicked, as a person would)."""
    viewer = open_viewer(url)
    viewer.wait("s.connected", "the page connected")
    viewer.page.locator(f'#tabs button[data-panel="{panel}"]').click()
    viewer.wait(f"v.panel() === {json.dumps(panel)}", f"the {panel} panel shown")
    return viewer


def keep_screenshot(viewer: Viewer, name: str) -> Path:
    """A picture of the page in the test's folder (``$LAUNCHKIT_PANEL_SHOTS`` keeps a copy
    there, for looking at them after the run)."""
    path = viewer.screenshot(name)
    folder = os.environ.get("LAUNCHKIT_PANEL_SHOTS")
    if folder:
        Path(folder).mkdir(parents=True, exist_ok=True)
        shutil.copy(path, Path(folder) / path.name)
    return path
