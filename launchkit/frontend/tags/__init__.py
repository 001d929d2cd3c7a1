"""Tag parsers: one function per tag, turning an entity of any syntax into its action.

``launch.py`` has the tags of ROS 2's ``launch`` package, ``ros.py`` and ``composition.py``
those of ``launch_ros``. Each module lists its tags in ``TAGS`` and adds them to an
:class:`ActionParser` with ``register``; :func:`standard_parser` is a parser with all of them.
"""

from __future__ import annotations

from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.tags import composition, launch, ros


def standard_parser() -> ActionParser:
    """An action parser that reads every tag launchkit supports."""
    parser = ActionParser()
    for module in (launch, ros, composition):
        module.register(parser)
    return parser


__all__ = ["standard_parser"]
