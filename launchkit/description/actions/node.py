"""``<node>``: a ROS node from a package, with ROS 2's command-line conventions.

The command is ``EXECUTABLE [args] [--ros-args ROS_ARGS] --ros-args -r __node:=NAME
-r __ns:=/NS [parameters] [-r from:=to ...]`` exactly as launch_ros builds it
(:mod:`launchkit.description.actions.node_arguments`), so a real ROS 2 executable found through
``AMENT_PREFIX_PATH`` runs unchanged and gets the same parameters.
"""

from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action
from launchkit.description.actions.executable import ProcessBuilder, ProcessOptions, start
from launchkit.description.actions.node_arguments import ros_arguments
from launchkit.description.actions.parameters import ParamEntry
from launchkit.description.actions.ros_scope import (
    NAMESPACE_CONFIGURATION,
    join_namespace,
    ros_namespace,
)
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
        if self.ros_args is not None:  # a section of its own, before launch_ros's
            argv += ["--ros-args", *self._words(self.ros_args, context)]
        remaps = [(remap.src, remap.dst) for remap in self.remaps]
        ros, files = ros_arguments(self.node_name, self.namespace, self.params, remaps, context)
        argv += ["--ros-args", *ros]
        # <node>'s `name` attribute is the ROS node name; the process label is exec_name or
        # the executable's name (as launch_ros does).
        options = dataclasses.replace(self.options, name=self.exec_name)
        label = os.path.basename(executable)
        spec = ProcessBuilder(options, context, self.location).build(argv, label, is_node=True)
        spec.files = files
        return spec

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
        own = perform(self.namespace, context).strip() if self.namespace is not None else None
        namespace = ros_namespace(context.configurations.get(NAMESPACE_CONFIGURATION), own)
        return join_namespace(namespace or "/", name)

    def execute(self, context: LaunchContext) -> None:
        """Hand the node's process to the runner."""
        start(self, self.evaluate(context), self.options, context)
