"""``launchkit build``: find the workspace's packages, order them, build each into
``install/PKG`` (several at once, each once the packages it depends on are done), write the
setup scripts, and report.

A package whose dependency failed or was skipped is skipped, saying which; the others are
built. Exit status: 0 when no package failed (skipped ones included: they are listed), 1 when
one failed, 2 for a mistake found before anything was built (no ``src/``, a malformed
package.xml, a dependency cycle, an unknown package named in an option).
"""

from __future__ import annotations

import importlib.util
import os
import sys
import time
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from dataclasses import dataclass, replace
from graphlib import TopologicalSorter
from pathlib import Path

from launchkit.errors import LaunchkitError, UserError
from launchkit.workspace.cmake_install import install_cmake_package
from launchkit.workspace.discovery import find_packages
from launchkit.workspace.folders import new_log_folder, prepare_folders
from launchkit.workspace.graph import Workspace
from launchkit.workspace.known import KnownPackages
from launchkit.workspace.pip_build import build_python_package, remove_prefix
from launchkit.workspace.plan import Job, NotBuilt, plan_package
from launchkit.workspace.processes import ChildProcesses
from launchkit.workspace.report import FAILED, FINISHED, SKIPPED, Report, Result
from launchkit.workspace.setup_scripts import write_setup_scripts

DEFAULT_BASE_PATH = Path("src")


@dataclass(frozen=True)
class BuildOptions:
    """What to build and where (paths relative to the working folder, the workspace root)."""

    base_paths: tuple[Path, ...] | None = None  # None: src/
    build_base: Path = Path("build")
    install_base: Path = Path("install")
    log_base: Path = Path("log")
    select: list[str] | None = None
    up_to: list[str] | None = None
    skip: list[str] | None = None
    symlink_install: bool = False
    workers: int = os.cpu_count() or 1


def build(options: BuildOptions, report: Report | None = None) -> int:
    """Build the workspace in the working folder; the exit status (see the module)."""
    report = report if report is not None else Report()
    started = time.monotonic()
    options = replace(
        options,
        build_base=options.build_base.absolute(),
        install_base=options.install_base.absolute(),
        log_base=options.log_base.absolute(),
    )
    manifests = find_packages(
        _base_paths(options), skip=[options.build_base, options.install_base, options.log_base]
    )
    workspace = Workspace(manifests)
    selected = workspace.select(options.select, options.up_to, options.skip)
    known = KnownPackages(set(workspace.packages))
    plans = {name: plan_package(workspace.packages[name], known) for name in selected}
    if any(isinstance(p, Job) and p.cmake is None for p in plans.values()):
        _check_python_tools()
    prepare_folders(options.build_base, options.install_base, options.log_base)
    if not workspace.packages:
        report.note(f"no packages found in {', '.join(map(str, _base_paths(options)))}")
    run = _Run(options, workspace, plans, report, new_log_folder(options.log_base))
    results = run.all(selected)
    write_setup_scripts(options.install_base)
    report.summary([results[name] for name in selected], time.monotonic() - started)
    return 1 if any(r.state == FAILED for r in results.values()) else 0


def _base_paths(options: BuildOptions) -> list[Path]:
    if options.base_paths is not None:
        return list(options.base_paths)
    if not DEFAULT_BASE_PATH.is_dir():
        raise UserError(
            f"no '{DEFAULT_BASE_PATH}' folder in {Path.cwd()}",
            expected="a workspace root holding src/ with the packages (or --base-paths)",
        )
    return [DEFAULT_BASE_PATH]


def _check_python_tools() -> None:
    missing = [name for name in ("pip", "setuptools") if importlib.util.find_spec(name) is None]
    if missing:
        raise UserError(
            f"building ament_python packages needs {' and '.join(missing)} "
            f"in launchkit's Python environment ({sys.executable})",
            expected="pip and setuptools installed beside launchkit",
            hint=f"{sys.executable} -m pip install {' '.join(missing)}"
            if "pip" not in missing
            else f"{sys.executable} -m ensurepip",
        )


