"""The supervisor loop without real processes: an injected process factory and clock, and the
loop turned one step at a time, so respawns, stops and escalations are checked line by line
and instantly (the same behaviour with real processes is in test_processes.py and
test_supervision.py)."""

from __future__ import annotations

import errno
import io
import signal
from collections.abc import Iterator
from dataclasses import dataclass

import pytest

from launchkit.description.process_spec import ProcessSpec
from launchkit.runtime.lifecycle import State
from launchkit.runtime.output import Output
from launchkit.runtime.process import ProcessPipes
from launchkit.runtime.supervisor import Supervisor


class FakeProcess(ProcessPipes):
    """A process that exists only here: it exits when the test says so, or on a signal it
    does not ignore. Its pids are made up and never signalled for real; it has no streams and
    no pidfd (the loop polls it)."""

    def __init__(
        self,
        spec: ProcessSpec,
        label: str,
        index: int,
        ignores: tuple[int, ...] = (),
        refuses_to_start: bool = False,
    ) -> None:
        super().__init__(spec, label, index)
        self.ignores = ignores
        self.refuses_to_start = refuses_to_start
        self.incarnations = 0
        self.received: list[int] = []
        self.code: int | None = None

    @property
    def pid(self) -> int:
        return 900_000 + 100 * self.index + self.incarnations

    def spawn(self) -> None:
        if self.refuses_to_start:
            raise OSError(errno.ENOENT, "No such file or directory")
        self.incarnations += 1
        self.code = None

    def poll(self) -> int | None:
        return self.code

    def signal_group(self, signum: int) -> None:
        self.received.append(signum)
        if signum not in self.ignores:
            self.code = -signum

    def group_alive(self) -> bool:
        return False

    def kill_leftovers(self) -> None:
        self.signal_group(signal.SIGKILL)

    def reap(self) -> None:
        pass


class Clock:
    """Time that moves only when told to."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


@dataclass
class Rig:
    """A supervisor with fake processes, a fake clock and its screen output."""

    supervisor: Supervisor
    clock: Clock
    screen: io.StringIO
    processes: dict[str, FakeProcess]
    seen: int = 0

    def start(self, name: str, **spec: object) -> FakeProcess:
        self.supervisor.start_process(ProcessSpec(name=name, cmd=["prog"], env={}, **spec))
        return self.processes[name]

    def advance(self, seconds: float) -> list[str]:
        """Let ``seconds`` pass, turn the loop once; the launch lines printed meanwhile."""
        self.clock.now += seconds
        self.supervisor.step(0)
        return self.lines()

    def lines(self) -> list[str]:
        lines = self.screen.getvalue().splitlines()
        new, self.seen = lines[self.seen :], len(lines)
        return new


@pytest.fixture
def rig() -> Iterator[Rig]:
    clock, screen = Clock(), io.StringIO()
    processes: dict[str, FakeProcess] = {}
    behaviour: dict[str, dict[str, object]] = {
        "stubborn": {"ignores": (signal.SIGINT, signal.SIGTERM)},
        "ghost": {"refuses_to_start": True},
    }

    def factory(spec: ProcessSpec, label: str, index: int) -> FakeProcess:
        process = FakeProcess(spec, label, index, **behaviour.get(spec.name, {}))
        processes[spec.name] = process
        return process

    supervisor = Supervisor(Output(screen, colour=False), clock=clock, process_factory=factory)
    yield Rig(supervisor, clock, screen, processes)
    supervisor.close()


def test_a_dead_process_respawns_after_its_delay_until_its_retries_run_out(rig: Rig) -> None:
    worker = rig.start("worker", respawn=True, respawn_delay=2.0, respawn_max_retries=1)
    assert rig.lines() == ["[INFO] [worker-1]: process started with pid [900101]"]
    worker.code = 4
    assert rig.advance(0) == [
        "[ERROR] [worker-1]: process has died [pid 900101, exit code 4, cmd 'prog'].",
        "[INFO] [worker-1]: respawning in 2 s",
    ]
    assert rig.advance(1.9) == []
    assert rig.advance(0.1) == ["[INFO] [worker-1]: process started with pid [900102]"]
    worker.code = 4
    assert rig.advance(0)[1:] == ["[WARNING] [worker-1]: not respawning: 1 retries used"]
    assert worker.state is State.EXITED and worker.incarnations == 2


def test_shutdown_escalates_on_the_stop_timeouts(rig: Rig) -> None:
    polite = rig.start("polite")
    stubborn = rig.start("stubborn", sigterm_timeout=3.0, sigkill_timeout=1.5)
    rig.lines()
    rig.supervisor.begin_shutdown("enough")
    assert rig.lines() == [
        "[INFO] [launch]: enough",
        "[INFO] [polite-1]: sending signal 'SIGINT' to process[polite-1]",
        "[INFO] [stubborn-2]: sending signal 'SIGINT' to process[stubborn-2]",
    ]
    assert rig.advance(0) == ["[INFO] [polite-1]: process has finished [pid 900101, signal SIGINT]"]
    assert rig.advance(2.9) == []
    assert rig.advance(0.1) == [
        "[ERROR] [stubborn-2]: process[stubborn-2] failed to terminate '3' seconds after "
        "receiving 'SIGINT', escalating to 'SIGTERM'",
        "[INFO] [stubborn-2]: sending signal 'SIGTERM' to process[stubborn-2]",
    ]
    kill = "[INFO] [stubborn-2]: sending signal 'SIGKILL' to process[stubborn-2]"
    assert rig.advance(1.5)[-1] == kill
    gone = "[INFO] [stubborn-2]: process has finished [pid 900201, signal SIGKILL]"
    assert rig.advance(0) == [gone]
    assert polite.received == [signal.SIGINT]
    assert stubborn.received == [signal.SIGINT, signal.SIGTERM, signal.SIGKILL]


def test_a_second_signal_escalates_at_once(rig: Rig) -> None:
    stubborn = rig.start("stubborn")
    rig.supervisor.handle_signal(signal.SIGINT)
    rig.lines()
    rig.supervisor.handle_signal(signal.SIGINT)
    assert rig.lines() == [
        "[WARNING] [launch]: SIGINT again: escalating now; still waiting for "
        "stubborn-1 [pid 900101]",
        "[INFO] [stubborn-1]: sending signal 'SIGTERM' to process[stubborn-1]",
    ]
    assert stubborn.received == [signal.SIGINT, signal.SIGTERM]


def test_a_required_process_ends_the_launch_with_its_exit_code(rig: Rig) -> None:
    required = rig.start("required", on_exit_shutdown=True, respawn=True)
    other = rig.start("other")
    required.code = 3
    lines = rig.advance(0)
    reason = "process[required-1] was required: shutting down launched system"
    assert f"[INFO] [launch]: {reason}" in lines
    assert rig.supervisor.exit_code == 3
    assert required.incarnations == 1 and other.received == [signal.SIGINT]


def test_a_process_that_cannot_start_stops_the_launch(rig: Rig) -> None:
    rig.start("ghost")
    lines = rig.lines()
    why = "could not start process: No such file or directory: 'prog'"
    assert lines[0] == f"[ERROR] [ghost-1]: {why}"
    assert lines[1] == "[ERROR] [launch]: a process could not be started"
    assert rig.supervisor.exit_code == 1 and rig.supervisor.shutting_down
