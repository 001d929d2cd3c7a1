"""docs/tutorials.md, run as written: every command of the page in order, its output compared
with what the page shows, and the page's pictures taken at their place in a headless Chromium.

The page is read, not copied, so page and test cannot drift apart:

- a ```` ```console ```` block holds commands (``$ COMMAND``) each followed by what it prints.
  Without ``terminal=N`` a command runs to its end in the tutorial's shell (its folder and its
  environment carry over from one command to the next, so ``cd`` and ``. install/setup.sh``
  work) and its standard output must be what is shown, exactly but for ``...``: a line ``...``
  stands for any lines, and ``...`` within a line for any text. Commands that only look at the
  graph are asked again until they show what the page shows (a node that just stopped leaves
  the graph a moment later), within a deadline.
- with ``terminal=N`` the command starts in terminal N (a pseudo-terminal, its own process
  group) and keeps running; each shown line must appear, in order. ``^C`` sends it SIGINT (what
  Ctrl-C sends) and waits for it to end; lines after ``^C`` must appear before it ends.
- a block after a line ``File `PATH`:`` is written to PATH, in the shell's folder.
- a picture ``(images/NAME.png)`` is taken then: :data:`PICTURES` says what each must show
  before it is taken. ``LAUNCHKIT_TUTORIAL_SHOTS=docs/images`` keeps the pictures there.

Mirrored from the page's words, not read from it: the keys a learner presses in the teleop
(↑ once, then ←), pressed once the turtle's ``cmd_vel`` has the teleop as its publisher. The
viewer's port and the router are the test's own (``LAUNCHKIT_VIEWER_PORT``,
``LAUNCHKIT_ROUTER``); the page's ``8765`` is read as that port.
"""

from __future__ import annotations

import functools
import os
import pty
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest

from launchkit.testing._isolation import free_loopback_port
from tests.stock.conftest import probe_node
from tests.support import hosted_router
from tests.viewer.conftest import Viewer, open_panel
from tests.viewer.test_panels import wait_drawn

pytestmark = pytest.mark.long  # started first: see tests/conftest.py

DOC = Path(__file__).resolve().parents[2] / "docs" / "tutorials.md"
DEADLINE = 120.0
DOC_PORT = "8765"
ANSI = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")
FENCE = re.compile(r"^```(\S*)(.*)$")
FILE_LINE = re.compile(r"^File `([^`]+)`:$")
PICTURE = re.compile(r"\]\(images/([\w-]+)\.png\)")
#: commands that only look at the graph: asked again until the graph settles
LOOKS = re.compile(
    r"^launchkit (node (list|info)|topic (list|info)|service (list|type|find)|param (list|get))\b"
)
UP, LEFT = b"\x1b[A", b"\x1b[D"
CENTRE = 5.544444561004639


# -- the page, read ---------------------------------------------------------------------------


@dataclass
class Run:
    """``$ COMMAND`` and the lines shown after it (in ``terminal``, or the shell when None)."""

    line: int
    command: str
    terminal: str | None
    expected: list[str] = field(default_factory=list)


@dataclass
class Stop:
    """``^C`` in ``terminal``, and the lines shown after it."""

    line: int
    terminal: str
    expected: list[str] = field(default_factory=list)


@dataclass
class WriteFile:
    """A block the page says is the file ``path``."""

    line: int
    path: str
    text: str


@dataclass
class Picture:
    """A picture of the viewer the page shows here."""

    line: int
    name: str


Step = Run | Stop | WriteFile | Picture


def read_steps(text: str) -> list[Step]:
    """The page's steps in order."""
    steps: list[Step] = []
    lines = text.splitlines()
    index = 0
    before = ""  # the last non-blank line outside a block
    while index < len(lines):
        line = lines[index]
        fence = FENCE.match(line)
        if not fence:
            picture = PICTURE.search(line)
            if picture:
                steps.append(Picture(index + 1, picture[1]))
            before = line if line.strip() else before
            index += 1
            continue
        start = index + 1
        end = next(i for i in range(start, len(lines)) if lines[i].startswith("```"))
        body = lines[start:end]
        if fence[1] == "console":
            terminal = re.search(r"terminal=(\w+)", fence[2])
            steps.extend(console_steps(body, start + 1, terminal[1] if terminal else None))
        elif FILE_LINE.match(before):
            steps.append(WriteFile(start, FILE_LINE.match(before)[1], "\n".join(body) + "\n"))  # type: ignore[index]
        before = ""
        index = end + 1
    return steps