class _Run:
    """One build: the decisions, the worker pool, the results as they come."""

    def __init__(
        self,
        options: BuildOptions,
        workspace: Workspace,
        plans: dict[str, Job | NotBuilt],
        report: Report,
        log_folder: Path,
    ) -> None:
        self.options = options
        self.workspace = workspace
        self.plans = plans
        self.report = report
        self.log_folder = log_folder
        self.results: dict[str, Result] = {}
        self.processes = ChildProcesses()

    def all(self, selected: list[str]) -> dict[str, Result]:
        """Build the selected packages (in an order their dependencies allow)."""
        chosen = set(selected)
        sorter: TopologicalSorter[str] = TopologicalSorter()
        for name in selected:
            sorter.add(name, *(d for d in self.workspace.dependencies(name) if d in chosen))
        sorter.prepare()
        running: dict[Future[Result], str] = {}
        waiting: list[str] = []  # ready to build, for a free worker
        workers = max(1, self.options.workers)
        pool = ThreadPoolExecutor(max_workers=workers)
        try:
            while sorter.is_active():
                for name in sorted(sorter.get_ready()):
                    decided = self._decided(name, chosen)
                    if decided is None:
                        waiting.append(name)
                    else:
                        self._record(decided)
                        sorter.done(name)
                while waiting and len(running) < workers:
                    name = waiting.pop(0)
                    self.report.started(name)
                    running[pool.submit(self._build, name)] = name
                if not running:
                    continue  # packages decided just now made others ready
                done, _ = wait(running, return_when=FIRST_COMPLETED)
                for future in done:
                    self._record(future.result())
                    sorter.done(running.pop(future))
        except BaseException:
            self.processes.stop_all()  # Ctrl-C: the running pip commands stop too
            raise
        finally:
            pool.shutdown(wait=True, cancel_futures=True)
            self.processes.close()
        return self.results

    def _record(self, result: Result) -> None:
        self.results[result.name] = result
        self.report.ended(result)

    def _decided(self, name: str, chosen: set[str]) -> Result | None:
        """The result of a package that is not built, or None if it is to be built."""
        plan = self.plans[name]
        if isinstance(plan, NotBuilt):
            state = FAILED if plan.failed else SKIPPED
            details = tuple(error.format() for error in plan.errors)
            return Result(name, state, reason=plan.reason, details=details)
        for dependency in self.workspace.dependencies(name):
            result = self.results.get(dependency)
            if dependency in chosen and result is not None and result.state != FINISHED:
                what = "failed" if result.state == FAILED else "was skipped"
                return Result(name, SKIPPED, reason=f"depends on {dependency}, which {what}")
        return None

    def _build(self, name: str) -> Result:
        plan = self.plans[name]
        assert isinstance(plan, Job)
        started = time.monotonic()
        prefix = self.options.install_base / name
        symlink = self.options.symlink_install
        try:
            if plan.cmake is None:
                log = self.log_folder / name / "stdout_stderr.log"
                staging = self.options.build_base / name
                build_python_package(plan.manifest, prefix, staging, log, self.processes, symlink)
            else:
                remove_prefix(prefix)
                install_cmake_package(plan.manifest, plan.cmake, prefix, symlink)
        except (LaunchkitError, OSError) as error:
            seconds = time.monotonic() - started
            if isinstance(error, LaunchkitError):
                return Result(name, FAILED, seconds, error.message, _details(error))
            return Result(name, FAILED, seconds, str(error))
        return Result(name, FINISHED, time.monotonic() - started)


def _details(error: LaunchkitError) -> tuple[str, ...]:
    """The lines under a failure: the located error line (its message without a location is
    the failure's reason already), what the tool said, the hint."""
    lines = error.format().splitlines()
    return tuple(lines if error.location is not None else lines[1:])
