"""Syntax to description: each launch file syntax is a thin layer over the same description.

``launch_loader.py`` picks the frontend by file suffix; ``xml/`` reads XML with lxml, ``yaml/``
YAML through :mod:`launchkit.safe_yaml` (both keep line and column marks), ``python/`` runs
``*.launch.py`` files against stand-ins of ROS's ``launch`` API. The tag parsers in ``tags/``
serve every syntax through the syntax-neutral :class:`base_entity.Entity` and the
:class:`action_parser.ActionParser` they register on.
"""
