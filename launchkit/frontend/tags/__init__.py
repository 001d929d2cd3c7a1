"""Tag parsers: one function per tag, turning an entity of any syntax into its action.

``launch.py`` has the tags of ROS 2's ``launch`` package, ``ros.py`` and ``composition.py``
those of ``launch_ros``.
Each module lists its tags in ``TAGS`` and adds them to an :class:`ActionParser` with
``register``; :func:`standard_parser` is a parser with all of them, each module imported when
a file first uses one of its tags (``STANDARD_TAGS`` names them without importing them;
tests/engine/test_frontend_seams.py checks it against each module's ``TAGS``).
"""

from __future__ import annotations

from launchkit.frontend.action_parser import ActionParser

#: Tag module -> the tags it reads (its ``TAGS``), so a launch imports only the ones it uses.
STANDARD_TAGS: dict[str, tuple[str, ...]] = {
    "launchkit.frontend.tags.launch": (
        "arg",
        "let",
        "group",
        "reset",
        "include",
        "executable",
        "timer",
        "set_env",
        "unset_env",
        "append_env",
        "reset_env",
        "log",
        "shutdown",
    ),
    "launchkit.frontend.tags.ros": (
        "node",
        "push_ros_namespace",
        "push-ros-namespace",
        "set_parameter",
        "set_parameters_from_file",
        "set_remap",
        "set_use_sim_time",
    ),
    "launchkit.frontend.tags.composition": ("node_container", "load_composable_node"),
}


def standard_parser() -> ActionParser:
    """An action parser that reads every tag launchkit supports."""
    parser = ActionParser()
    for module, names in STANDARD_TAGS.items():
        parser.register_module(module, names)
    return parser


__all__ = ["standard_parser"]
