"""``<executable>``: run a command as a supervised process (and the options ``<node>`` shares)."""

from __future__ import annotations

import os
import re
import shlex
import shutil
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action, typed_bool, typed_float, typed_int
from launchkit.description.command_line import split_command
from launchkit.description.events import EventHandler, ProcessExited, action_matcher
from launchkit.description.process_spec import OUTPUT_MODES, ProcessSpec
from launchkit.description.substitutions.base import Value, perform
from launchkit.description.truth import condition_value
from launchkit.errors import Location, RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext

ON_EXIT = ("shutdown",)


@dataclass
class ProcessOptions:
    """The attributes ``<executable>`` and ``<node>`` share, unevaluated (None = not given)."""

    cwd: Value | None = None
    name: Value | None = None
    launch_prefix: Value | None = None
    output: Value | None = None
    shell: Value | None = None
    emulate_tty: Value | None = None
    sigterm_timeout: Value | None = None
    sigkill_timeout: Value | None = None
    respawn: Value | None = None
    respawn_delay: Value | None = None
    respawn_max_retries: Value | None = None
    on_exit: Value | None = None
    env: list[tuple[Value, Value]] = field(default_factory=list)
    #: Actions to run each time the process exits (Python's ``on_exit=[...]``).
    on_exit_actions: list[Action] = field(default_factory=list)
    #: Start from an empty environment plus ``env`` (Python's ``env=``), not the launch's.
    clean_env: bool = False


class ProcessBuilder:
    """Evaluates :class:`ProcessOptions` in a context into the parts of a ProcessSpec."""

    def __init__(self, options: ProcessOptions, context: LaunchContext, location: Location | None):
        self.options = options
        self.context = context
        self.location = location

    def text(self, value: Value | None, default: str | None = None) -> str | None:
        """An optional attribute performed, or ``default``."""
        return default if value is None else perform(value, self.context)

    def number(self, value: Value | None, config: str, default: float, what: str) -> float:
        """A float attribute, else the launch configuration ``config``, else ``default``."""
        if value is None:
            configured = self.context.configurations.get(config)
            if configured is None:
                return default
            try:
                return float(configured)
            except ValueError:
                raise RuntimeLaunchError(
                    f"launch configuration '{config}' is {configured!r}",
                    self.location,
                    expected="a number",
                ) from None
        return typed_float(value, self.context, what, self.location)

    def flag(self, value: Value | None, default: bool, what: str) -> bool:
        """A boolean attribute, else ``default``."""
        return default if value is None else typed_bool(value, self.context, what, self.location)

    def launch_prefix(self, program: str) -> list[str]:
        """The launch prefix words: the attribute, else the configuration (with its filter)."""
        if self.options.launch_prefix is not None:
            return shlex.split(perform(self.options.launch_prefix, self.context))
        configured = self.context.configurations.get("launch-prefix", "")
        if not configured:
            return []
        pattern = self.context.configurations.get("launch-prefix-filter")
        if pattern and not re.search(pattern, os.path.basename(program)):
            return []
        return shlex.split(configured)

    def build(
        self, words: list[str], default_name: str, is_node: bool, prefixed: bool = False
    ) -> ProcessSpec:
        """The evaluated process: command, environment, output and lifecycle settings
        (``prefixed``: the launch prefix is already in ``words``)."""
        o, ctx = self.options, self.context
        if not words:
            raise RuntimeLaunchError("the command is empty", self.location, expected="a program")
        env = {} if o.clean_env else dict(ctx.environment)
        for name, value in o.env:
            env[perform(name, ctx)] = perform(value, ctx)
        stand_in = None if is_node or prefixed else self._stand_in(words[0], env)
        if stand_in is not None:
            words = stand_in + words[1:]
            is_node = True  # launchkit's stand-ins are ROS nodes: they need the router
        cmd = words if prefixed else self.launch_prefix(words[0]) + words
        env.setdefault("PYTHONUNBUFFERED", "1")
        output = self._output()
        emulate_default = condition_value(ctx.configurations.get("emulate_tty", "false")) or False
        on_exit = self.text(o.on_exit)
        if on_exit is not None and on_exit not in ON_EXIT:
            raise RuntimeLaunchError(
                f"on_exit is {on_exit!r}", self.location, expected='on_exit="shutdown"'
            )
        spec = ProcessSpec(
            name=self.text(o.name) or os.path.basename(default_name),
            cmd=cmd,
            env=env,
            cwd=self.text(o.cwd),
            output=output,
            emulate_tty=self.flag(o.emulate_tty, emulate_default, "emulate_tty"),
            sigterm_timeout=self.number(
                o.sigterm_timeout, "sigterm_timeout", 5.0, "sigterm_timeout"
            ),
            sigkill_timeout=self.number(
                o.sigkill_timeout, "sigkill_timeout", 5.0, "sigkill_timeout"
            ),
            respawn=self.flag(o.respawn, False, "respawn"),
            respawn_delay=self.number(o.respawn_delay, "", 0.0, "respawn_delay"),
            respawn_max_retries=-1
            if o.respawn_max_retries is None
            else typed_int(o.respawn_max_retries, ctx, "respawn_max_retries", self.location),
            on_exit_shutdown=on_exit == "shutdown",
            is_node=is_node,
            location=self.location,
        )
        spec.env_changes = _changes(ctx.initial_environment, env)
        spec.machine = ctx.scope.machine
        return spec

    def _stand_in(self, program: str, env: dict[str, str]) -> list[str] | None:
        """launchkit's stand-in for a program called by bare name that is not installed
        (``gazebo``, ``gzclient``, ``rviz2``), said on the console; None otherwise."""
        if "/" in program or shutil.which(program, path=env.get("PATH", os.defpath)):
            return None
        found = self.context.packages.stand_in(program)
        if found is None:
            return None
        package, argv = found
        self.context.log(
            "INFO",
            f"'{program}' is not installed: running launchkit's stand-in from package "
            f"'{package}' in its place",
        )
        return argv

    def _output(self) -> str:
        override = self.context.initial_environment.get("OVERRIDE_LAUNCH_PROCESS_OUTPUT")
        output = override or self.text(self.options.output, "log") or "log"
        if output not in OUTPUT_MODES:
            raise RuntimeLaunchError(
                f"output is {output!r}", self.location, expected="one of " + ", ".join(OUTPUT_MODES)
            )
        return output


