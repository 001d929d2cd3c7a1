"""The ROS command line: ``launchkit topic|node|service|param|interface|router``.

A client of :mod:`launchkit.ros` like any other program: nothing in the library imports it.
``main.py`` parses and dispatches; each ``*_commands.py`` is one command family.
"""
