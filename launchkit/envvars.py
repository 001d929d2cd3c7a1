"""The name of every ``LAUNCHKIT_*`` environment variable, in one place.

====================================  ==============================================================
``LAUNCHKIT_AGENT_KEY``               the key file shared by ``launchkit agent`` and the launchers
                                      that use it (default ``~/.config/launchkit/agent.key``)
``LAUNCHKIT_AGENT_TIMEOUT``           seconds a launch waits for an agent to appear (default 30)
``LAUNCHKIT_CACHE_DIR``               the folder of launchkit's per-user cache (the ROS message
                                      definitions read from rosbags, per rosbags version); default
                                      ``$XDG_CACHE_HOME/launchkit``, else ``~/.cache/launchkit``
``LAUNCHKIT_LOCKSTEP``                ``1``: the process's ROS contexts take part in the launch's
                                      lockstep simulated clock (set by ``launchkit run
                                      --lockstep``; :mod:`launchkit.ros.lockstep`)
``LAUNCHKIT_LOG_FILE_MB``             a log file of ``launchkit run`` that reaches this size (MB) is
                                      renamed ``NAME.1`` and started again (default 50; 0: never)
``LAUNCHKIT_LOG_KEEP_RUNS``           how many run folders ``launchkit run`` keeps in the log
                                      folder; older ones are removed when a run starts (default
                                      50; 0: all)
``LAUNCHKIT_LOG_RUN_MB``              after a run's log folder holds this much (MB), child output is
                                      no longer logged (default 1000; 0: no limit)
``LAUNCHKIT_NO_CGROUP``               any value: ``launchkit run`` makes no cgroup for its
                                      processes and relies on being their subreaper alone (see
                                      ``launchkit/runtime/containment.py``)
``LAUNCHKIT_RCLPY``                   which rclpy the processes launchkit starts get: ``launchkit``
                                      (its own, the face folder first on ``PYTHONPATH``) or ``ros``
                                      (the real one); unset, a sourced ROS 2 install's when there
                                      is one (``ROS_DISTRO`` and an ``rclpy`` in an
                                      ``AMENT_PREFIX_PATH`` prefix), else launchkit's
``LAUNCHKIT_REMOTE_GRACE``            seconds an agent keeps a launch's processes once it lost the
                                      launcher (killed, or the link cut; default 10)
``LAUNCHKIT_ROUTER``                  the Zenoh router every node connects to (``tcp/HOST:PORT``,
                                      default ``tcp/127.0.0.1:7447``); ``launchkit run`` sets it for
                                      the processes it starts
``LAUNCHKIT_ROUTER_ACCESS``           a JSON5 file with Zenoh's ``access_control`` section
``LAUNCHKIT_ROUTER_AUTOSTART``        ``0``: a process that finds no router at its loopback endpoint
                                      waits for one instead of starting the shared background
                                      router (``launchkit run`` sets it for its processes: the
                                      launch owns its router)
``LAUNCHKIT_ROUTER_CONNECT``          routers of other hosts that every router launchkit hosts
                                      connects to
``LAUNCHKIT_ROUTER_IDLE_TIMEOUT``     seconds the shared background router stays up with nothing
                                      connected (default 300; 0: until ``launchkit router stop``)
``LAUNCHKIT_ROUTER_LISTEN``           more endpoints every router launchkit hosts listens at, for
                                      other hosts (``tls/0.0.0.0:7448``; comma/space-separated)
``LAUNCHKIT_ROUTER_MTLS``             the same folder, and clients must show a certificate too
``LAUNCHKIT_ROUTER_TLS``              a folder with ``ca.pem``, ``cert.pem``, ``key.pem``: TLS for
                                      ``tls/`` endpoints
``LAUNCHKIT_ROUTER_TRUSTED_USERS``    users (names or uids, comma-separated) whose router a process
                                      may join; another user's router is refused otherwise
``LAUNCHKIT_RUN_TMPDIR``              a private folder of the launch, set by ``launchkit run`` for
                                      its processes: files put there are removed when the launch
                                      ends, even if the launcher is killed
``LAUNCHKIT_STANDINS``               where launchkit's stand-ins for ROS packages (rviz2,
                                      robot_state_publisher, gazebo_ros, ...) come: ``auto``
                                      (default) after installed packages of the same name,
                                      ``prefer`` before them, ``never`` not at all
``LAUNCHKIT_SUPERVISOR_SOCKET``       the launcher's child-request socket, set by ``launchkit run``
                                      for its processes (:mod:`launchkit.runtime.supervisor_client`)
``LAUNCHKIT_TIMEOUT_SCALE``           multiplies every wait of the pytest plugin (slow machines)
``LAUNCHKIT_VIEWER_PORT``             the rviz2 stand-in's viewer (HTTP + WebSocket) port when
                                      neither ``--port`` nor its ``port`` parameter is given
====================================  ==============================================================

Other variables launchkit reads keep the names ROS gives them (``ROS_DOMAIN_ID``,
``ROS_LOG_DIR``, ``AMENT_PREFIX_PATH``, ``RCUTILS_LOGGING_USE_STDOUT``, ...).
"""

