"""A node's ROS arguments, built as launch_ros (Jazzy) builds them, in its order.

After the executable, its ``args`` and (when given) ``--ros-args ROS_ARGS``, a node gets one
more ``--ros-args`` section, always, holding:

1. ``-r __node:=NAME`` when it has a name; ``-r __ns:=NS`` when it has a namespace (its own,
   made absolute and prefixed by the pushed one; ``namespace=''`` means ``/``);
2. the scope's global parameters in the order they were set: ``-p name:=value`` for each
   ``SetParameter``, ``--params-file FILE`` for each ``SetParametersFromFile``;
3. its own parameters in document order: one generated params file per dict (per ``<param>``
   in XML), the given file for a parameter file, ``-p name:=value`` for a lone ``Parameter``.
   A generated file names the node by its full name when name and namespace are both known,
   else ``/**``;
4. the scope's remaps (``SetRemap``), then its own ``-r from:=to``.

Checked against ``ros2 launch`` (tests/engine/test_node_command_lines.py).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

import yaml

from launchkit.description.actions.parameters import (
    ParamEntry,
    ParamFile,
    ParamRule,
    evaluate_params,
    evaluate_value,
    params_file,
    typed_value,
)
from launchkit.description.actions.ros_scope import NAMESPACE_CONFIGURATION, ros_namespace
from launchkit.description.substitutions.base import Value, perform

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


def global_parameter(name: str, text: str) -> str:
    """``name:=value`` for a SetParameter: launch_ros reads the value as YAML and writes it
    back with Python's ``str`` (``true`` -> ``True``); a list is written as a YAML list."""
    value = typed_value(text, None, None)
    if isinstance(value, list):
        return f"{name}:={yaml.safe_dump(value, default_flow_style=True).strip()}"
    return f"{name}:={value}"


def parameter_rule(entry: ParamRule, context: LaunchContext) -> str:
    """``name:=value`` for a lone ``Parameter``: the value as ``yaml.dump`` writes it (with
    its document end marker, as launch_ros passes it)."""
    value = evaluate_value(entry.param, context)
    return f"{perform(entry.param.name, context)}:={yaml.dump(value)}"


def ros_arguments(
    node_name: Value | None,
    namespace: Value | None,
    params: Sequence[ParamEntry],
    remaps: Sequence[tuple[Value, Value]],
    context: LaunchContext,
) -> tuple[list[str], dict[str, str]]:
    """The items of the node's last ``--ros-args`` section, and the params files generated
    for it (path -> text, for ``--print``)."""
    out: list[str] = []
    files: dict[str, str] = {}
    name = perform(node_name, context) if node_name is not None else None
    if name is not None:
        out += ["-r", f"__node:={name}"]
    own = perform(namespace, context).strip() if namespace is not None else None
    ns = ros_namespace(context.configurations.get(NAMESPACE_CONFIGURATION), own)
    if ns is not None:
        out += ["-r", f"__ns:={ns}"]
    key = "/**" if name is None or ns is None else ns.rstrip("/") + "/" + name
    for item in context.scope.global_params:
        if isinstance(item, str):
            out += ["--params-file", os.path.abspath(item)]
        else:
            out += ["-p", global_parameter(*item)]
    for entry in params:
        if isinstance(entry, ParamFile):
            out += ["--params-file", str(params_file(entry, context))]
        elif isinstance(entry, ParamRule):
            out += ["-p", parameter_rule(entry, context)]
        else:
            values = evaluate_params([entry], context)[0]
            assert isinstance(values, dict)
            # nested names dotted, as launch_ros writes them
            text = yaml.safe_dump({key: {"ros__parameters": values}}, default_flow_style=False)
            path = context.write_scratch_file("launch_params_", ".yaml", text)
            files[str(path)] = text
            out += ["--params-file", str(path)]
    for src, dst in context.scope.remaps:
        out += ["-r", f"{src}:={dst}"]
    for src_value, dst_value in remaps:
        out += ["-r", f"{perform(src_value, context)}:={perform(dst_value, context)}"]
    return out, files
