"""A node process that has its node forked by a fork host (:mod:`launchkit.runtime.fork_host`:
the launcher's node host, or the simulator's plugin host).

    python -I -S fork_trampoline.py SOCKET python -m MODULE ARGS...

Run by the launcher (or the server) in place of ``python -m MODULE ARGS...``: this process is
the one supervised (its pid, its process group, its output streams), and the node itself is
forked from the host at SOCKET with the message layer already imported, writing to this
process's stdout and stderr. Signals sent here go on to the node's process group; this process
ends with the node's exit status (the same signal when the node was killed by one). If the host
cannot be reached or refuses, it runs the command itself (``exec``); if the host dies while the
node runs, it waits for the node's end and exits 1 (the status is lost).

Standard library only, and run with ``-I -S``: it starts in a few milliseconds.
"""

from __future__ import annotations

import array
import json
import os
import select
import signal
import socket
import sys

FORWARDED = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT, signal.SIGUSR1)


def main(argv: list[str]) -> None:
    """Have the host fork ``argv[2:]``, forward signals to it, exit with its status."""
    path, command = argv[1], argv[2:]
    node: list[int] = []
    pending: list[int] = []

    def forward(signum: int, _frame: object) -> None:
        if node:
            try:
                os.killpg(node[0], signum)
            except OSError:
                pass  # it has ended; its status is on its way
        else:
            pending.append(signum)

    for forwarded in FORWARDED:
        signal.signal(forwarded, forward)
    try:
        conn = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        conn.connect(path)
        request = {"argv": command, "cwd": os.getcwd(), "env": dict(os.environ)}
        fds = array.array("i", [0, 1, 2])
        conn.sendmsg([json.dumps(request).encode()], [(socket.SOL_SOCKET, socket.SCM_RIGHTS, fds)])
        reply = _receive(conn)
    except OSError:
        reply = ""
    if not reply.startswith("pid "):
        for forwarded in FORWARDED:
            signal.signal(forwarded, signal.SIG_DFL)
        for signum in pending:  # a stop asked for while the host was busy
            os.kill(os.getpid(), signum)
        os.execv(command[0], command)  # no host: start cold, as if it was never asked
    node.append(int(reply.split()[1]))
    for signum in pending:
        forward(signum, None)
    reply = _receive(conn)
    if reply.startswith("exit "):
        code = int(reply.split()[1])
    else:  # the host died before the node: its status is lost
        _wait_gone(node[0])
        print("fork host gone: the node's exit status is unknown", file=sys.stderr, flush=True)
        code = 1
    if code < 0:
        signal.signal(-code, signal.SIG_DFL)
        os.kill(os.getpid(), -code)
    os._exit(code if code >= 0 else 128 - code)


def _wait_gone(pid: int) -> None:
    """Wait until process ``pid`` (not a child of this one) has ended."""
    try:
        pidfd = os.pidfd_open(pid)
    except OSError:
        return  # gone already
    select.select([pidfd], [], [])


def _receive(conn: socket.socket) -> str:
    """One message from the host ('' at its end; a forwarded signal does not interrupt it)."""
    return conn.recv(256).decode()


if __name__ == "__main__":
    main(sys.argv)
