"""The viewer server: the page over HTTP and live data over WebSocket, on one port.

It runs an asyncio event loop in a thread of its own (the ROS node spins in the main thread).
Every request passes the :class:`~.access.AccessPolicy` first: a ``Host`` that is not this
machine's gets 403, and so does a WebSocket handshake from a web page of another site. A
WebSocket then speaks the subprotocol the client asked for: ``launchkit.viewer.v1`` (the
page, :mod:`.page_session`) or Foxglove's (``foxglove.sdk.v1`` / ``foxglove.websocket.v1``,
:mod:`.foxglove_session`).
"""

from __future__ import annotations

import asyncio
import contextlib
import errno
import threading
from collections.abc import Callable
from typing import Any

from websockets.asyncio.server import Server, ServerConnection, serve
from websockets.exceptions import ConnectionClosed
from websockets.http11 import Request, Response
from websockets.typing import Subprotocol

from launchkit.errors import UserError
from launchkit.stock.rviz2 import foxglove_session, page_session
from launchkit.stock.rviz2.access import AccessPolicy
from launchkit.stock.rviz2.foxglove_session import FoxgloveSession, session_id
from launchkit.stock.rviz2.hub import Hub
from launchkit.stock.rviz2.outbox import Frame
from launchkit.stock.rviz2.page_session import PageSession
from launchkit.stock.rviz2.web_files import WebFiles, text_response

SUBPROTOCOLS = [Subprotocol(p) for p in (page_session.SUBPROTOCOL, *foxglove_session.SUBPROTOCOLS)]
#: Seconds between the rate reports a page gets.
RATES_PERIOD = 1.0
#: A write buffer this full makes the sender wait (images are ~2 MB each).
WRITE_LIMIT = 4 * 2**20
STARTUP_TIMEOUT = 10.0
#: What to do about a busy port, in each of the ways the port is chosen.
BUSY_PORT_HINT = (
    "choose another port: viewer_port:=N on the robot's launch (launchkit run "
    "gazebo_and_rviz.launch.xml viewer_port:=8766; 0 picks a free one), else rviz2's "
    "port parameter, its --port N, or $LAUNCHKIT_VIEWER_PORT"
)

Log = Callable[[str], object]


class PortInUse(UserError):
    """The port asked for is taken (by another viewer, or by another program)."""


