"""Stand-ins for ``launch_ros`` (actions and substitutions) that launch files construct."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import yaml

from launchkit.description import actions as lk
from launchkit.description.actions.parameters import ParamEntry
from launchkit.description.conditions import Condition
from launchkit.description.substitutions import ExecInPkg, FindPkgPrefix, FindPkgShare
from launchkit.frontend.python.launch_api import process_options
from launchkit.frontend.python.values import (
    SubstitutionLike,
    argv_text,
    here,
    optional_value,
    to_value,
)


class FindPackageShare(SubstitutionLike):
    """``launch_ros.substitutions.FindPackageShare``."""

    def __init__(self, package: Any) -> None:
        super().__init__(FindPkgShare([to_value(package)], here()))

    def find(self, *paths: Any) -> list[Any]:
        """``FindPackageShare(pkg).find('a', 'b')``: the share dir joined with ``paths``."""
        out: list[Any] = [self]
        for path in paths:
            out += ["/", path]
        return out


class FindPackagePrefix(SubstitutionLike):
    """``launch_ros.substitutions.FindPackagePrefix``."""

    def __init__(self, package: Any) -> None:
        super().__init__(FindPkgPrefix([to_value(package)], here()))


class ExecutableInPackage(SubstitutionLike):
    """``launch_ros.substitutions.ExecutableInPackage``."""

    def __init__(self, executable: Any, package: Any) -> None:
        super().__init__(ExecInPkg([to_value(executable), to_value(package)], here()))


def _param_entries(parameters: Iterable[Any]) -> list[ParamEntry]:
    entries: list[ParamEntry] = []
    for item in parameters:
        if isinstance(item, Mapping):
            entries.append(lk.ParamDict(_dict_entries(item)))  # one params file, as launch_ros
        else:
            entries.append(lk.ParamFile(to_value(item), False, here()))
    return entries


def _dict_entries(values: Mapping[Any, Any]) -> list[lk.ParamValue | lk.ParamGroup]:
    entries: list[lk.ParamValue | lk.ParamGroup] = []
    for name, value in values.items():
        if isinstance(value, Mapping):
            entries.append(lk.ParamGroup(to_value(name), _dict_entries(value)))
            continue
        if isinstance(value, bool | int | float | list | tuple) and not isinstance(
            value, SubstitutionLike
        ):
            # Python values keep their type: written as YAML, read back typed.
            text = yaml.safe_dump(
                list(value) if isinstance(value, tuple) else value, default_flow_style=True
            )
            text = text.strip().removesuffix("...").strip()
            entries.append(lk.ParamValue(to_value(name), to_value(text), None, None, here()))
        else:
            kind = "str" if isinstance(value, str) else None
            entries.append(lk.ParamValue(to_value(name), to_value(value), kind, None, here()))
    return entries


class Node(lk.ExecuteNode):
    """``launch_ros.actions.Node``."""

    def __init__(
        self,
        *,
        executable: Any,
        package: Any = None,
        name: Any = None,
        namespace: Any = None,
        exec_name: Any = None,
        parameters: Iterable[Any] | None = None,
        remappings: Iterable[tuple[Any, Any]] | None = None,
        arguments: Iterable[Any] | None = None,
        ros_arguments: Iterable[Any] | None = None,
        condition: Condition | None = None,
        **options: Any,
    ) -> None:
        super().__init__(
            optional_value(package),
            to_value(executable),
            process_options(**options),
            node_name=optional_value(name),
            namespace=optional_value(namespace),
            exec_name=optional_value(exec_name),
            args=argv_text(list(arguments)) if arguments else None,
            ros_args=argv_text(list(ros_arguments)) if ros_arguments else None,
            params=_param_entries(parameters or []),
            remaps=[lk.Remap(to_value(a), to_value(b)) for a, b in (remappings or [])],
            location=here(),
            condition=condition,
        )


class PushRosNamespace(lk.PushRosNamespace):
    """``launch_ros.actions.PushRosNamespace``."""

    def __init__(self, namespace: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(namespace), here(), condition)


class SetParameter(lk.SetParameter):
    """``launch_ros.actions.SetParameter``."""

    def __init__(self, name: Any, value: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(name), to_value(value), here(), condition)


class SetRemap(lk.SetRemap):
    """``launch_ros.actions.SetRemap``."""

    def __init__(self, src: Any, dst: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(src), to_value(dst), here(), condition)


class SetUseSimTime(lk.SetUseSimTime):
    """``launch_ros.actions.SetUseSimTime``."""

    def __init__(self, value: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(value), here(), condition)
