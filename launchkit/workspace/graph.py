"""The workspace's dependency graph: which package must be built before which, the
selection options (``--packages-select``, ``--packages-up-to``, ``--packages-skip``), and
cycles found before anything is built.

Every dependency kind but ``test_depend`` and ``doc_depend`` orders the build, as colcon
orders a build; a ``group_depend`` stands for every workspace package that is a
``member_of_group`` of that group.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from graphlib import CycleError, TopologicalSorter

from launchkit.errors import UserError
from launchkit.workspace.manifest import DEPENDENCY_TAGS, Dependency, Manifest

#: Dependency kinds that order a build (format 1's ``run_depend`` is read as ``exec_depend``).
ORDERING_KINDS = tuple(
    kind for kind in DEPENDENCY_TAGS if kind not in ("test_depend", "doc_depend", "run_depend")
)


def topological(dependencies: Mapping[str, Iterable[str]]) -> list[str]:
    """Every name of ``dependencies`` after the names it maps to (ties by name);
    :class:`graphlib.CycleError` if they go round."""
    sorter: TopologicalSorter[str] = TopologicalSorter()
    for name in sorted(dependencies):
        sorter.add(name, *sorted(dependencies[name]))
    sorter.prepare()
    order: list[str] = []
    while sorter.is_active():
        ready = sorted(sorter.get_ready())
        order.extend(ready)
        sorter.done(*ready)
    return order


class Workspace:
    """The packages found, by name, with their dependencies inside the workspace."""

    def __init__(self, manifests: Iterable[Manifest]) -> None:
        self.packages = {m.name: m for m in manifests}
        groups: dict[str, list[str]] = {}
        for manifest in self.packages.values():
            for group in manifest.groups:
                groups.setdefault(group, []).append(manifest.name)
        self.edges: dict[str, dict[str, Dependency | None]] = {}
        for manifest in self.packages.values():
            edges: dict[str, Dependency | None] = {}
            for dep in manifest.depends(*ORDERING_KINDS):
                if dep.name in self.packages:
                    edges.setdefault(dep.name, dep)
            for group in manifest.group_depends:
                for member in groups.get(group, []):
                    if member != manifest.name:
                        edges.setdefault(member, None)
            self.edges[manifest.name] = edges

    def dependencies(self, name: str) -> list[str]:
        """The workspace packages ``name`` depends on directly, sorted."""
        return sorted(self.edges[name])

    def order(self) -> list[str]:
        """Every package, each after the ones it depends on (ties by name);
        :class:`UserError` naming the packages of a cycle."""
        try:
            return topological(self.edges)
        except CycleError as error:
            raise self._cycle_error(list(error.args[1])) from None

    def _cycle_error(self, cycle: list[str]) -> UserError:
        # graphlib reports the cycle backwards (each node is a dependency of the next)
        cycle = cycle[::-1]
        first = self.edges[cycle[0]].get(cycle[1])
        return UserError(
            "dependency cycle: " + " -> ".join(cycle),
            first.location if first is not None else self.packages[cycle[0]].location,
            expected="packages that do not depend on each other in a circle",
            hint="the package.xml files: "
            + ", ".join(str(self.packages[n].manifest_path) for n in sorted(set(cycle))),
        )

    def select(
        self,
        select: list[str] | None = None,
        up_to: list[str] | None = None,
        skip: list[str] | None = None,
    ) -> list[str]:
        """The packages to build, in build order."""
        order = self.order()
        chosen = set(order)
        if select is not None:
            chosen = set(self._known(select, "--packages-select"))
        if up_to is not None:
            wanted = self._known(up_to, "--packages-up-to")
            chosen &= self._with_dependencies(wanted)
        if skip is not None:
            chosen -= set(self._known(skip, "--packages-skip"))
        return [name for name in order if name in chosen]

    def _known(self, names: list[str], option: str) -> list[str]:
        unknown = [n for n in names if n not in self.packages]
        if unknown:
            raise UserError(
                f"{option}: no package named {', '.join(repr(n) for n in unknown)} "
                "in the workspace",
                expected="one of: " + (", ".join(sorted(self.packages)) or "(no packages found)"),
            )
        return names

    def _with_dependencies(self, names: list[str]) -> set[str]:
        found: set[str] = set()
        todo = list(names)
        while todo:
            name = todo.pop()
            if name not in found:
                found.add(name)
                todo.extend(self.edges[name])
        return found
