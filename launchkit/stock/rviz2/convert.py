"""ROS messages (CDR bytes) as the browser page reads them: compact JSON, images as binary.

The page gets only what it draws: a TF message is a list of ``{parent, child, t, q}``, a scan
its geometry and ranges (``null`` where a range is not finite), odometry a pose and a twist.
Images travel as one binary WebSocket frame: a little-endian ``uint32`` length, that many bytes
of JSON header (topic, width, height, encoding, step or format) and the pixels or the
compressed bytes as they came. The page's image panel is a few hundred pixels wide, so raw
images wider than :data:`MAX_PAGE_WIDTH` are sent with every n-th pixel of every n-th row
(``"scale": n`` in the header): the seed's 800x800 camera goes as 400x400, a quarter of the
bytes to send and to convert in the browser. Foxglove clients get every image whole.

Every other type is sent as its fields (long arrays cut, as
``ros2 topic echo`` does) for the topic list's message view, and ``/rosout``'s log lines whole
for the console. Any topic can also be had in its fields form (:func:`to_fields`): every field
of the message, which the plot reads its numbers from. Both go through one generic conversion
(:func:`launchkit.ros.message_text.to_data`), whatever containers the message class uses.
"""

from __future__ import annotations

import json
import math
import struct
from collections.abc import Callable
from typing import Any

from launchkit.ros.message_text import to_data
from launchkit.ros.msgs import deserialize

#: Longest array or string of a message shown whole in the topic list's message view.
ECHO_TRUNCATE = 32
#: Longest array or string of a message sent whole in its fields form (the plot's elements).
FIELDS_TRUNCATE = 256
#: Raw images wider than this are thinned for the page.
MAX_PAGE_WIDTH = 640

PageFrame = str | bytes


def _vec(v: Any) -> list[float]:
    return [float(v.x), float(v.y), float(v.z)]


def _quat(q: Any) -> list[float]:
    return [float(q.x), float(q.y), float(q.z), float(q.w)]


def _stamp(header: Any) -> float:
    return float(header.stamp.sec) + float(header.stamp.nanosec) * 1e-9


def _tf(msg: Any) -> dict[str, Any]:
    return {
        "transforms": [
            {
                "parent": t.header.frame_id.lstrip("/"),
                "child": t.child_frame_id.lstrip("/"),
                "t": _vec(t.transform.translation),
                "q": _quat(t.transform.rotation),
            }
            for t in msg.transforms
        ]
    }


def _scan(msg: Any) -> dict[str, Any]:
    return {
        "frame": msg.header.frame_id.lstrip("/"),
        "stamp": _stamp(msg.header),
        "angle_min": float(msg.angle_min),
        "angle_increment": float(msg.angle_increment),
        "range_min": float(msg.range_min),
        "range_max": float(msg.range_max),
        "ranges": [round(float(r), 4) if math.isfinite(r) else None for r in msg.ranges],
    }


def _odometry(msg: Any) -> dict[str, Any]:
    return {
        "frame": msg.header.frame_id.lstrip("/"),
        "child": msg.child_frame_id.lstrip("/"),
        "stamp": _stamp(msg.header),
        "p": _vec(msg.pose.pose.position),
        "q": _quat(msg.pose.pose.orientation),
        "v": _vec(msg.twist.twist.linear),
        "w": _vec(msg.twist.twist.angular),
    }


def _joint_state(msg: Any) -> dict[str, Any]:
    return {"name": list(msg.name), "position": [float(p) for p in msg.position]}


def _string(msg: Any) -> dict[str, Any]:
    return {"data": str(msg.data)}


def _log(msg: Any) -> dict[str, Any]:
    """A ``/rosout`` line whole (the echo form would cut its text)."""
    return {
        "stamp": float(msg.stamp.sec) + float(msg.stamp.nanosec) * 1e-9,
        "level": int(msg.level),
        "name": str(msg.name),
        "msg": str(msg.msg),
        "file": str(msg.file),
        "function": str(msg.function),
        "line": int(msg.line),
    }


