"""The architecture of docs/architecture.md, checked from the source with ``ast``: what each
package may import, and no import circles (imports made only for type checking count too)."""

from __future__ import annotations

import ast
from collections.abc import Iterator
from functools import cache
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "launchkit"

#: Modules that may import which launchkit modules (by prefix), besides their own package's.
#: The most specific prefix rules; docs/architecture.md draws the same table.
ALLOWED: dict[str, tuple[str, ...]] = {
    "launchkit": ("launchkit._lazy", "launchkit.api", "launchkit.checks", "launchkit.errors",
                  "launchkit.packages", "launchkit.runtime.hooks"),
    "launchkit.__main__": ("launchkit.cli",),
    "launchkit.cli": ("launchkit._argparse", "launchkit._exit", "launchkit.api",
                      "launchkit.bag.cli", "launchkit.bridge.cli", "launchkit.checks",
                      "launchkit.errors", "launchkit.own_process", "launchkit.packages",
                      "launchkit.remote.cli", "launchkit.ros.face", "launchkit.ros_cli",
                      "launchkit.runtime", "launchkit.workspace.cli"),
    "launchkit.api": ("launchkit.bridge.launch", "launchkit.checks", "launchkit.description",
                      "launchkit.errors", "launchkit.frontend", "launchkit.packages",
                      "launchkit.remote.launch", "launchkit.ros_adapter",
                      "launchkit.ros_cli.ros2_shim", "launchkit.runtime"),
    "launchkit.checks": ("launchkit.description", "launchkit.errors", "launchkit.frontend",
                         "launchkit.packages"),
    "launchkit.frontend": ("launchkit.description", "launchkit.errors", "launchkit.packages",
                           "launchkit.safe_yaml"),
    "launchkit.description": ("launchkit.errors", "launchkit.own_process", "launchkit.packages",
                              "launchkit.safe_yaml"),
    "launchkit.runtime": ("launchkit.description", "launchkit.envvars", "launchkit.errors",
                          "launchkit.own_process", "launchkit.startup_sigint",
                          "launchkit.ros.face", "launchkit.ros.federation", "launchkit.ros.router"),
    "launchkit.ros": ("launchkit._lazy", "launchkit.envvars", "launchkit.errors",
                      "launchkit.own_process",
                      "launchkit.rotations", "launchkit.safe_yaml"),
    "launchkit.ros.msgs": ("launchkit._lazy", "launchkit.envvars", "launchkit.errors",
                           "launchkit.packages"),
    "launchkit.ros_adapter": ("launchkit.description", "launchkit.envvars", "launchkit.errors",
                              "launchkit.ros"),
    "launchkit.ros_cli": ("launchkit._argparse", "launchkit.envvars", "launchkit.errors",
                          "launchkit.packages", "launchkit.ros"),
    "launchkit.stock": ("launchkit._exit", "launchkit.envvars", "launchkit.errors",
                        "launchkit.startup_sigint",
                        "launchkit.packages", "launchkit.ros", "launchkit.rotations",
                        "launchkit.runtime.lifecycle", "launchkit.runtime.process",
                        "launchkit.runtime.supervisor_client"),
    "launchkit.bag": ("launchkit.envvars", "launchkit.errors", "launchkit.ros"),
    "launchkit.bridge": ("launchkit.description", "launchkit.envvars", "launchkit.errors",
                         "launchkit.packages", "launchkit.ros", "launchkit.stock._entry"),
    "launchkit.stock.gazebo_ros.sim": ("launchkit.errors", "launchkit.rotations"),
    "launchkit.remote": ("launchkit.description", "launchkit.envvars", "launchkit.errors",
                         "launchkit.ros", "launchkit.ros_cli.router_options",
                         "launchkit.runtime"),
    "launchkit.testing": ("launchkit.envvars", "launchkit.errors", "launchkit.ros",
                          "launchkit.runtime"),
    "launchkit.workspace": ("launchkit._argparse", "launchkit.errors", "launchkit.packages",
                            "launchkit.ros.msgs", "launchkit.runtime.orphan_guard"),
    "launchkit.packages": ("launchkit.envvars", "launchkit.errors"),
    "launchkit.safe_yaml": ("launchkit.errors",),
    "launchkit.errors": (),
    "launchkit._argparse": (),
    "launchkit._exit": (),
    "launchkit._lazy": (),
    "launchkit.envvars": (),
    "launchkit.own_process": (),
    "launchkit.startup_sigint": (),
    "launchkit.rotations": (),
}  # fmt: skip

#: Known import circles allowed (none today).
EXEMPT_CIRCLES: list[set[str]] = []


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


@cache
def modules() -> dict[str, Path]:
    return {module_name(path): path for path in PACKAGE.rglob("*.py")}


def imports_of(name: str) -> set[str]:
    """The launchkit modules ``name`` imports anywhere in its body (``from X import Y`` is an
    import of module ``X.Y`` when that is a module, else of ``X``)."""
    path = modules()[name]
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*parent, *([node.module] if node.module else [])])
            submodules = {f"{base}.{alias.name}" for alias in node.names} & set(modules())
            found |= submodules
            if len(submodules) < len(node.names):
                found.add(base)
    return {target for target in found if target in modules() and target != name}


@cache
def graph() -> dict[str, set[str]]:
    """Every module's imports of launchkit modules (read once for the tests below)."""
    return {name: imports_of(name) for name in modules()}


def rule_for(name: str) -> str:
    return max((prefix for prefix in ALLOWED if within(name, prefix)), key=len)


def within(name: str, prefix: str) -> bool:
    return name == prefix or name.startswith(prefix + ".")


def own_package(name: str, rule: str) -> str | None:
    """The package whose modules ``name`` may import freely (none for ``launchkit`` itself)."""
    if rule.count(".") >= 2:
        return rule
    return ".".join(name.split(".")[:2]) if "." in name else None


def test_every_package_has_an_import_rule() -> None:
    # A new package (a bridge, bags, a YAML frontend's folder inside frontend/ is covered) gets
    # its line in ALLOWED and in the table of docs/architecture.md.
    unruled = sorted({".".join(n.split(".")[:2]) for n in modules() if rule_for(n) == "launchkit"})
    assert unruled == ["launchkit"]


def test_every_package_imports_only_what_its_layer_allows() -> None:
    wrong = []
    for name, targets in sorted(graph().items()):
        rule = rule_for(name)
        own = own_package(name, rule)
        for target in sorted(targets):
            if own is not None and within(target, own):
                continue
            if not any(within(target, allowed) for allowed in ALLOWED[rule]):
                wrong.append(f"{name} imports {target}")
    assert wrong == []


def circles(edges: dict[str, set[str]]) -> Iterator[set[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()

    def visit(node: str) -> Iterator[set[str]]:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in sorted(edges.get(node, ())):
            if target not in index:
                yield from visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = set()
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.add(member)
                if member == node:
                    break
            if len(component) > 1:
                yield component

    for node in sorted(edges):
        if node not in index:
            yield from visit(node)


def test_no_import_circles() -> None:
    found = [sorted(c) for c in circles(graph()) if c not in EXEMPT_CIRCLES]
    assert found == []


def test_the_circle_finder_finds_circles() -> None:
    edges = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert list(circles(edges)) == [{"a", "b", "c"}]
