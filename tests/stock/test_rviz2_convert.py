"""What the page gets for a ROS message (launchkit/stock/rviz2/convert.py), from real CDR."""

from __future__ import annotations

import json
import struct

import numpy as np
import pytest

from launchkit.ros.msgs import get_message, serialize
from launchkit.stock.rviz2.convert import to_page


def _frame(type_name: str, **fields: object) -> str | bytes:
    return to_page("/t", type_name, serialize(get_message(type_name)(**fields), type_name))


def _split(frame: str | bytes) -> tuple[dict[str, object], bytes]:
    assert isinstance(frame, bytes)
    (size,) = struct.unpack_from("<I", frame)
    return json.loads(frame[4 : 4 + size]), frame[4 + size :]


def test_an_image_is_a_binary_frame_with_its_pixels_unchanged() -> None:
    pixels = (np.arange(4 * 3 * 3) * 7 % 256).astype(np.uint8)
    header, data = _split(
        _frame("sensor_msgs/msg/Image", width=4, height=3, encoding="bgr8", step=12, data=pixels)
    )
    assert header == {
        "topic": "/t",
        "frame": "",
        "stamp": 0.0,
        "width": 4,
        "height": 3,
        "encoding": "bgr8",
        "step": 12,
        "bigendian": False,
        "scale": 1,
    }
    assert data == pixels.tobytes()


def test_a_wide_image_is_thinned_for_the_page() -> None:
    pixels = np.arange(800 * 600 * 3, dtype=np.uint32).astype(np.uint8).reshape(600, 800, 3)
    header, data = _split(
        _frame(
            "sensor_msgs/msg/Image",
            width=800,
            height=600,
            encoding="rgb8",
            step=2400,
            data=pixels.reshape(-1),
        )
    )
    assert (header["width"], header["height"], header["step"], header["scale"]) == (
        400,
        300,
        1200,
        2,
    )
    assert data == pixels[::2, ::2].tobytes()


def test_a_compressed_image_keeps_its_bytes_and_format() -> None:
    jpeg = np.frombuffer(b"\xff\xd8\xff\xe0 a jpeg", np.uint8)
    header, data = _split(_frame("sensor_msgs/msg/CompressedImage", format="jpeg", data=jpeg))
    assert (header["format"], data) == ("jpeg", jpeg.tobytes())


def test_a_scan_has_null_where_a_range_is_not_finite() -> None:
    ranges = np.array([1.0, np.inf, np.nan, 2.25], np.float32)
    body = json.loads(_frame("sensor_msgs/msg/LaserScan", ranges=ranges, range_max=5.0))  # type: ignore[arg-type]
    assert body["msg"]["ranges"] == [1.0, None, None, 2.25]


def test_transforms_are_compact_and_a_nan_is_null_not_invalid_json() -> None:
    transform = get_message("geometry_msgs/msg/TransformStamped")(child_frame_id="/wheel")
    transform.header.frame_id = "base"
    transform.transform.translation.x = float("nan")
    frame = _frame("tf2_msgs/msg/TFMessage", transforms=[transform])
    assert isinstance(frame, str) and "NaN" not in frame
    (got,) = json.loads(frame)["msg"]["transforms"]
    assert got == {
        "parent": "base",
        "child": "wheel",
        "t": [None, 0.0, 0.0],
        "q": [0.0, 0.0, 0.0, 1.0],
    }


def test_other_types_are_their_fields_with_long_arrays_cut() -> None:
    body = json.loads(_frame("std_msgs/msg/Float64MultiArray", data=np.arange(100, dtype=float)))  # type: ignore[arg-type]
    values = body["msg"]["fields"]["data"]
    assert values[:3] == [0.0, 1.0, 2.0] and values[-1] == "..." and len(values) == 33


def test_bytes_that_are_not_the_type_raise() -> None:
    with pytest.raises(Exception):  # noqa: B017 - the decoder's own error, whichever it is
        to_page("/t", "sensor_msgs/msg/Image", b"\x00\x01\x00\x00\x01")
