"""The test suite's own environment: whatever the shell exports, the suite runs the same.

A user's shell may name a router (``LAUNCHKIT_ROUTER``), a viewer port, a ROS domain, a
federation, log limits, an RMW: none of them may change what the suite does or reach the
user's robot, and no test may write into the home folder or bind the default ports (7447, 8765).
So :func:`suite_environment` drops every ``LAUNCHKIT_*`` setting (``launchkit.envvars``) and
``RMW_IMPLEMENTATION``, and points every folder a program would make below the home (launchkit's
logs and cache, ROS's logs, the XDG folders) into one folder of the run; :func:`private_defaults`
gives the defaults that remain a private router port, viewer port and ROS domain. The suite's
``conftest.py`` applies both once per process (each xdist worker has defaults of its own).

The suite's own settings stay the user's to give: ``LAUNCHKIT_FUZZ_PROFILE`` and
``LAUNCHKIT_FUZZ_EXAMPLES`` (tests/fuzz), ``LAUNCHKIT_CHROMIUM`` (tests/viewer),
``LAUNCHKIT_ROS2_REFERENCE`` (the real ROS 2 launch stack to compare with),
``LAUNCHKIT_STRESS_RUNS`` and ``LAUNCHKIT_VIEWER_SCREENSHOT``; launchkit itself reads none of them.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping
from pathlib import Path

from launchkit.envvars import CACHE_DIR, NAMES, ROUTER, ROUTER_AUTOSTART, VIEWER_PORT
from launchkit.testing._isolation import domain_id, free_loopback_port, router_endpoint

#: The run's folder, made by the pytest process that starts the run and inherited by its xdist
#: workers (a name of the suite's own, not one launchkit reads).
RUN_DIR_ENV = "LAUNCHKIT_TEST_RUN_DIR"
#: What ROS and the XDG base directories put below the home folder, and launchkit's log folder
#: (``ROS_LOG_DIR``; its default is ``~/.launchkit/log``), each a sub-folder of the run's.
FOLDERS = {
    CACHE_DIR: "launchkit-cache",
    "ROS_LOG_DIR": "ros-log",
    "ROS_HOME": "ros-home",
    "XDG_CACHE_HOME": "xdg-cache",
    "XDG_CONFIG_HOME": "xdg-config",
    "XDG_DATA_HOME": "xdg-data",
    "XDG_STATE_HOME": "xdg-state",
    "XDG_RUNTIME_DIR": "xdg-runtime",
}
#: Variables of the shell that the suite never passes on (besides ``LAUNCHKIT_*``): the RMW is
#: the one the ros-jazzy wheels default to.
DROPPED = frozenset(NAMES) | {"RMW_IMPLEMENTATION", "ROS_DOMAIN_ID"}
#: Where the run's Python processes keep their bytecode when the shell asks Python not to write
#: it beside the sources (``PYTHONDONTWRITEBYTECODE``): without it each of the suite's thousands
#: of processes compiles every launchkit module it imports again (a fifth of a node's start).
BYTECODE = "bytecode"
#: One BLAS thread per process: numpy's OpenBLAS otherwise starts a pool of threads in every
#: process that imports it, which on a 2-core machine costs a third of the import's CPU (0.1 s)
#: in each of the suite's thousands of processes, and none of them does linear algebra to speak of.
BLAS_THREADS = {"OPENBLAS_NUM_THREADS": "1"}
#: What :func:`private_defaults` sets.
PRIVATE_DEFAULTS = (ROUTER, VIEWER_PORT, "ROS_DOMAIN_ID")


def run_dir() -> tuple[Path, bool]:
    """The run's folder, and whether this process made it (and so removes it at the end).

    An xdist worker uses the one its controller made; any other pytest process makes its own
    (so a value exported in the shell is never used).
    """
    inherited = os.environ.get(RUN_DIR_ENV)
    if inherited and os.environ.get("PYTEST_XDIST_WORKER") and Path(inherited).is_dir():
        return Path(inherited), False
    return Path(tempfile.mkdtemp(prefix="lk-test-run-")), True


def suite_environment(environ: Mapping[str, str], folder: Path) -> dict[str, str]:
    """``environ`` as the suite runs in it: without the shell's launchkit and ROS settings
    (:data:`DROPPED`), every home-derived folder in ``folder`` (:data:`FOLDERS`, made here),
    no shared background router started by accident (tests that mean to start one say so), one
    BLAS thread (:data:`BLAS_THREADS`), and bytecode kept in ``folder`` (:data:`BYTECODE`) where
    the shell forbids writing it beside the sources."""
    environment = {name: value for name, value in environ.items() if name not in DROPPED}
    for name, sub in FOLDERS.items():
        path = folder / sub
        path.mkdir(mode=0o700, exist_ok=True)  # XDG_RUNTIME_DIR must be private
        environment[name] = str(path)
    if environment.pop("PYTHONDONTWRITEBYTECODE", None):
        # compiled once into the run's folder and read from there; the sources stay unwritten
        path = folder / BYTECODE
        path.mkdir(exist_ok=True)
        environment["PYTHONPYCACHEPREFIX"] = str(path)
    environment[RUN_DIR_ENV] = str(folder)
    environment[ROUTER_AUTOSTART] = "0"
    environment.update(BLAS_THREADS)
    return environment


def private_defaults() -> dict[str, str]:
    """A router endpoint and a viewer port nothing listens on, and a ROS domain no DDS
    participant here uses: what a process started without its own gets instead of the
    defaults (7447, 8765, domain 0) that a user's running robot may hold."""
    return {
        ROUTER: router_endpoint(free_loopback_port()),
        VIEWER_PORT: str(free_loopback_port()),
        "ROS_DOMAIN_ID": str(domain_id()),
    }