from __future__ import annotations

CACHE_DIR = "LAUNCHKIT_CACHE_DIR"
LOCKSTEP = "LAUNCHKIT_LOCKSTEP"
LOG_FILE_MB = "LAUNCHKIT_LOG_FILE_MB"
LOG_RUN_MB = "LAUNCHKIT_LOG_RUN_MB"
LOG_KEEP_RUNS = "LAUNCHKIT_LOG_KEEP_RUNS"
ROUTER = "LAUNCHKIT_ROUTER"
RUN_TMPDIR = "LAUNCHKIT_RUN_TMPDIR"
STANDINS = "LAUNCHKIT_STANDINS"
ROUTER_LISTEN = "LAUNCHKIT_ROUTER_LISTEN"
ROUTER_CONNECT = "LAUNCHKIT_ROUTER_CONNECT"
ROUTER_TLS = "LAUNCHKIT_ROUTER_TLS"
ROUTER_MTLS = "LAUNCHKIT_ROUTER_MTLS"
ROUTER_ACCESS = "LAUNCHKIT_ROUTER_ACCESS"
ROUTER_AUTOSTART = "LAUNCHKIT_ROUTER_AUTOSTART"
ROUTER_IDLE_TIMEOUT = "LAUNCHKIT_ROUTER_IDLE_TIMEOUT"
ROUTER_TRUSTED_USERS = "LAUNCHKIT_ROUTER_TRUSTED_USERS"
SUPERVISOR_SOCKET = "LAUNCHKIT_SUPERVISOR_SOCKET"
AGENT_KEY = "LAUNCHKIT_AGENT_KEY"
NO_CGROUP = "LAUNCHKIT_NO_CGROUP"
AGENT_TIMEOUT = "LAUNCHKIT_AGENT_TIMEOUT"
REMOTE_GRACE = "LAUNCHKIT_REMOTE_GRACE"
RCLPY = "LAUNCHKIT_RCLPY"
TIMEOUT_SCALE = "LAUNCHKIT_TIMEOUT_SCALE"
VIEWER_PORT = "LAUNCHKIT_VIEWER_PORT"

#: Every ``LAUNCHKIT_*`` variable above (the pytest plugin keeps a shell's values of them out of
#: the launches it starts).
NAMES = (
    AGENT_KEY,
    AGENT_TIMEOUT,
    CACHE_DIR,
    LOG_FILE_MB,
    LOG_KEEP_RUNS,
    LOCKSTEP,
    LOG_RUN_MB,
    NO_CGROUP,
    RCLPY,
    REMOTE_GRACE,
    ROUTER,
    ROUTER_ACCESS,
    ROUTER_AUTOSTART,
    ROUTER_CONNECT,
    ROUTER_IDLE_TIMEOUT,
    ROUTER_LISTEN,
    ROUTER_MTLS,
    ROUTER_TLS,
    ROUTER_TRUSTED_USERS,
    RUN_TMPDIR,
    STANDINS,
    SUPERVISOR_SOCKET,
    TIMEOUT_SCALE,
    VIEWER_PORT,
)
