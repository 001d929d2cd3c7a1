"""Where the suite's time goes: ``--cpu-report=FILE`` records, per test, its wall time and the
CPU time (user + system) of the test's process and of the children it reaped during the test
(a process that outlives its test, or that nobody reaps, is not counted).

Each xdist worker appends to ``FILE.gw<N>`` (``FILE.main`` without xdist); one line per test:
``nodeid<TAB>wall<TAB>cpu_self<TAB>cpu_children`` in seconds. ``python -m tests.cpu_report FILE``
sums the lines per test file, most CPU first.
"""

from __future__ import annotations

import os
import resource
import sys
import time
from collections import defaultdict
from collections.abc import Iterator
from pathlib import Path

import pytest


def _cpu(who: int) -> float:
    usage = resource.getrusage(who)
    return usage.ru_utime + usage.ru_stime


def pytest_addoption(parser: pytest.Parser) -> None:
    """The ``--cpu-report`` option."""
    parser.addoption(
        "--cpu-report",
        metavar="FILE",
        default=None,
        help="append each test's wall and CPU time (own and reaped children's) to FILE.<worker>",
    )


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item: pytest.Item, nextitem: pytest.Item | None) -> Iterator[None]:
    """Measure one test: its setup, call and teardown."""
    report = item.config.getoption("--cpu-report")
    if not report:
        yield
        return
    start = (time.monotonic(), _cpu(resource.RUSAGE_SELF), _cpu(resource.RUSAGE_CHILDREN))
    yield
    wall = time.monotonic() - start[0]
    own = _cpu(resource.RUSAGE_SELF) - start[1]
    children = _cpu(resource.RUSAGE_CHILDREN) - start[2]
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    with open(f"{report}.{worker}", "a", encoding="utf-8") as out:
        out.write(f"{item.nodeid}\t{wall:.3f}\t{own:.3f}\t{children:.3f}\n")


def summarize(report: str) -> list[tuple[str, int, float, float]]:
    """Per test file: (file, tests, wall, cpu), most CPU first, from every ``report.*`` file."""
    tests: dict[str, int] = defaultdict(int)
    wall: dict[str, float] = defaultdict(float)
    cpu: dict[str, float] = defaultdict(float)
    parts = Path(report).parent.glob(Path(report).name + ".*")
    for part in (p for p in parts if p.suffix == ".main" or p.suffix.startswith(".gw")):
        for line in part.read_text(encoding="utf-8").splitlines():
            nodeid, seconds, own, children = line.split("\t")
            name = nodeid.split("::", 1)[0]
            tests[name] += 1
            wall[name] += float(seconds)
            cpu[name] += float(own) + float(children)
    rows = [(name, tests[name], wall[name], cpu[name]) for name in tests]
    return sorted(rows, key=lambda row: -row[3])


if __name__ == "__main__":
    rows = summarize(sys.argv[1])
    print(
        f"total: {sum(r[1] for r in rows)} tests, wall {sum(r[2] for r in rows):.0f} s, "
        f"cpu {sum(r[3] for r in rows):.0f} s"
    )
    for name, count, seconds, cpu in rows:
        print(f"{cpu:8.1f} {seconds:8.1f} {count:5d}  {name}")
