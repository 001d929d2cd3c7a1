"""``<node>``: a ROS node from a package, with ROS 2's command-line conventions.

The command is ``EXECUTABLE [args] --ros-args [ros_args] -r __node:=NAME -r __ns:=/NS
[global parameters] [node parameters] -r from:=to ...``, as launch_ros builds it, so a real
ROS 2 executable found through ``AMENT_PREFIX_PATH`` runs unchanged. Global parameters
(``<set_parameter>``, ``<set_parameters_from_file>``) come first, as ``-p NAME:=VALUE`` and
``--params-file FILE`` in the order they were set; then each of the node's own parameters in
document order: a generated params file for every ``<param name>`` (every dict in Python), the
file itself for every ``<param from>``. The last one to set a name wins.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action
from launchkit.description.actions.executable import ProcessBuilder, ProcessOptions
from launchkit.description.actions.parameters import ParamEntry, evaluate_params
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

    def __init__(
        self,
        pkg: Value | None,
        exec: Value,
        options: ProcessOptions,
        *,
        node_name: Value | None = None,
        namespace: Value | None = None,
        exec_name: Value | None = None,
        args: Value | None = None,
        ros_args: Value | None = None,
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
        argv = program + (split_command(self.args, context, self.location) if self.args else [])
        if self.ros_args is not None:  # its own --ros-args section, as launch_ros writes it
            argv += ["--ros-args", *split_command(self.ros_args, context, self.location)]
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
        if self.node_name is not None:
            out += ["-r", f"__node:={perform(self.node_name, context)}"]
        namespace = self._namespace(context)
        if namespace:
            out += ["-r", f"__ns:={namespace}"]
        for item in context.scope.global_params:
            if isinstance(item, tuple):
                out += ["-p", f"{item[0]}:={item[1]}"]
            else:
                out += ["--params-file", os.path.abspath(item)]
        node_name = self._params_key(context, namespace)
        for params in evaluate_params(self.params, context):
            if isinstance(params, dict):
                text = yaml.safe_dump(
                    {node_name: {"ros__parameters": params}}, default_flow_style=False
                )
                path = context.write_scratch_file("params_", ".yaml", text)
                files[str(path)] = text
                params = path
            out += ["--params-file", str(params)]
        for src, dst in context.scope.remaps:
            out += ["-r", f"{src}:={dst}"]
        for remap in self.remaps:
            out += ["-r", f"{perform(remap.src, context)}:={perform(remap.dst, context)}"]
        return out, files

    def _params_key(self, context: LaunchContext, namespace: str) -> str:
        """The node key of its generated params files: its full name when both its name and
        namespace are known (as launch_ros writes it), else ``/**``."""
        if self.node_name is None or not namespace:
            return "/**"
        return join_namespace(namespace, perform(self.node_name, context))

    def _namespace(self, context: LaunchContext) -> str:
        base = context.configurations.get(NAMESPACE_CONFIGURATION, "")
        own = perform(self.namespace, context).strip() if self.namespace is not None else ""
        if not own:
            return join_namespace("", base) if base else ""
        return join_namespace(base, own)

    def execute(self, context: LaunchContext) -> None:
        """Hand the node's process to the runner."""
        context.runner.start_process(self.evaluate(context))
