"""The robot's mesh and texture files, served to the page and to Foxglove clients
(``fetchAsset``).

Only files a robot description names are served: every ``<mesh filename=...>`` and ``<texture
filename=...>`` of a URDF seen on a description topic, plus the images and material files in
the folder of a named mesh (a COLLADA or OBJ mesh loads its textures by relative path). Each
must have a mesh or image file extension. ``package://PKG/path`` resolves through launchkit's
package index (share directories, ``AMENT_PREFIX_PATH``); ``file:///abs/path`` and plain
absolute paths are used as they are. Nothing else on the disk is reachable.

The page fetches ``package://PKG/a/b.dae`` as ``/asset/package/PKG/a/b.dae`` and
``file:///a/b.stl`` as ``/asset/file/a/b.stl``, so that relative texture paths resolve.
"""

from __future__ import annotations

from pathlib import Path
from urllib.parse import unquote, urlsplit

from lxml import etree

from launchkit.errors import LaunchkitError
from launchkit.packages import PackageIndex

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
    """The files the page and Foxglove clients may fetch, by the URI the URDF uses."""

    def __init__(self, packages: PackageIndex | None = None) -> None:
        self._packages = packages
        self._files: set[Path] = set()
        self._folders: set[Path] = set()
        self._seen: set[str] = set()

    def note_description(self, urdf: str) -> None:
        """Allow the files a robot description (the text of a description topic) names."""
        for uri in referenced_uris(urdf) - self._seen:
            self._seen.add(uri)
            path = self._path(uri)
            if path is None or path.suffix.lower() not in EXTENSIONS:
                continue
            path = path.resolve()
            self._files.add(path)
            self._folders.add(path.parent)

    def resolve(self, uri: str) -> Path | None:
        """The file behind ``uri``; None when it is not allowed, not found or not a file."""
        path = self._path(uri)
        if path is None:
            return None
        path = path.resolve()
        allowed = path in self._files or (
            path.suffix.lower() in SIBLING_EXTENSIONS
            and any(path.is_relative_to(folder) for folder in self._folders)
        )
        return path if allowed and path.is_file() else None

    def _path(self, uri: str) -> Path | None:
        parts = urlsplit(uri)
        if parts.scheme == "package":
            if self._packages is None:
                self._packages = PackageIndex()
            try:
                share = self._packages.share_dir(parts.netloc)
            except LaunchkitError:
                return None
            return share / unquote(parts.path).lstrip("/")
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