def _finite(value: Any) -> Any:
    """``value`` with non-finite floats as None (JSON has no NaN or Infinity)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, list):
        return [_finite(v) for v in value]
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    return value


def _echo(msg: Any) -> dict[str, Any]:
    return {"fields": _finite(to_data(msg, ECHO_TRUNCATE))}


_JSON: dict[str, Callable[[Any], dict[str, Any]]] = {
    "tf2_msgs/msg/TFMessage": _tf,
    "sensor_msgs/msg/LaserScan": _scan,
    "nav_msgs/msg/Odometry": _odometry,
    "sensor_msgs/msg/JointState": _joint_state,
    "std_msgs/msg/String": _string,
    "rcl_interfaces/msg/Log": _log,
}

IMAGE_TYPES = ("sensor_msgs/msg/Image", "sensor_msgs/msg/CompressedImage")


def _binary(header: dict[str, Any], payload: bytes, msg: Any) -> bytes:
    """The frame: header, then the message's ``data``, which is the last field of both image
    types and so the tail of the CDR bytes (taken from there: one copy of ~2 MB, not three)."""
    head = json.dumps(header).encode()
    size = len(msg.data)
    data = memoryview(payload)[len(payload) - size :] if size else b""
    return b"".join((struct.pack("<I", len(head)), head, data))


def _image(topic: str, msg: Any, payload: bytes) -> bytes:
    width, height, step = int(msg.width), int(msg.height), int(msg.step)
    header = {
        "topic": topic,
        "frame": msg.header.frame_id,
        "stamp": _stamp(msg.header),
        "width": width,
        "height": height,
        "encoding": str(msg.encoding),
        "step": step,
        "bigendian": bool(msg.is_bigendian),
        "scale": 1,
    }
    factor = -(-width // MAX_PAGE_WIDTH)
    whole_pixels = width > 0 and step % width == 0 and step * height == len(msg.data)
    if factor > 1 and whole_pixels:
        import numpy as np  # here: a viewer that shows no image (turtlesim's) never loads it

        size = step // width  # bytes a pixel
        pixels = np.asarray(msg.data, dtype=np.uint8).reshape(height, width, size)
        thinned = np.ascontiguousarray(pixels[::factor, ::factor])
        rows, columns = thinned.shape[:2]
        header.update(width=columns, height=rows, step=columns * size, scale=factor)
        head = json.dumps(header).encode()
        return b"".join((struct.pack("<I", len(head)), head, thinned.tobytes()))
    return _binary(header, payload, msg)


def _compressed(topic: str, msg: Any, payload: bytes) -> bytes:
    header = {
        "topic": topic,
        "frame": msg.header.frame_id,
        "stamp": _stamp(msg.header),
        "format": str(msg.format),
    }
    return _binary(header, payload, msg)


def to_json(body: dict[str, Any]) -> str:
    """``body`` as compact JSON, non-finite floats as null (JSON has no NaN)."""
    try:
        return json.dumps(body, separators=(",", ":"), allow_nan=False)
    except ValueError:  # a NaN somewhere (a bad transform, say): send it as null
        return json.dumps(_finite(body), separators=(",", ":"), allow_nan=False)


def to_fields(topic: str, type_name: str, payload: bytes, stamp_ns: int) -> str:
    """Every field of one message (arrays and strings past :data:`FIELDS_TRUNCATE` cut), with
    the time it arrived: what the plot and the echo of any type read.

    Raises ``ValueError`` (or the decoder's own error) for bytes that are not a ``type_name``.
    """
    msg = deserialize(payload, type_name)
    body = {
        "op": "fields",
        "topic": topic,
        "type": type_name,
        "t": stamp_ns * 1e-9,
        "msg": to_data(msg, FIELDS_TRUNCATE),
    }
    return to_json(body)


def to_page(topic: str, type_name: str, payload: bytes) -> PageFrame:
    """One message for the page: JSON text, or a binary frame for images.

    Raises ``ValueError`` (or the decoder's own error) for bytes that are not a ``type_name``.
    """
    msg = deserialize(payload, type_name)
    if type_name == "sensor_msgs/msg/Image":
        return _image(topic, msg, payload)
    if type_name == "sensor_msgs/msg/CompressedImage":
        return _compressed(topic, msg, payload)
    convert = _JSON.get(type_name, _echo)
    body = {"op": "msg", "topic": topic, "type": type_name, "msg": convert(msg)}
    return to_json(body)