class ViewerServer:
    """Serves the page and the hub's data on ``address:port`` (``port`` 0: a free one)."""

    def __init__(
        self,
        hub: Hub,
        policy: AccessPolicy,
        port: int,
        hello: dict[str, Any],
        warn: Log | None = None,
        name: str = "launchkit rviz2",
    ) -> None:
        self.hub = hub
        self.policy = policy
        self.address = policy.address
        self.name = name
        self._requested_port = port
        self.session_id = session_id()
        self._hello = {"server": name, "sessionId": self.session_id, **hello}
        self._warn = warn or (lambda text: None)
        self._warned: set[str] = set()
        self.files = WebFiles(hub.catalog)
        self.loop = asyncio.new_event_loop()
        self._server: Server | None = None
        self._thread = threading.Thread(target=self._run, name="viewer-server", daemon=True)
        self._started = threading.Event()
        self._error: BaseException | None = None

    # -- lifecycle (any thread) --------------------------------------------------------------

    def start(self) -> None:
        """Listen; :class:`UserError` when the address or port cannot be used."""
        self._thread.start()
        if not self._started.wait(STARTUP_TIMEOUT):
            raise UserError(
                f"the viewer server did not start within {STARTUP_TIMEOUT:g} s",
                expected="a machine not overloaded",
            )
        if isinstance(self._error, OSError) and self._error.errno == errno.EADDRINUSE:
            raise PortInUse(
                f"cannot serve the viewer on {self.address}:{self._requested_port}: the port is "
                "already in use (another viewer, or another program, listens there)",
                expected="a free port",
                hint=BUSY_PORT_HINT,
            ) from None
        if self._error is not None:
            raise UserError(
                f"cannot serve the viewer on {self.address}:{self._requested_port}: "
                f"{getattr(self._error, 'strerror', None) or self._error}",
                expected="a free port (choose one with the port parameter or --port N)",
            ) from None

    @property
    def port(self) -> int:
        """The port the server listens on."""
        assert self._server is not None
        return int(next(iter(self._server.sockets)).getsockname()[1])

    @property
    def url(self) -> str:
        """The page's address."""
        host = "127.0.0.1" if self.address in ("", "0.0.0.0") else self.address
        host = f"[{host}]" if ":" in host else host
        return f"http://{host}:{self.port}/"

    @property
    def ws_url(self) -> str:
        """The WebSocket address (for Foxglove)."""
        return "ws" + self.url[len("http") :].rstrip("/")

    def post(self, callback: Callable[..., Any], *args: Any) -> None:
        """Run ``callback(*args)`` on the server's loop (from any thread); nothing after close."""
        with contextlib.suppress(RuntimeError):  # the loop is closed: shutting down
            self.loop.call_soon_threadsafe(callback, *args)

    def close(self) -> None:
        """Stop serving and close every connection."""
        if self._thread.is_alive():
            self.post(self._stop)
            self._thread.join(STARTUP_TIMEOUT)

    # -- the loop thread ---------------------------------------------------------------------

    def _run(self) -> None:
        asyncio.set_event_loop(self.loop)
        try:
            self._server = self.loop.run_until_complete(self._listen())
        except (OSError, OverflowError) as error:  # busy port, unknown address, port > 65535
            self._error = error
            self._started.set()
            self.loop.close()
            return
        self._started.set()
        try:
            self.loop.run_forever()
        finally:
            self.loop.run_until_complete(self.loop.shutdown_asyncgens())
            self.loop.close()

    async def _listen(self) -> Server:
        server: Server = await serve(
            self._connection,
            self.address,
            self._requested_port,
            subprotocols=SUBPROTOCOLS,
            process_request=self._process_request,
            compression=None,  # images do not compress, and deflating 2 MB frames costs a core
            write_limit=WRITE_LIMIT,
            max_size=2**20,
            server_header=None,
        )
        return server

    def _stop(self) -> None:
        async def stop() -> None:
            if self._server is not None:
                self._server.close()
                await self._server.wait_closed()
            self.loop.stop()

        self.loop.create_task(stop())

    def _process_request(self, connection: ServerConnection, request: Request) -> Response | None:
        repeated = [
            name
            for name in ("Host", "Upgrade", "Origin", "If-None-Match")
            if len(request.headers.get_all(name)) > 1
        ]
        if repeated:  # which one would a proxy in front of us have checked?
            return text_response(400, "Bad Request", f"more than one {repeated[0]} header\n")
        host = request.headers.get("Host")
        if not self.policy.host_allowed(host):
            self._note(f"refused a request for Host {host!r} (not this machine's address)")
            return text_response(403, "Forbidden", f"Host {host!r} is not served here\n")
        if "websocket" not in request.headers.get("Upgrade", "").lower():
            return self.files.respond(request.path, request.headers.get("If-None-Match"))
        origin = request.headers.get("Origin")
        if not self.policy.origin_allowed(origin, host):
            self._note(
                f"refused a WebSocket from a page of {origin} (only this machine's pages are "
                "accepted; add the origin to the allowed_origins parameter to allow it)"
            )
            return text_response(403, "Forbidden", f"Origin {origin!r} is not allowed\n")
        return None

    def _note(self, text: str) -> None:
        if text not in self._warned:  # each distinct refusal once
            self._warned.add(text)
            self._warn(text)

    async def _connection(self, connection: ServerConnection) -> None:
        protocol = connection.subprotocol
        session: PageSession | FoxgloveSession
        if protocol == page_session.SUBPROTOCOL:
            session = PageSession(self.hub, connection.send, self._hello)
        elif protocol in foxglove_session.SUBPROTOCOLS:
            session = FoxgloveSession(self.hub, connection.send, self.name, self.session_id)
        else:
            await connection.close(
                1002, "no subprotocol: ask for launchkit.viewer.v1 or foxglove.websocket.v1"
            )
            return
        session.start()
        tasks = [asyncio.create_task(_send_all(session))]
        if isinstance(session, PageSession):
            tasks.append(asyncio.create_task(_report_rates(session)))
        try:
            async for frame in connection:
                session.handle(_frame(frame))
        except ConnectionClosed:
            pass
        finally:
            for task in tasks:
                task.cancel()
            session.close()


def _frame(frame: str | bytes) -> Frame:
    return frame if isinstance(frame, str) else bytes(frame)


async def _send_all(session: PageSession | FoxgloveSession) -> None:
    with contextlib.suppress(ConnectionClosed):  # the reading side sees the close too
        await session.outbox.run()


async def _report_rates(session: PageSession) -> None:
    while True:
        await asyncio.sleep(RATES_PERIOD)
        session.send_rates()
