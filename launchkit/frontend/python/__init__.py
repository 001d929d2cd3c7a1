"""Python launch files (``*.launch.py``) written against ROS 2's ``launch`` / ``launch_ros`` API.

launchkit does not ship ROS's launch engine. Instead it runs the file's
``generate_launch_description()`` with small stand-in modules named ``launch``,
``launch.actions``, ``launch_ros.actions``, ... whose classes build launchkit's own description
objects, so an included ``gazebo.launch.py`` runs through the same supervisor, checks and
errors as XML. ``modules.py`` lists every name provided (actions in ``launch_api.py``,
``process_api.py``, ``ros_api.py``; substitutions in ``launch_substitutions.py``; conditions
in ``conditions_api.py``; events in ``event_api.py``; ``launch.utilities`` in
``utilities_api.py`` and ``type_utils_api.py``); any other name is a clear error naming the
file and line.
"""

from __future__ import annotations

from launchkit.frontend.python.loader import load_python_launch

__all__ = ["load_python_launch"]
