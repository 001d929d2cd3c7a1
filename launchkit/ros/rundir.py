"""The user's runtime folder, where the shared router keeps its lock, state and log files.

``$XDG_RUNTIME_DIR/launchkit`` when the session has one (``/run/user/UID``: private, cleared
at logout), else ``/tmp/launchkit-UID``. Either must be a real folder owned by this user and
closed to others; anything else (a symlink planted by another user, loose permissions) is
refused rather than trusted.
"""

from __future__ import annotations

import fcntl
import os
import stat
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from launchkit.errors import RuntimeLaunchError


class RunDirError(RuntimeLaunchError):
    """The runtime folder is unsafe or cannot be made."""


def runtime_dir() -> Path:
    """The user's launchkit runtime folder, created (mode 0700) if needed."""
    base = os.environ.get("XDG_RUNTIME_DIR", "")
    if base and Path(base).is_dir():
        folder = Path(base) / "launchkit"
    else:
        folder = Path("/tmp") / f"launchkit-{os.getuid()}"
    try:
        folder.mkdir(mode=0o700, exist_ok=True)
        info = os.lstat(folder)
    except OSError as error:
        raise RunDirError(f"cannot make the runtime folder {folder}: {error.strerror}") from None
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid() or info.st_mode & 0o077:
        raise RunDirError(
            f"refusing the runtime folder {folder}: it must be a folder of yours that only "
            "you can read (remove it, or set XDG_RUNTIME_DIR)"
        )
    return folder


def network_namespace() -> str:
    """An id of this process's network namespace (ports are per namespace), "" if unknown."""
    try:
        return str(os.stat("/proc/self/ns/net").st_ino)
    except OSError:
        return ""


def router_file(host: str, port: int, suffix: str) -> Path:
    """The runtime file ``suffix`` (``lock``, ``json``, ``log``) of the router at host:port."""
    namespace = network_namespace()
    tag = f"-net{namespace}" if namespace else ""
    safe_host = "".join(c if c.isalnum() or c in ".-" else "_" for c in host)
    return runtime_dir() / f"router-{safe_host}-{port}{tag}.{suffix}"


@contextmanager
def locked(path: Path, timeout: float, what: str) -> Iterator[None]:
    """Hold an exclusive lock on ``path`` for the ``with`` block; wait at most ``timeout``
    seconds for another holder, then fail naming ``what`` it was doing.

    The file exists only while someone holds it (the holder removes it before letting go), so
    the folder does not fill with one file per port ever used; a waiter that got the lock on
    a file already removed tries again on the new one.
    """
    deadline = time.monotonic() + timeout
    while True:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC | os.O_NOFOLLOW, 0o600)
        try:
            _acquire(fd, deadline, path, timeout, what)
            try:
                current = os.stat(path, follow_symlinks=False).st_ino
            except FileNotFoundError:
                current = -1
            if current == os.fstat(fd).st_ino:
                break
        except BaseException:
            os.close(fd)
            raise
        os.close(fd)  # locked a file its holder had already removed: take the new one
    try:
        yield
    finally:
        try:
            path.unlink(missing_ok=True)
        finally:
            os.close(fd)  # closing releases the lock


def _acquire(fd: int, deadline: float, path: Path, timeout: float, what: str) -> None:
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return
        except BlockingIOError:
            if time.monotonic() > deadline:
                raise RunDirError(
                    f"another launchkit process has been {what} for {timeout:.0f} s "
                    f"(it holds {path})"
                ) from None
            time.sleep(0.02)