def _changes(before: dict[str, str], after: dict[str, str]) -> dict[str, str | None]:
    changed: dict[str, str | None] = {k: v for k, v in after.items() if before.get(k) != v}
    changed.update({k: None for k in before if k not in after})
    return changed


def start(
    action: Action, spec: ProcessSpec, options: ProcessOptions, context: LaunchContext
) -> None:
    """Hand ``spec`` to the runner as started by ``action``, with its ``on_exit`` actions
    registered as a handler of its exits."""
    spec.origin = action
    if options.on_exit_actions:
        handler = EventHandler(
            matcher=action_matcher(ProcessExited, action),
            entities=options.on_exit_actions,
            description=f"on_exit of {spec.name}",
        )
        context.register_handler(handler)
    context.runner.start_process(spec)


class ExecuteProcess(Action):
    """``<executable cmd="...">``: one supervised process."""

    TAG = "executable"
    COMPLETES_LATER = True

    def __init__(
        self,
        cmd: Value,
        options: ProcessOptions,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.cmd = cmd
        self.options = options

    def evaluate(self, context: LaunchContext) -> ProcessSpec:
        """The process this tag describes, in ``context``."""
        builder = ProcessBuilder(self.options, context, self.location)
        if builder.flag(self.options.shell, False, "shell"):
            # The command text goes to the shell as written, quoting intact.
            text = perform(self.cmd, context).strip()
            words = split_command(self.cmd, context, self.location)
            prefix = builder.launch_prefix(words[0] if words else "sh")
            if prefix:
                text = shlex.join(prefix) + " " + text
            return builder.build(["/bin/sh", "-c", text], words[0] if words else "sh", False, True)
        words = split_command(self.cmd, context, self.location)
        return builder.build(words, words[0] if words else "", False)

    def children(self) -> Sequence[Action]:
        """The ``on_exit`` actions."""
        return self.options.on_exit_actions

    def execute(self, context: LaunchContext) -> None:
        """Hand the process to the runner."""
        start(self, self.evaluate(context), self.options, context)
