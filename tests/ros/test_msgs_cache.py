"""The cache of Jazzy's message definitions (``launchkit/ros/msgs/_defcache.py``).

Each case runs fresh Python processes, as a user's commands are: the first one reads rosbags'
store and writes the cache, later ones read the cache and never import rosbags' store modules;
a damaged or foreign cache is ignored and rewritten; a cache folder that cannot be written
changes nothing but the speed. Every process also encodes an Odometry and a service request,
so a cache that loses anything shows up as different bytes or hashes.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path
from typing import Any

import pytest

from launchkit.ros.msgs._defcache import cache_dir

STORE = "rosbags.typesys.stores.ros2_jazzy"
PROBE = f"""
import json, sys
from launchkit.ros.msgs import get_message, get_service, serialize, type_hash, type_names
odom = get_message("nav_msgs/msg/Odometry")()
odom.pose.covariance[0] = 2.5
request = get_service("rcl_interfaces/srv/GetParameters").Request(names=["a"])
print(json.dumps({{
    "store": {STORE!r} in sys.modules,
    "odom": serialize(odom).hex(),
    "request": serialize(request).hex(),
    "hashes": [type_hash("nav_msgs/msg/Odometry"), type_hash("rcl_interfaces/srv/GetParameters")],
    "types": len(type_names("msg")),
}}))
"""


def probe(cache: Path) -> dict[str, Any]:
    """What a fresh process using ``cache`` as its cache folder reports (see ``PROBE``)."""
    env = {**os.environ, "LAUNCHKIT_CACHE_DIR": str(cache)}
    done = subprocess.run(
        [sys.executable, "-c", PROBE], env=env, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert done.stderr == "", done.stderr
    result: dict[str, Any] = json.loads(done.stdout)
    return result


def cache_file(cache: Path) -> Path:
    """The file the cache folder holds for the installed rosbags."""
    return cache / f"rosbags-{version('rosbags')}-ros2_jazzy.json"


def same_messages(a: dict[str, Any], b: dict[str, Any]) -> bool:
    """Both processes encoded and hashed identically and knew the same types."""
    return all(a[key] == b[key] for key in ("odom", "request", "hashes", "types"))


def test_first_use_writes_the_cache_and_later_processes_use_it(tmp_path: Path) -> None:
    cache = tmp_path / "cache"
    first = probe(cache)
    assert first["store"], "with no cache, the definitions come from rosbags' store"
    assert cache_file(cache).is_file()
    assert list(cache.iterdir()) == [cache_file(cache)], "no temporary file left behind"
    second = probe(cache)
    assert not second["store"], "with the cache, rosbags' store modules are not imported"
    assert same_messages(first, second)
    assert first["types"] > 150


@pytest.mark.parametrize(
    "damage",
    ["garbage", "truncated", "other rosbags version", "other distro", "unknown nested type"],
)
def test_a_damaged_or_foreign_cache_is_ignored_and_rewritten(tmp_path: Path, damage: str) -> None:
    cache = tmp_path / "cache"
    reference = probe(cache)
    path = cache_file(cache)
    text = path.read_text()
    data = json.loads(text)
    if damage == "garbage":
        path.write_bytes(b"\x00\xff not json")
    elif damage == "truncated":
        path.write_text(text[: len(text) // 2])
    elif damage == "other rosbags version":
        path.write_text(json.dumps({**data, "rosbags": "0.0.1"}))
    elif damage == "other distro":
        path.write_text(json.dumps({**data, "distro": "ros2_humble"}))
    else:
        del data["types"]["std_msgs/msg/Header"]
        path.write_text(json.dumps(data))
    rebuilt = probe(cache)
    assert rebuilt["store"], "the damaged cache was used"
    assert same_messages(reference, rebuilt)
    assert json.loads(path.read_text()) == json.loads(text), "the cache was not rewritten"
    assert not probe(cache)["store"]


def test_a_cache_folder_that_cannot_be_written_changes_nothing_but_speed(tmp_path: Path) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    unwritable = blocker / "cache"  # below a regular file: cannot be made, even by root
    reference = probe(tmp_path / "cache")
    first, second = probe(unwritable), probe(unwritable)
    assert first["store"] and second["store"]
    assert same_messages(reference, first) and same_messages(reference, second)


def test_the_cache_folder_follows_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("LAUNCHKIT_CACHE_DIR", "/somewhere/lk")
    assert cache_dir() == Path("/somewhere/lk")
    monkeypatch.delenv("LAUNCHKIT_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", "/xdg")
    assert cache_dir() == Path("/xdg/launchkit")
    monkeypatch.setenv("XDG_CACHE_HOME", "relative")  # the XDG spec: ignored unless absolute
    monkeypatch.setenv("HOME", "/home/someone")
    assert cache_dir() == Path("/home/someone/.cache/launchkit")


def test_the_test_run_does_not_cache_into_the_real_home() -> None:
    assert "LAUNCHKIT_CACHE_DIR" in os.environ
    assert not Path(os.environ["LAUNCHKIT_CACHE_DIR"]).is_relative_to(Path.home() / ".cache")


def test_built_in_message_types_are_rosbags_jazzy_types() -> None:
    from rosbags.typesys import Stores, get_typestore

    from launchkit.ros.msgs import message_spec, type_names

    def no_char(desc: Any) -> Any:  # the one deliberate change: rosidl reads char as uint8
        kind, detail = desc
        if kind == 1 and detail[0] == "char":
            return (1, ("uint8", detail[1]))
        if kind in (3, 4):
            return (kind, (no_char(detail[0]), detail[1]))
        return desc

    jazzy = get_typestore(Stores.ROS2_JAZZY)
    assert set(jazzy.fielddefs) <= set(type_names("msg"))
    for name, (consts, fields) in jazzy.fielddefs.items():
        mine = message_spec(name).typesdict_entry()
        assert mine[1] == [(f, no_char(d)) for f, d in fields], name
        assert [c[0] for c in mine[0]] == [c[0] for c in consts], name
