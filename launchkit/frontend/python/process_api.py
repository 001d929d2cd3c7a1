"""``launch.actions.ExecuteProcess`` and the process keyword arguments it shares with
``launch_ros.actions.Node``.

A command is a list of words, each one argv item after substitution (an empty word stays an
empty argument, as in ROS); ``shell=True`` joins them with spaces for ``/bin/sh -c``.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from launchkit.description import actions as lk
from launchkit.description.actions.base import Action
from launchkit.description.actions.executable import ProcessBuilder
from launchkit.description.conditions import Condition
from launchkit.description.launch_context import LaunchContext
from launchkit.description.process_spec import ProcessSpec
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import LaunchFileError
from launchkit.frontend.python.event_api import CallOnEvent
from launchkit.frontend.python.values import argv_text, here, optional_value, to_value


def words_of(cmd: Any) -> list[Value]:
    """A ``cmd`` / ``arguments`` list as one value per argv word (a plain string is one word)."""
    if isinstance(cmd, str) or not isinstance(cmd, Iterable):
        return [to_value(cmd)]
    return [to_value(word) for word in cmd]


def perform_words(words: Sequence[Value], context: LaunchContext) -> list[str]:
    """The argv words in ``context``."""
    return [perform(word, context) for word in words]


def _actions(on_exit: Any) -> list[Action]:
    items = list(on_exit) if isinstance(on_exit, Iterable) else [on_exit]
    for item in items:
        if not isinstance(item, Action):
            raise LaunchFileError(
                f"on_exit holds a {type(item).__name__}",
                here(),
                expected="launch actions, e.g. on_exit=[LogInfo(msg='...'), Shutdown()], or a "
                "function of the event and the context",
            )
    return items


def process_options(
    *,
    cwd: Any = None,
    name: Any = None,
    prefix: Any = None,
    output: Any = None,
    shell: bool | None = None,
    emulate_tty: bool | None = None,
    sigterm_timeout: Any = None,
    sigkill_timeout: Any = None,
    respawn: Any = None,
    respawn_delay: Any = None,
    respawn_max_retries: Any = None,
    additional_env: Mapping[Any, Any] | None = None,
    env: Mapping[Any, Any] | None = None,
    on_exit: Any = None,
    log_cmd: bool = False,
    cached_output: bool = False,
) -> lk.ProcessOptions:
    """The process keyword arguments ExecuteProcess and Node share, as ProcessOptions.

    ``on_exit=Shutdown()`` (alone or in a list) is launchkit's ``on_exit="shutdown"``: the
    launch's exit status tells the process's failure; any other actions run each time the
    process exits, as an OnProcessExit handler would, and so does a function, called with the
    ProcessExited event and the context (what it returns runs). ``env=`` is the whole environment
    (plus ``additional_env``), as in ROS."""
    del log_cmd, cached_output  # accepted for compatibility; launchkit always logs the command
    exit_value: Value | None = None
    exit_actions: list[Action] = []
    if isinstance(on_exit, str):
        exit_value = to_value(on_exit)
    elif callable(on_exit) and not isinstance(on_exit, Action):  # f(event, context), as ROS
        exit_actions.append(CallOnEvent(on_exit, "on_exit"))
    elif on_exit is not None:
        for action in _actions(on_exit):
            if isinstance(action, lk.Shutdown) and action.condition is None:
                exit_value = to_value("shutdown")
            else:
                exit_actions.append(action)
    environment = [
        (to_value(k), to_value(v)) for k, v in {**(env or {}), **(additional_env or {})}.items()
    ]
    return lk.ProcessOptions(
        cwd=optional_value(cwd),
        name=optional_value(name),
        launch_prefix=optional_value(prefix),
        output=optional_value(output),
        shell=optional_value(shell),
        emulate_tty=optional_value(emulate_tty),
        sigterm_timeout=optional_value(sigterm_timeout),
        sigkill_timeout=optional_value(sigkill_timeout),
        respawn=optional_value(respawn),
        respawn_delay=optional_value(respawn_delay),
        respawn_max_retries=optional_value(respawn_max_retries),
        on_exit=exit_value,
        env=environment,
        on_exit_actions=exit_actions,
        clean_env=env is not None,
    )


class ExecuteProcess(lk.ExecuteProcess):
    """``launch.actions.ExecuteProcess``: ``cmd`` is a list of words, each one argv item."""

    def __init__(
        self, *, cmd: Iterable[Any], condition: Condition | None = None, **options: Any
    ) -> None:
        self.words = words_of(cmd)
        super().__init__(argv_text(self.words), process_options(**options), here(), condition)

    def evaluate(self, context: LaunchContext) -> ProcessSpec:
        """The process, its argv built word by word."""
        builder = ProcessBuilder(self.options, context, self.location)
        words = perform_words(self.words, context)
        program = words[0] if words else ""
        if builder.flag(self.options.shell, False, "shell"):
            prefix = builder.launch_prefix(program or "sh")
            text = " ".join(prefix + words)
            return builder.build(["/bin/sh", "-c", text], program or "sh", False, True)
        return builder.build(words, program, False)


class ExecuteLocal(ExecuteProcess):
    """``launch.actions.ExecuteLocal``: an ExecuteProcess given as a process description
    (``launch.descriptions.Executable``)."""

    def __init__(
        self,
        *,
        process_description: Executable,
        condition: Condition | None = None,
        **options: Any,
    ) -> None:
        super().__init__(
            cmd=process_description.cmd,
            condition=condition,
            **process_description.options,
            **options,
        )


class Executable:
    """``launch.descriptions.Executable``: a command and where and how it runs."""

    def __init__(self, *, cmd: Iterable[Any], **options: Any) -> None:
        self.cmd = list(cmd)
        self.options = options