def console_steps(body: list[str], first_line: int, terminal: str | None) -> list[Step]:
    """The commands and stops of one console block."""
    steps: list[Step] = []
    for offset, line in enumerate(body):
        if line.startswith("$ "):
            steps.append(Run(first_line + offset, line[2:], terminal))
        elif line == "^C":
            assert terminal, f"tutorials.md:{first_line + offset}: ^C outside a terminal block"
            steps.append(Stop(first_line + offset, terminal))
        else:
            step = steps[-1] if steps else None
            assert isinstance(step, (Run, Stop)), (
                f"tutorials.md:{first_line + offset}: output first"
            )
            step.expected.append(line)
    return steps


# -- what is shown, compared ------------------------------------------------------------------


@functools.cache
def pattern(shown: str) -> re.Pattern[str]:
    """A shown line as a pattern: ``...`` matches any text."""
    return re.compile(".*".join(re.escape(part) for part in shown.rstrip().split("...")) + r"\Z")


def trimmed(lines: list[str]) -> list[str]:
    """Lines without trailing spaces, and without blank lines at the end."""
    out = [line.rstrip() for line in lines]
    while out and not out[-1]:
        out.pop()
    return out


def same_output(shown: list[str], printed: list[str]) -> bool:
    """Whether ``printed`` is what ``shown`` shows (a ``...`` line: any lines)."""
    want, got = trimmed(shown), trimmed(printed)

    @functools.cache
    def fits(i: int, j: int) -> bool:
        if i == len(want):
            return j == len(got)
        if want[i].strip() == "...":
            return any(fits(i + 1, k) for k in range(j, len(got) + 1))
        return j < len(got) and bool(pattern(want[i]).match(got[j])) and fits(i + 1, j + 1)

    return fits(0, 0)


# -- the learner's shell and terminals ---------------------------------------------------------


class Shell:
    """The tutorial's shell: a folder and an environment that carry over between commands."""

    def __init__(self, cwd: Path, env: dict[str, str], state: Path) -> None:
        self.cwd = cwd
        self.env = env
        self._state = state

    def run(self, command: str) -> subprocess.CompletedProcess[str]:
        """Run ``command`` to its end; keep the folder and environment it leaves."""
        where, env = self._state / "cwd", self._state / "env"
        script = f'{command}\n__status=$?\npwd > "{where}"\nenv -0 > "{env}"\nexit $__status\n'
        done = subprocess.run(
            ["bash", "-c", script],
            cwd=self.cwd,
            env=self.env,
            capture_output=True,
            text=True,
            timeout=DEADLINE,
            stdin=subprocess.DEVNULL,
        )
        if done.returncode == 0:
            self.cwd = Path(where.read_text().strip())
            pairs = env.read_bytes().decode().split("\0")
            self.env = dict(pair.split("=", 1) for pair in pairs if "=" in pair)
        return done


class Terminal:
    """A command running in a pseudo-terminal of its own, its output kept as lines."""

    def __init__(self, command: str, shell: Shell) -> None:
        self.command = command
        master, slave = pty.openpty()
        self.proc = subprocess.Popen(
            ["bash", "-c", command],
            stdin=slave,
            stdout=slave,
            stderr=slave,
            cwd=shell.cwd,
            env=shell.env,
            start_new_session=True,
        )
        os.close(slave)
        self.master = master
        self.lines: list[str] = []
        self.seen = 0  # lines before this one were matched already
        self._lock = threading.Lock()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        partial = ""
        while True:
            try:
                data = os.read(self.master, 65536)
            except OSError:  # the terminal's other side closed: the program ended
                break
            if not data:
                break
            *complete, partial = (partial + data.decode(errors="replace")).split("\n")
            with self._lock:
                self.lines.extend(ANSI.sub("", line).replace("\r", "") for line in complete)
        with self._lock:
            if partial:
                self.lines.append(ANSI.sub("", partial).replace("\r", ""))

    def expect(self, shown: list[str], where: str) -> None:
        """Wait until each of ``shown`` has appeared, in order."""
        for line in shown:
            wanted = pattern(line)
            deadline = time.monotonic() + DEADLINE
            while True:
                with self._lock:
                    found = next(
                        (
                            i
                            for i in range(self.seen, len(self.lines))
                            if wanted.match(self.lines[i])
                        ),
                        None,
                    )
                    tail = self.lines[-15:]
                if found is not None:
                    self.seen = found + 1
                    break
                ended = self.proc.poll() is not None and not self._reader.is_alive()
                if ended or time.monotonic() > deadline:
                    raise AssertionError(
                        f"{where}: `{self.command}` did not print {line!r} "
                        f"({f'it ended, status {self.proc.returncode}' if ended else 'deadline'}); "
                        f"its last lines: {tail}"
                    )
                time.sleep(0.05)

    def send(self, keys: bytes) -> None:
        """Type ``keys`` into the terminal."""
        os.write(self.master, keys)

    def interrupt(self, where: str) -> None:
        """Ctrl-C: SIGINT to its process group; wait for it to end."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGINT)
        try:
            self.proc.wait(DEADLINE)
        except subprocess.TimeoutExpired:
            self.kill()
            raise AssertionError(f"{where}: `{self.command}` did not end on Ctrl-C") from None
        self._reader.join(10)

    def kill(self) -> None:
        """End it whatever it is doing (cleanup)."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait()
        self._reader.join(10)
        os.close(self.master)


