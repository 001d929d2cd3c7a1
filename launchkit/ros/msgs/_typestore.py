"""The typestore: rosbags' ROS 2 Jazzy messages, launchkit's services, rclpy-style defaults.

rosbags generates plain dataclasses whose fields are all required and whose numeric arrays must be
numpy arrays. ``_make_rclpy_like`` patches each class so that ``Twist()`` works, every field has
rclpy's default, and lists assigned to numeric array fields become numpy arrays.

A message type is registered (its class generated) when first asked for, with the types inside
it, from Jazzy's definitions (:mod:`launchkit.ros.msgs._defcache`: a per-user cache, so that a
process does not import rosbags' store modules of every ROS distribution); a service likewise.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable, Iterable
from typing import Any

import numpy as np
from rosbags.typesys import get_types_from_msg
from rosbags.typesys.store import Typestore

from launchkit.ros.msgs._defcache import Definitions, definitions
from launchkit.ros.msgs._srv_defs import SERVICES
from launchkit.ros.msgs._store import LazyTypestore

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4

_NUMPY_DTYPES: dict[str, Any] = {
    "bool": np.bool_,
    "byte": np.uint8,
    "char": np.uint8,
    "int8": np.int8,
    "uint8": np.uint8,
    "int16": np.int16,
    "uint16": np.uint16,
    "int32": np.int32,
    "uint32": np.uint32,
    "int64": np.int64,
    "uint64": np.uint64,
    "float32": np.float32,
    "float64": np.float64,
}

# Default values written in the .msg files (rosbags does not keep them); rclpy honours them.
_MSG_DEFAULTS: dict[str, dict[str, Any]] = {
    "geometry_msgs/msg/Quaternion": {"w": 1.0},
    "sensor_msgs/msg/NavSatStatus": {"status": -2},
}

_lock = threading.Lock()
_store: Typestore | None = None
_jazzy: Definitions | None = None  # every Jazzy message's definition, registered or not
_registered: set[str] = set()  # the services of SERVICES registered so far
_SERVICE_PARTS = ("_Request", "_Response", "_Event")


def typestore(services: bool = True) -> Typestore:
    """The process-wide typestore with every Jazzy message type registered; ``services``: and
    every service type of launchkit's. For one type (much cheaper), :func:`typestore_for`."""
    with _lock:
        store = _built()
        _register_messages(store, _definitions())
        if services:
            _register_services(store, [name for name in SERVICES if name not in _registered])
        return store


def typestore_for(type_name: str) -> Typestore:
    """The typestore, with what looking up ``type_name`` needs: a message type and the types
    inside it, or for a service's type (``pkg/srv/Name``, ``..._Request``, ...) that service.

    Generating the code of a type costs: ``launchkit topic echo /odom`` registers the ten types
    of an Odometry, a node the six parameter services it serves (and their messages).
    """
    with _lock:
        store = _built()
        if "/srv/" in type_name:
            name = type_name
            for part in _SERVICE_PARTS:
                name = name.removesuffix(part)
            if name in SERVICES and name not in _registered:
                _register_services(store, [name])
        elif type_name not in store.types:
            _register_messages(store, [type_name])
        return store


def known_names(kind: str) -> set[str]:
    """Every type name of a kind (``msg`` or ``srv``) that can be looked up, without registering
    any: Jazzy's messages, launchkit's services, and types registered by hand (a bag's)."""
    with _lock:
        registered = list(_built().types)
        if kind == "msg":
            return {*_definitions(), *(n for n in registered if "/msg/" in n)}
        services = (n for n in registered if "/srv/" in n and not n.endswith(_SERVICE_PARTS))
        return {*SERVICES, *services}


def _built() -> Typestore:
    global _store
    if _store is None:
        _store = LazyTypestore()
    return _store


def _definitions() -> Definitions:
    global _jazzy
    if _jazzy is None:
        _jazzy = definitions()
    return _jazzy


def _register_messages(ts: Typestore, names: Iterable[str]) -> None:
    """Register the Jazzy types ``names`` and the types they contain (those not registered yet;
    names Jazzy does not have are left out: looking them up fails as before)."""
    jazzy = _definitions()
    missing: dict[str, Any] = {}
    todo = list(names)
    while todo:
        name = todo.pop()
        if name in missing or name in ts.types or name not in jazzy:
            continue
        missing[name] = jazzy[name]
        todo.extend(_references(jazzy[name][1]))
    if not missing:
        return
    ts.register(missing)  # at once: each register() generates and compiles code
    _chars_as_uint8(ts, missing)
    for name in missing:
        _make_rclpy_like(ts, name)


def _references(fields: Iterable[tuple[str, Any]]) -> list[str]:
    """The type names the fields use."""
    found = []
    for _, desc in fields:
        while desc[0] in (_ARRAY, _SEQUENCE):
            desc = desc[1][0]
        if desc[0] == _NAME:
            found.append(desc[1])
    return found


def _register_services(ts: Typestore, names: list[str]) -> None:
    if not names:
        return
    services: dict[str, Any] = {}
    for name in names:
        services.update(_service_types(name, SERVICES[name]))
    _register_messages(ts, [ref for _, fields in services.values() for ref in _references(fields)])
    ts.register(services)  # at once: each register() generates and compiles code
    for cls_name in services:
        _make_rclpy_like(ts, cls_name)
    _registered.update(names)


