"""Stand-ins for the ROS packages the tutorials use, one subpackage each.

Every subpackage exposes a :class:`launchkit.packages.PythonPackage` named ``PACKAGE``,
registered in the ``launchkit.packages`` entry-point group, whose executables are real nodes on
:mod:`launchkit.ros`.
"""
