"""The name of every ``LAUNCHKIT_*`` environment variable, in one place.

=================================  =================================================================
``LAUNCHKIT_LOG_FILE_MB``          a log file of ``launchkit run`` that reaches this size (MB) is
                                   renamed ``NAME.1`` and started again (default 50; 0: never)
``LAUNCHKIT_LOG_RUN_MB``           after a run's log folder holds this much (MB), child output is
                                   no longer logged (default 1000; 0: no limit)
``LAUNCHKIT_LOG_KEEP_RUNS``        how many run folders ``launchkit run`` keeps in the log folder;
                                   older ones are removed when a run starts (default 50; 0: all)
``LAUNCHKIT_ROUTER``               the Zenoh router every node connects to (``tcp/HOST:PORT``,
                                   default ``tcp/127.0.0.1:7447``); ``launchkit run`` sets it for
                                   the processes it starts
``LAUNCHKIT_RUN_TMPDIR``           a private folder of the launch, set by ``launchkit run`` for its
                                   processes: files put there are removed when the launch ends,
                                   even if the launcher is killed
``LAUNCHKIT_SUPERVISOR_SOCKET``    the launcher's child-request socket, set by ``launchkit run``
                                   for its processes (:mod:`launchkit.runtime.supervisor_client`)
``LAUNCHKIT_TIMEOUT_SCALE``        multiplies every wait of the pytest plugin (slow machines)
``LAUNCHKIT_VIEWER_PORT``          the rviz2 stand-in's viewer (HTTP + WebSocket) port when
                                   neither ``--port`` nor its ``port`` parameter is given
=================================  =================================================================

Other variables launchkit reads keep the names ROS gives them (``ROS_DOMAIN_ID``,
``ROS_LOG_DIR``, ``AMENT_PREFIX_PATH``, ``RCUTILS_LOGGING_USE_STDOUT``, ...).
"""

from __future__ import annotations

LOG_FILE_MB = "LAUNCHKIT_LOG_FILE_MB"
LOG_RUN_MB = "LAUNCHKIT_LOG_RUN_MB"
LOG_KEEP_RUNS = "LAUNCHKIT_LOG_KEEP_RUNS"
ROUTER = "LAUNCHKIT_ROUTER"
RUN_TMPDIR = "LAUNCHKIT_RUN_TMPDIR"
SUPERVISOR_SOCKET = "LAUNCHKIT_SUPERVISOR_SOCKET"
TIMEOUT_SCALE = "LAUNCHKIT_TIMEOUT_SCALE"
VIEWER_PORT = "LAUNCHKIT_VIEWER_PORT"
