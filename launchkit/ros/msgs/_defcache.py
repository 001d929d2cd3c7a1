"""ROS 2 Jazzy's message definitions, from a per-user cache or, once per rosbags version, rosbags.

Importing rosbags' Jazzy store module imports every older distribution's store too (each one is
built on the one before: ~300 dataclasses), where a process usually needs a handful of types.
So the first process reads the definitions (``FIELDDEFS``) out of that module and writes them as
JSON to ``rosbags-<version>-ros2_jazzy.json`` in the cache folder; later processes read that file
and register only the types they use (:mod:`launchkit.ros.msgs._typestore`).

The folder is ``$LAUNCHKIT_CACHE_DIR``, else ``$XDG_CACHE_HOME/launchkit``, else
``~/.cache/launchkit``. The file is written atomically (a temporary file renamed over it); one
that cannot be read, is malformed, or names another rosbags version or distribution is ignored
and rewritten; a folder that cannot be written means no cache, not an error.
"""

from __future__ import annotations

import json
import os
import tempfile
from importlib import import_module
from pathlib import Path
from typing import Any

import rosbags.typesys.store as store

from launchkit.envvars import CACHE_DIR

DISTRO = "ros2_jazzy"
FORMAT = 1  # bumped when the file's layout changes
_INFO = ".dist-info"
_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4

Definitions = dict[str, tuple[list[tuple[str, str, Any]], list[tuple[str, Any]]]]


def definitions() -> Definitions:
    """Every Jazzy message type's ``(constants, fields)``, as rosbags' store has them."""
    version = rosbags_version()
    path = cache_file(version)
    if path is not None:
        cached = _read(path, version)
        if cached is not None:
            return cached
    found = _from_store()
    if path is not None:
        _write(path, version, found)
    return found


def cache_dir() -> Path:
    """The folder launchkit keeps its per-user cache in (see the module docstring)."""
    explicit = os.environ.get(CACHE_DIR)
    if explicit:
        return Path(explicit)
    xdg = os.environ.get("XDG_CACHE_HOME")
    if xdg and os.path.isabs(xdg):
        return Path(xdg) / "launchkit"
    return Path.home() / ".cache" / "launchkit"


def cache_file(version: str) -> Path | None:
    """The cache file of this rosbags version (None: no home folder to put it in)."""
    try:
        return cache_dir() / f"rosbags-{version}-{DISTRO}.json"
    except RuntimeError:  # Path.home() without HOME or a passwd entry
        return None


def rosbags_version() -> str:
    """The installed rosbags' version, from its ``.dist-info`` folder beside the package.

    ``importlib.metadata`` would take 50-150 ms on a busy machine to search every path entry;
    the folder name says the same for a pip install.
    """
    site = Path(store.__file__).parents[2]
    try:
        found = [n for n in os.listdir(site) if n.startswith("rosbags-") and n.endswith(_INFO)]
    except OSError:
        found = []
    if len(found) == 1:
        return found[0][len("rosbags-") : -len(_INFO)]
    from importlib import metadata  # only here: importing it is most of its cost

    return metadata.version("rosbags")


def _from_store() -> Definitions:
    module = import_module(f"rosbags.typesys.stores.{DISTRO}")
    return _checked(json.loads(json.dumps(module.FIELDDEFS)))


def _read(path: Path, version: str) -> Definitions | None:
    try:
        data = json.loads(path.read_bytes())
        if data.get("format") != FORMAT or data.get("rosbags") != version:
            return None
        if data.get("distro") != DISTRO:
            return None
        return _checked(data["types"])
    except (OSError, ValueError, TypeError, KeyError, AttributeError):
        return None


def _write(path: Path, version: str, defs: Definitions) -> None:
    text = json.dumps(
        {"format": FORMAT, "rosbags": version, "distro": DISTRO, "types": defs},
        separators=(",", ":"),
    )
    tmp = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            out.write(text)
        os.replace(tmp, path)
        tmp = None
    except OSError:  # a read-only home, a full disk, ...: run without the cache, silently
        pass
    finally:
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass


def _checked(types: Any) -> Definitions:
    """``types`` decoded from JSON, checked field by field, lists turned back into tuples
    where rosbags has tuples; ValueError for anything else (a damaged or foreign file)."""
    if not isinstance(types, dict) or not types:
        raise ValueError("no types")
    out: Definitions = {}
    for name, entry in types.items():
        consts, fields = _pair(entry)
        if not isinstance(consts, list) or not isinstance(fields, list):
            raise ValueError(name)
        out[name] = (
            [_constant(c) for c in consts],
            [(_str(f[0]), _desc(f[1])) for f in map(_pair, fields)],
        )
    for _, fields in out.values():
        for _, desc in fields:
            _refs_known(desc, out)
    return out


def _pair(value: Any) -> tuple[Any, Any]:
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise ValueError(value)
    return value[0], value[1]


def _str(value: Any) -> str:
    if not isinstance(value, str):
        raise ValueError(value)
    return value


def _int(value: Any) -> int:
    if not isinstance(value, int) or isinstance(value, bool):
        raise ValueError(value)
    return value


def _constant(value: Any) -> tuple[str, str, Any]:
    if not isinstance(value, list) or len(value) != 3:
        raise ValueError(value)
    name, typ, const = value
    if not isinstance(const, (int, float, str)):
        raise ValueError(value)
    return _str(name), _str(typ), const


def _desc(value: Any) -> Any:
    kind, detail = _pair(value)
    if kind == _BASE:
        base, bound = _pair(detail)
        return (_BASE, (_str(base), _int(bound)))
    if kind == _NAME:
        return (_NAME, _str(detail))
    if kind in (_ARRAY, _SEQUENCE):
        sub, length = _pair(detail)
        return (kind, (_desc(sub), _int(length)))
    raise ValueError(value)


def _refs_known(desc: Any, types: Definitions) -> None:
    kind, detail = desc
    if kind == _NAME and detail not in types:
        raise ValueError(f"unknown type {detail!r}")
    if kind in (_ARRAY, _SEQUENCE):
        _refs_known(detail[0], types)
