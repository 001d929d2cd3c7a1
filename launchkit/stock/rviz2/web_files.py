"""The HTTP side of the viewer server: the page's files and the robot's meshes.

``GET /`` is the page (``web/index.html``), other paths are files under ``web/`` (the page's
scripts and the vendored libraries, shipped inside the wheel), ``/asset/package/PKG/...`` and
``/asset/file/...`` are the mesh files the robot description names (:mod:`.assets`). Responses
carry an ETag, so a reload revalidates instead of downloading three.js again, and forbid
framing by other sites (a page that framed the viewer could trick clicks into driving).
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote, urlsplit

from websockets.datastructures import Headers
from websockets.http11 import Response

from launchkit.stock.rviz2.assets import AssetCatalog, uri_of_path

WEB_ROOT = Path(__file__).resolve().parent / "web"

CONTENT_TYPES = {
    ".html": "text/html; charset=utf-8",
    ".js": "text/javascript; charset=utf-8",
    ".css": "text/css; charset=utf-8",
    ".png": "image/png",
    ".svg": "image/svg+xml",
    ".ico": "image/x-icon",
}


@dataclass(frozen=True)
class Body:
    """A response body with its type and ETag."""

    data: bytes
    content_type: str
    etag: str


def _body(data: bytes, content_type: str) -> Body:
    return Body(data, content_type, '"' + hashlib.sha1(data).hexdigest() + '"')


class WebFiles:
    """Answers the plain HTTP requests of the viewer server."""

    def __init__(self, catalog: AssetCatalog, root: Path = WEB_ROOT) -> None:
        self.catalog = catalog
        self.root = root
        self._cache: dict[str, Body] = {}

    def static(self, path: str) -> Body | None:
        """A file of the page by URL path (``/`` is ``index.html``); None when there is none."""
        relative = "index.html" if path in ("", "/") else path.lstrip("/")
        cached = self._cache.get(relative)
        if cached is not None:
            return cached
        parts = relative.split("/")
        if any(p in ("", ".", "..") or p.startswith(".") for p in parts):
            return None
        file = self.root.joinpath(*parts)
        content_type = CONTENT_TYPES.get(file.suffix.lower())
        if content_type is None or not file.is_file():
            return None
        body = _body(file.read_bytes(), content_type)
        self._cache[relative] = body
        return body

    def asset(self, path: str) -> Body | None:
        """A mesh or texture by its ``/asset/...`` path; None unless the robot names it."""
        uri = uri_of_path(path)
        found = self.catalog.read(uri) if uri else None
        return None if found is None else _body(*found)

    def respond(self, target: str, if_none_match: str | None) -> Response:
        """The response to ``GET target``."""
        path = unquote(urlsplit(target).path)
        if path.startswith("/asset/"):
            body = self.asset(path[len("/asset/") :])
        else:
            body = self.static(path)
        if body is None:
            return text_response(404, "Not Found", f"{path}: no such file in the viewer\n")
        headers = _headers(body.content_type)
        headers["ETag"] = body.etag
        headers["Cache-Control"] = "no-cache"
        if if_none_match == body.etag:
            return Response(304, "Not Modified", headers, b"")
        headers["Content-Length"] = str(len(body.data))
        return Response(200, "OK", headers, body.data)


def _headers(content_type: str) -> Headers:
    headers = Headers()
    headers["Content-Type"] = content_type
    headers["X-Content-Type-Options"] = "nosniff"
    headers["Content-Security-Policy"] = "frame-ancestors 'none'"
    headers["X-Frame-Options"] = "DENY"
    headers["Referrer-Policy"] = "no-referrer"
    headers["Connection"] = "close"
    return headers


def text_response(status: int, reason: str, text: str) -> Response:
    """A plain-text response (errors and refusals)."""
    body = text.encode()
    headers = _headers("text/plain; charset=utf-8")
    headers["Content-Length"] = str(len(body))
    return Response(status, reason, headers, body)
