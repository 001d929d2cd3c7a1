"""``<node>``: a ROS node from a package, with ROS 2's command-line conventions.

The command is ``EXECUTABLE [args] --ros-args [ros_args] -r __node:=NAME -r __ns:=/NS
--params-file FILE ... -r from:=to ...``, so a real ROS 2 executable found through
``AMENT_PREFIX_PATH`` runs unchanged.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from launchkit.description.actions.base import Action
from launchkit.description.actions.executable import ProcessBuilder, ProcessOptions, start
from launchkit.description.actions.parameters import (
    ParamEntry,
    evaluate_params,
    nest,
    typed_value,
)
from launchkit.description.actions.ros_scope import NAMESPACE_CONFIGURATION, join_namespace
from launchkit.description.command_line import split_command
from launchkit.description.process_spec import ProcessSpec
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import Location

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


@dataclass(frozen=True)
class Remap:
    """``<remap from="a" to="b"/>``."""

    src: Value
    dst: Value


class ExecuteNode(Action):
    """Run executable EXEC of package PKG as a ROS node."""

    TAG = "node"
    COMPLETES_LATER = True

    def __init__(
        self,
        pkg: Value | None,
        exec: Value,
        options: ProcessOptions,
        *,
        node_name: Value | None = None,
        namespace: Value | None = None,
        exec_name: Value | None = None,
        args: Value | list[Value] | None = None,
        ros_args: Value | list[Value] | None = None,
        params: list[ParamEntry] | None = None,
        remaps: list[Remap] | None = None,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.pkg = pkg
        self.exec = exec
        self.options = options
        self.node_name = node_name
        self.namespace = namespace
        self.exec_name = exec_name
        self.args = args
        self.ros_args = ros_args
        self.params = params or []
        self.remaps = remaps or []

    def evaluate(self, context: LaunchContext) -> ProcessSpec:
        """The node's process in ``context``."""
        executable = perform(self.exec, context)
        if self.pkg is not None:
            program = context.packages.executable(perform(self.pkg, context), executable)
        else:
            program = [executable]
        argv = program + self._words(self.args, context)
        ros_args, files = self._ros_arguments(context)
        if ros_args:
            argv += ["--ros-args", *ros_args]
        # <node>'s `name` attribute is the ROS node name; the process label is exec_name or
        # the executable's name (as launch_ros does).
        options = ProcessOptions(**{**vars(self.options), "name": self.exec_name})
        label = os.path.basename(executable)
        spec = ProcessBuilder(options, context, self.location).build(argv, label, is_node=True)
        spec.files = files
        return spec

    def _ros_arguments(self, context: LaunchContext) -> tuple[list[str], dict[str, str]]:
        import yaml  # lazily: most launches never need it

        out: list[str] = []
        files: dict[str, str] = {}
        out += self._words(self.ros_args, context)
        if self.node_name is not None:
            out += ["-r", f"__node:={perform(self.node_name, context)}"]
        namespace = self._namespace(context)
        if namespace:
            out += ["-r", f"__ns:={namespace}"]
        params: dict[str, Any] = {
            name: typed_value(value, None, self.location)
            for name, value in context.scope.global_params
        }
        node_values, node_files = evaluate_params(self.params, context)
        params.update(node_values)
        for global_file in context.scope.params_files:
            out += ["--params-file", global_file]
        if params:
            text = yaml.safe_dump({"/**": {"ros__parameters": nest(params)}}, sort_keys=False)
            path = context.write_scratch_file("params_", ".yaml", text)
            files[str(path)] = text
            out += ["--params-file", str(path)]
        for file in node_files:
            out += ["--params-file", str(file)]
        for src, dst in context.scope.remaps:
            out += ["-r", f"{src}:={dst}"]
        for remap in self.remaps:
            out += ["-r", f"{perform(remap.src, context)}:={perform(remap.dst, context)}"]
        return out, files

    def _words(self, value: Value | list[Value] | None, context: LaunchContext) -> list[str]:
        """``args`` / ``ros_args``: an attribute split like a command line, or (Python's
        ``arguments=[...]``) one argv word per item."""
        if value is None:
            return []
        if isinstance(value, list):
            return [perform(word, context) for word in value]
        return split_command(value, context, self.location)

    def full_name(self, context: LaunchContext) -> str:
        """The node's fully qualified name (its ``name``, else the executable's)."""
        name = perform(self.node_name, context) if self.node_name is not None else ""
        name = name or os.path.basename(perform(self.exec, context))
        return join_namespace(self._namespace(context) or "/", name)

    def _namespace(self, context: LaunchContext) -> str:
        base = context.configurations.get(NAMESPACE_CONFIGURATION, "")
        own = perform(self.namespace, context).strip() if self.namespace is not None else ""
        if not own:
            return join_namespace("", base) if base else ""
        return join_namespace(base, own)

    def children(self) -> Sequence[Action]:
        """The ``on_exit`` actions."""
        return self.options.on_exit_actions

    def execute(self, context: LaunchContext) -> None:
        """Hand the node's process to the runner."""
        start(self, self.evaluate(context), self.options, context)
