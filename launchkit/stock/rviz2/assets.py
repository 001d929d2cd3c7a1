"""The robot's mesh and texture files, served to the page and to Foxglove clients
(``fetchAsset``).

A file is served when two things hold. A robot description names it: a ``<mesh filename=...>``
or ``<texture filename=...>`` of a URDF seen on a description topic, or an image or material
file in the folder of a named mesh (a COLLADA or OBJ mesh loads its textures by relative path),
with a mesh or image file extension. And it lies, once every symbolic link is resolved, in a
folder the viewer trusts: a package's share folder (launchkit's package index, with
``AMENT_PREFIX_PATH``), a folder given at start (``--asset-folder`` / ``asset_folders``), or the
folder of a mesh the viewer's own ``robot_description`` parameter names. A description topic
is the network's to write: a description naming ``file:///etc/...`` or another user's files
makes nothing outside those folders reachable. ``package://PKG/path`` resolves in PKG's share
folder (and must stay in it); ``file:///abs/path`` and plain absolute paths are used as they
are.

The page fetches ``package://PKG/a/b.dae`` as ``/asset/package/PKG/a/b.dae`` and
``file:///a/b.stl`` as ``/asset/file/a/b.stl``, so that relative texture paths resolve.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from urllib.parse import unquote, urlsplit

from lxml import etree

from launchkit.errors import LaunchkitError
from launchkit.packages import PackageIndex, is_file

#: File types a URDF visual can name (meshes, their materials and textures).
EXTENSIONS = {
    ".stl",
    ".dae",
    ".obj",
    ".mtl",
    ".gltf",
    ".glb",
    ".png",
    ".jpg",
    ".jpeg",
    ".tga",
    ".bmp",
    ".webp",
}

CONTENT_TYPES = {
    ".stl": "model/stl",
    ".dae": "model/vnd.collada+xml",
    ".obj": "model/obj",
    ".mtl": "text/plain",
    ".gltf": "model/gltf+json",
    ".glb": "model/gltf-binary",
    ".png": "image/png",
    ".jpg": "image/jpeg",
    ".jpeg": "image/jpeg",
    ".tga": "image/x-tga",
    ".bmp": "image/bmp",
    ".webp": "image/webp",
}


def referenced_uris(urdf: str) -> set[str]:
    """The mesh and texture file names a URDF's links use; empty for text that is not a URDF."""
    if "<robot" not in urdf:
        return set()
    try:
        parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
        root = etree.fromstring(urdf.encode(), parser)
    except (etree.XMLSyntaxError, ValueError):
        return set()
    found = set()
    for element in root.iter("mesh", "texture"):
        name = element.get("filename")
        if name:
            found.add(name.strip())
    return found


#: Files a mesh may load from its own folder.
SIBLING_EXTENSIONS = EXTENSIONS - {".stl", ".dae", ".obj", ".gltf", ".glb"}


def uri_of_path(path: str) -> str | None:
    """The URI behind a page's asset path (``package/PKG/a.stl`` -> ``package://PKG/a.stl``)."""
    kind, _, rest = path.partition("/")
    if kind == "package" and rest:
        return f"package://{rest}"
    if kind == "file" and rest:
        return f"file:///{rest}"
    return None


class AssetCatalog:
    """The files the page and Foxglove clients may fetch, by the URI the URDF uses, inside
    the package share folders and the trusted ``folders``."""

    def __init__(self, packages: PackageIndex | None = None, folders: Iterable[Path] = ()) -> None:
        self._packages = packages
        self._given = [Path(folder).resolve() for folder in folders]
        self._roots: list[Path] | None = None
        self._files: set[Path] = set()
        self._folders: set[Path] = set()
        self._seen: set[str] = set()

    def trust_description(self, urdf: str) -> None:
        """Trust the folders of the meshes a description given at start names (the viewer's
        own ``robot_description`` parameter), and allow its files."""
        for uri in referenced_uris(urdf):
            path = _resolved(self._path(uri))
            if path is not None:
                self._given.append(path.parent)
        self._roots = None
        self.note_description(urdf)

    def note_description(self, urdf: str) -> None:
        """Allow the files a robot description (the text of a description topic) names."""
        for uri in referenced_uris(urdf) - self._seen:
            self._seen.add(uri)
            path = _resolved(self._path(uri))
            if path is None or path.suffix.lower() not in EXTENSIONS:
                continue
            self._files.add(path)
            self._folders.add(path.parent)

    def resolve(self, uri: str) -> Path | None:
        """The file behind ``uri``; None when it is not allowed, not found or not a file."""
        path = _resolved(self._path(uri))
        if path is None:
            return None
        named = path in self._files or (
            path.suffix.lower() in SIBLING_EXTENSIONS
            and any(path.is_relative_to(folder) for folder in self._folders)
        )
        if not named or not self._trusted(uri, path):
            return None
        return path if is_file(path) else None

    def _trusted(self, uri: str, path: Path) -> bool:
        """Whether ``path`` (resolved) lies where ``uri`` may lead."""
        parts = urlsplit(uri)
        if parts.scheme == "package":
            share = self._share(parts.netloc)
            return share is not None and path.is_relative_to(share)
        return any(path.is_relative_to(root) for root in self._trusted_roots())

    def _trusted_roots(self) -> list[Path]:
        if self._roots is None:
            index = self._index()
            shares = [self._share(name) for name in index.names()]
            self._roots = [*self._given, *(share for share in shares if share is not None)]
        return self._roots

    def _index(self) -> PackageIndex:
        if self._packages is None:
            self._packages = PackageIndex()
        return self._packages

    def _share(self, package: str) -> Path | None:
        try:
            return self._index().share_dir(package).resolve()
        except (LaunchkitError, OSError):
            return None

    def _path(self, uri: str) -> Path | None:
        parts = urlsplit(uri)
        if parts.scheme == "package":
            share = self._share(parts.netloc)
            return None if share is None else share / unquote(parts.path).lstrip("/")
        if parts.scheme == "file":
            return Path(unquote(parts.path))
        if parts.scheme == "" and uri.startswith("/"):
            return Path(uri)
        return None

    def read(self, uri: str) -> tuple[bytes, str] | None:
        """The bytes and content type of an allowed asset; None otherwise."""
        path = self.resolve(uri)
        if path is None:
            return None
        try:
            data = path.read_bytes()
        except OSError:
            return None
        return data, CONTENT_TYPES.get(path.suffix.lower(), "application/octet-stream")


def _resolved(path: Path | None) -> Path | None:
    """``path`` with every symbolic link resolved; None for a path that cannot be one (a NUL
    byte, a link loop, a name too long)."""
    if path is None:
        return None
    try:
        return path.resolve()
    except (OSError, RuntimeError, ValueError):
        return None