# -- the learner's hands and eyes -------------------------------------------------------------


class Turtles:
    """The test's own node, watching turtle1 and the teleop as a learner watches the page."""

    def __init__(self, node: Any) -> None:
        from launchkit.ros.msgs.turtlesim.msg import Pose

        self.node = node
        self.poses: list[Any] = []
        node.create_subscription(Pose, "/turtle1/pose", self.poses.append, 10)

    def wait(self, predicate: Callable[[], bool], what: str, timeout: float = DEADLINE) -> bool:
        """Spin until ``predicate()``; False after ``timeout``."""
        import launchkit.ros as ros

        deadline = time.monotonic() + timeout
        while not predicate():
            if time.monotonic() > deadline:
                return False
            ros.spin_once(self.node, timeout_sec=0.05)
        return True

    def drive_with_keys(self, terminal: Terminal, where: str) -> None:
        """Press ↑ until turtle1 moves (each press is one command), then ← once it stopped."""
        publisher = lambda: self.node.count_publishers("/turtle1/cmd_vel") > 0  # noqa: E731
        assert self.wait(publisher, "the teleop's publisher"), f"{where}: no teleop publisher"
        for _ in range(10):
            self.poses.clear()
            terminal.send(UP)
            if self.wait(lambda: any(p.linear_velocity > 0 for p in self.poses), "", 5.0):
                break
        else:
            raise AssertionError(f"{where}: turtle1 did not move on ↑")
        # the next key replaces the command: press it once this one has run its second
        stopped = lambda: self.poses[-1].linear_velocity == 0.0  # noqa: E731
        assert self.wait(stopped, "turtle1 at rest"), f"{where}: turtle1 did not stop"
        terminal.send(LEFT)


def keep(viewer: Viewer, name: str) -> Path:
    """The picture, in the test's folder (and in $LAUNCHKIT_TUTORIAL_SHOTS when set)."""
    path = viewer.screenshot(name)
    folder = os.environ.get("LAUNCHKIT_TUTORIAL_SHOTS")
    if folder:
        Path(folder).mkdir(parents=True, exist_ok=True)
        shutil.copy(path, Path(folder) / path.name)
    return path


def wait_turtlesim(viewer: Viewer, expression: str, what: str) -> None:
    """:meth:`Viewer.wait`, saying what the turtlesim tab showed when it fails."""
    try:
        viewer.wait(expression, what)
    except AssertionError as error:
        shown = viewer.page.evaluate(
            "JSON.stringify(window.__turtlesim && window.__turtlesim.stats)"
        )
        raise AssertionError(f"{error}; the turtlesim tab: {shown}") from None


def turtle_moved(open_viewer: Callable[[str], Viewer], url: str) -> Viewer:
    viewer = open_viewer(url)
    centre = int(CENTRE * 45)  # its trail starts where it stood: the pen's colour there
    wait_turtlesim(
        viewer,
        "v.panel() === 'turtlesim' && window.__turtlesim.stats.turtles.length === 1 "
        f"&& Math.abs(window.__turtlesim.stats.turtles[0].x - {CENTRE}) > 0.5 "
        f"&& window.__turtlesim.pixel({centre}, {centre}).join() === '179,184,255,255'",
        "the turtlesim tab showing turtle1 moved from the centre, its trail behind it",
    )
    return viewer


def graph_of_teleop(open_viewer: Callable[[str], Viewer], url: str) -> Viewer:
    viewer = open_panel(open_viewer, url, "graph")
    shown = wait_drawn(
        viewer,
        ["n:/teleop_turtle", "t:/turtle1/cmd_vel", "n:/turtlesim"],
        "the teleop, its topic and turtlesim drawn",
    )
    edges = {tuple(edge) for edge in shown["edges"]}
    assert ("n:/teleop_turtle", "t:/turtle1/cmd_vel") in edges, edges
    assert ("t:/turtle1/cmd_vel", "n:/turtlesim") in edges, edges
    return viewer


def turtle2_follows(open_viewer: Callable[[str], Viewer], url: str) -> Viewer:
    viewer = open_viewer(url)
    # spawned at (4, 2), 3.9 m from turtle1: it has closed in on it
    wait_turtlesim(
        viewer,
        "v.panel() === 'turtlesim' && window.__turtlesim.stats.turtles.length === 2 && "
        "(() => { const [a, b] = window.__turtlesim.stats.turtles; "
        "return Math.hypot(a.x - b.x, a.y - b.y) < 1.5; })()",
        "turtle2 within 1.5 m of turtle1",
    )
    return viewer


