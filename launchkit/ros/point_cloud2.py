"""``sensor_msgs_py.point_cloud2``: PointCloud2 messages to and from NumPy arrays, as ROS 2
Jazzy's pure-Python package does (the package is not on PyPI, so launchkit brings it).

A cloud's points are one NumPy *structured* array whose dtype the message's ``fields`` give
(:func:`dtype_from_fields`); the message's ``data`` is that array's bytes. Unstructured input
(an ``N x len(fields)`` array of one type) is accepted where every field has that type, as
upstream accepts it.
"""

from __future__ import annotations

import array
import sys
from collections import namedtuple
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np
from numpy.lib import recfunctions

from launchkit.ros.msgs import get_message

PointCloud2 = get_message("sensor_msgs/msg/PointCloud2")
PointField = get_message("sensor_msgs/msg/PointField")

#: PointField's datatype constants and the NumPy types they name.
DATATYPES = {
    1: np.dtype(np.int8),
    2: np.dtype(np.uint8),
    3: np.dtype(np.int16),
    4: np.dtype(np.uint16),
    5: np.dtype(np.int32),
    6: np.dtype(np.uint32),
    7: np.dtype(np.float32),
    8: np.dtype(np.float64),
}
#: The fields :func:`create_cloud_xyz32` makes.
_XYZ32 = [("x", 0), ("y", 4), ("z", 8)]


def dtype_from_fields(fields: Iterable[Any], point_step: int | None = None) -> np.dtype[Any]:
    """The structured NumPy dtype of one point described by PointField ``fields`` (a field
    with ``count`` > 1 is a sub-array; ``point_step`` pads the point to that many bytes)."""
    names: list[str] = []
    formats: list[Any] = []
    offsets: list[int] = []
    for index, field in enumerate(fields):
        if field.datatype not in DATATYPES:
            raise ValueError(f"field '{field.name}' has an unknown datatype {field.datatype}")
        base = DATATYPES[field.datatype]
        names.append(field.name or f"unnamed_field_{index}")
        formats.append(base if field.count == 1 else (base, (field.count,)))
        offsets.append(field.offset)
    layout: dict[str, Any] = {"names": names, "formats": formats, "offsets": offsets}
    if point_step is not None:
        layout["itemsize"] = point_step
    dtype: np.dtype[Any] = np.dtype(layout)  # type: ignore[call-overload]
    return dtype


def create_cloud(
    header: Any, fields: Sequence[Any], points: Any, point_step: int | None = None
) -> Any:
    """A PointCloud2 of ``points`` (a structured array of the fields' dtype, an unstructured
    array whose columns are the fields, or an iterable of per-point sequences) with ``header``
    and ``fields``. A 2-D structured array makes an organized cloud (``height`` rows)."""
    dtype = dtype_from_fields(fields, point_step)
    if isinstance(points, np.ndarray) and points.dtype.names is None:
        if any(field.datatype != fields[0].datatype for field in fields[1:]):
            raise ValueError("an unstructured array needs fields that all have one datatype")
        points = recfunctions.unstructured_to_structured(points, dtype=dtype)
    elif isinstance(points, np.ndarray):
        if points.dtype != dtype:
            raise ValueError(f"the points' dtype {points.dtype} is not the fields' {dtype}")
    else:
        points = np.array([tuple(point) for point in points], dtype=dtype)
    if points.ndim > 2:
        raise ValueError(f"points must be 1-D or 2-D (organized), not {points.ndim}-D")
    data = array.array("B")
    data.frombytes(np.ascontiguousarray(points).tobytes())
    width = points.shape[0]
    return PointCloud2(
        header=header,
        height=points.shape[1] if points.ndim == 2 else 1,
        width=width,
        fields=list(fields),
        is_bigendian=sys.byteorder != "little",
        point_step=dtype.itemsize,
        row_step=dtype.itemsize * width,
        data=data,
        is_dense=False,
    )


def create_cloud_xyz32(header: Any, points: Any) -> Any:
    """A PointCloud2 of float32 ``x``, ``y``, ``z`` from ``points`` (N x 3)."""
    fields = [
        PointField(name=name, offset=offset, datatype=PointField.FLOAT32, count=1)
        for name, offset in _XYZ32
    ]
    return create_cloud(header, fields, points)


def read_points(
    cloud: Any,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[Any] | None = None,
    reshape_organized_cloud: bool = False,
) -> np.ndarray[Any, Any]:
    """The points of ``cloud`` as a structured array: only ``field_names`` (all by default),
    without points holding a NaN in those fields (``skip_nans``), only the points at the
    indices or ``(u, v)`` pairs of ``uvs``; an organized cloud as ``height x width`` when
    ``reshape_organized_cloud``."""
    if cloud.is_bigendian != (sys.byteorder != "little"):
        raise ValueError("the cloud's byte order is not this machine's")
    dtype = dtype_from_fields(cloud.fields, cloud.point_step)
    points = np.frombuffer(bytes(cloud.data), dtype=dtype)
    if field_names is not None:
        points = recfunctions.repack_fields(points[list(field_names)])
    if uvs is not None:
        points = points[np.array([_flat_index(uv, cloud.width) for uv in uvs], dtype=np.intp)]
    if skip_nans and not cloud.is_dense:
        keep = np.ones(len(points), dtype=bool)
        for name in points.dtype.names or ():
            values = points[name]
            if np.issubdtype(values.dtype, np.floating):
                keep &= ~np.isnan(values).reshape(len(points), -1).any(axis=1)
        points = points[keep]
    if reshape_organized_cloud and cloud.height > 1 and not skip_nans and uvs is None:
        points = points.reshape(cloud.height, cloud.width)
    return points


def _flat_index(uv: Any, width: int) -> int:
    """A point's index from an index or a ``(u, v)`` pair (column, row)."""
    if isinstance(uv, int | np.integer):
        return int(uv)
    u, v = uv
    return int(u) + int(v) * width


def read_points_numpy(
    cloud: Any,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[Any] | None = None,
    reshape_organized_cloud: bool = False,
) -> np.ndarray[Any, Any]:
    """:func:`read_points` as an unstructured array (every selected field of one type)."""
    points = read_points(cloud, field_names, skip_nans, uvs, reshape_organized_cloud)
    types = {points.dtype.fields[name][0] for name in points.dtype.names or ()}
    if len(types) > 1:
        raise ValueError("read_points_numpy needs fields that all have one datatype")
    return recfunctions.structured_to_unstructured(points)


def read_points_list(
    cloud: Any,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[Any] | None = None,
) -> list[Any]:
    """:func:`read_points` as a list of named tuples (``Point(x=..., y=..., ...)``)."""
    points = read_points(cloud, field_names, skip_nans, uvs)
    point = namedtuple("Point", points.dtype.names or ())  # type: ignore[misc]
    return [point._make(row) for row in points.tolist()]