def _chars_as_uint8(ts: Typestore, names: Iterable[str]) -> None:
    # rosidl maps the .msg ``char`` to uint8; rosbags keeps "char", which changes the RIHS01 hash
    # (service_msgs/ServiceEventInfo, hence every service hash). The CDR bytes are the same.
    def fix(desc: Any) -> Any:
        kind, detail = desc
        if kind == _BASE and detail[0] == "char":
            return (kind, ("uint8", detail[1]))
        if kind in (_ARRAY, _SEQUENCE):
            return (kind, (fix(detail[0]), detail[1]))
        return desc

    for name in names:
        consts, fields = ts.fielddefs[name]
        ts.fielddefs[name] = (consts, [(fname, fix(desc)) for fname, desc in fields])


def _service_types(name: str, text: str) -> dict[str, Any]:
    """Request, Response, Event and the service's own description (used only for its hash)."""
    pkg, _, short = name.split("/")
    request_text, _, response_text = text.partition("---\n")
    renames = {
        f"{pkg}/msg/{short}_{part}": f"{name}_{part}" for part in ("Request", "Response", "Event")
    }

    def parse(body: str, suffix: str) -> tuple[str, Any]:
        ((_, (consts, fields)),) = get_types_from_msg(body, f"{pkg}/msg/{short}{suffix}").items()
        return f"{name}{suffix}", (consts, [(n, _rename(d, renames)) for n, d in fields])

    event = (
        f"service_msgs/msg/ServiceEventInfo info\n"
        f"{short}_Request[<=1] request\n{short}_Response[<=1] response\n"
    )
    whole = (
        f"{short}_Request request_message\n{short}_Response response_message\n"
        f"{short}_Event event_message\n"
    )
    return dict(
        [
            parse(request_text, "_Request"),
            parse(response_text, "_Response"),
            parse(event, "_Event"),
            parse(whole, ""),
        ]
    )


def _rename(desc: Any, renames: dict[str, str]) -> Any:
    kind, detail = desc
    if kind == _NAME:
        return (kind, renames.get(detail, detail))
    if kind in (_ARRAY, _SEQUENCE):
        return (kind, (_rename(detail[0], renames), detail[1]))
    return desc


def _default_factory(ts: Typestore, desc: Any) -> Callable[[], Any]:
    """A zero-argument callable giving rclpy's default for a field of this description."""
    kind, detail = desc
    if kind == _BASE:
        base = detail[0]
        if base == "string" or base == "wstring":
            return str
        if base == "bool":
            return bool
        if base in ("float32", "float64"):
            return float
        return int
    if kind == _NAME:
        return lambda: ts.types[detail]()
    sub, length = detail
    dtype = _numpy_dtype(sub)
    if kind == _ARRAY:
        if dtype is not None:
            return lambda: np.zeros(length, dtype=dtype)
        element = _default_factory(ts, sub)
        return lambda: [element() for _ in range(length)]
    if dtype is not None:
        return lambda: np.zeros(0, dtype=dtype)
    return list


def _numpy_dtype(desc: Any) -> Any:
    kind, detail = desc
    if kind == _BASE:
        return _NUMPY_DTYPES.get(detail[0])
    return None


def _make_rclpy_like(ts: Typestore, name: str) -> None:
    cls = ts.types[name]
    if getattr(cls, "__launchkit__", False):
        return
    fields = ts.fielddefs[name][1]
    defaults = {fname: _default_factory(ts, desc) for fname, desc in fields}
    for fname, value in _MSG_DEFAULTS.get(name, {}).items():
        defaults[fname] = functools.partial(lambda v: v, value)
    arrays = {
        fname: dtype
        for fname, desc in fields
        if desc[0] in (_ARRAY, _SEQUENCE) and (dtype := _numpy_dtype(desc[1][0])) is not None
    }
    names = [fname for fname, _ in fields]
    original_init = cls.__init__

    @functools.wraps(original_init)
    def __init__(self: Any, *args: Any, **kwargs: Any) -> None:
        if len(args) != len(names):
            for fname in names[len(args) :]:
                if fname not in kwargs:
                    kwargs[fname] = defaults[fname]()
        original_init(self, *args, **kwargs)

    setattr(cls, "__init__", __init__)  # noqa: B010 (assigning a method)
    if arrays:

        def __setattr__(self: Any, key: str, value: Any) -> None:
            dtype = arrays.get(key)
            if dtype is not None and not isinstance(value, np.ndarray):
                if isinstance(value, (bytes, bytearray, memoryview)):
                    value = np.frombuffer(value, dtype=np.uint8).astype(dtype, copy=False)
                else:
                    value = np.asarray(value, dtype=dtype)
            object.__setattr__(self, key, value)

        setattr(cls, "__setattr__", __setattr__)  # noqa: B010

    def __eq__(self: Any, other: Any) -> bool:
        # the dataclass __eq__ compares tuples, which numpy arrays make ambiguous
        if other.__class__ is not self.__class__:
            return NotImplemented
        for fname in names:
            mine, theirs = getattr(self, fname), getattr(other, fname)
            if fname in arrays:
                if not np.array_equal(mine, theirs):
                    return False
            elif mine != theirs:
                return False
        return True

    setattr(cls, "__eq__", __eq__)  # noqa: B010
    short = name.rsplit("/", 1)[-1]
    cls.__name__ = short
    cls.__qualname__ = short
    setattr(cls, "__launchkit__", True)  # noqa: B010