def frames_of_two_turtles(open_viewer: Callable[[str], Viewer], url: str) -> Viewer:
    viewer = open_panel(open_viewer, url, "tf")
    viewer.wait(
        " && ".join(
            f"document.querySelector('#tf-table tr[data-frame=\"{f}\"]')"
            for f in ("turtle1", "turtle2")
        )
        + " && [...document.querySelectorAll('#tf-table tbody tr')]"
        ".every((r) => r.cells[1].textContent === 'world' && r.cells[2].textContent !== '0.0')",
        "turtle1 and turtle2 listed under world, with their rates",
    )
    return viewer


#: what each of the page's pictures must show before it is taken
PICTURES: dict[str, Callable[[Callable[[str], Viewer], str], Viewer]] = {
    "tutorial-turtlesim": turtle_moved,
    "tutorial-graph": graph_of_teleop,
    "tutorial-tf2-follow": turtle2_follows,
    "tutorial-tf2-frames": frames_of_two_turtles,
}


# -- the test ---------------------------------------------------------------------------------


def test_the_page_reads_as_steps() -> None:
    steps = read_steps(DOC.read_text())
    names = {step.name for step in steps if isinstance(step, Picture)}
    assert names == set(PICTURES)
    for name in names:  # every picture the page shows is committed beside it
        assert (DOC.parent / "images" / f"{name}.png").is_file(), name
    assert any(isinstance(s, WriteFile) and s.path.endswith("setup.py") for s in steps)
    assert same_output(["a", "...", "x: ..."], ["a", "b", "c", "x: 1.0"])
    assert not same_output(["a", "x: ..."], ["a", "b", "x: 1.0"])


@pytest.fixture
def tutorial(tmp_path: Path) -> Iterator[tuple[Shell, str]]:
    """The learner's shell in a fresh folder, on the test's own router and viewer port."""
    home = tmp_path / "home"
    home.mkdir()
    port = str(free_loopback_port())
    with hosted_router() as endpoint, pytest.MonkeyPatch.context() as patch:
        patch.setenv("LAUNCHKIT_ROUTER", endpoint)
        env = {
            **os.environ,
            "HOME": str(home),
            "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}",
            "LAUNCHKIT_ROUTER": endpoint,
            "LAUNCHKIT_VIEWER_PORT": port,
            "ROS_LOG_DIR": str(tmp_path / "ros_log"),
        }
        state = tmp_path / "state"
        state.mkdir()
        yield Shell(tmp_path, env, state), port


def test_every_step_of_the_tutorial_runs_as_written(
    tutorial: tuple[Shell, str], open_viewer: Callable[[str], Viewer]
) -> None:
    shell, port = tutorial
    url = f"http://127.0.0.1:{port}/"
    terminals: dict[str, Terminal] = {}

    def shown(lines: list[str]) -> list[str]:
        return [line.replace(DOC_PORT, port) for line in lines]

    # hidden, so that node list leaves the test's own node out
    with probe_node("_tutorial_learner") as node:
        turtles = Turtles(node)
        try:
            for step in read_steps(DOC.read_text()):
                where = f"docs/tutorials.md:{step.line}"
                if isinstance(step, WriteFile):
                    target = shell.cwd / step.path
                    target.parent.mkdir(parents=True, exist_ok=True)
                    target.write_text(step.text)
                elif isinstance(step, Picture):
                    viewer = PICTURES[step.name](open_viewer, url)
                    keep(viewer, step.name)
                elif isinstance(step, Stop):
                    terminals[step.terminal].interrupt(where)
                    terminals.pop(step.terminal).expect(shown(step.expected), where)
                elif step.terminal is not None:
                    assert step.terminal not in terminals, f"{where}: terminal {step.terminal} busy"
                    terminal = terminals[step.terminal] = Terminal(step.command, shell)
                    terminal.expect(shown(step.expected), where)
                    if "turtle_teleop_key" in step.command:
                        turtles.drive_with_keys(terminal, where)
                else:
                    run_in_shell(shell, step, shown(step.expected), where)
        finally:
            for terminal in terminals.values():
                terminal.kill()


def run_in_shell(shell: Shell, step: Run, expected: list[str], where: str) -> None:
    """Run a command to its end; fail unless it succeeds printing what the page shows."""
    deadline = time.monotonic() + DEADLINE
    while True:
        done = shell.run(step.command)
        printed = done.stdout.splitlines()
        if done.returncode == 0 and same_output(expected, printed):
            return
        if not LOOKS.match(step.command) or time.monotonic() > deadline:
            raise AssertionError(
                f"{where}: `{step.command}` (status {done.returncode}) printed\n"
                f"{done.stdout}\nnot what the page shows:\n" + "\n".join(expected) + "\n"
                f"stderr: {done.stderr}"
            )
        time.sleep(0.5)  # asked again: the graph settles
