"""The YAML frontend: ROS's YAML launch spelling (``launch_yaml``) read with line and column
marks, safely (``document.py``), into the entities every tag parser reads (``entity.py``)."""
