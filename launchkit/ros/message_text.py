"""Messages as text, the way ROS 2 prints them: ``ros2 topic echo``'s YAML and CSV
(rosidl_runtime_py's ``message_to_yaml`` / ``message_to_csv``), and the ``repr`` that rosidl's
generated classes give (``ros2 topic pub`` and ``ros2 service call`` print it).

Everything here is driven by the message's *field types*, never by how a value happens to be
stored: a numeric sequence may be held as a list, an ``array.array`` or a numpy array, and each
value is first turned into what rosidl's Python holds for its field (:func:`rosidl_value`), so
the text is rosidl's whatever class the message is.
"""

from __future__ import annotations

import array
import sys
from typing import Any

import yaml

from launchkit.ros.message_data import fields_of
from launchkit.ros.msgs import message_type_name

# rosidl_adapter's .msg -> IDL names, and the array type codes of rosidl's numeric sequences
from launchkit.ros.msgs._spec import IDL_NAMES, TYPE_CODES

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4
TRUNCATE_LENGTH = 128
#: the member rosidl gives an empty message; its Python classes do not show it
_PLACEHOLDER = "structure_needs_at_least_one_member"


def rosidl_value(value: Any, desc: Any) -> Any:
    """``value`` of a field of type ``desc`` (a rosbags field description) as rosidl's Python
    holds it: ``bytes`` for ``byte``, an ``array.array`` for a numeric sequence, a numpy array
    for a fixed-size numeric array, a list for any other array or sequence, Python scalars."""
    kind, detail = desc
    if kind == _BASE:
        return _scalar(value, detail[0])
    if kind == _NAME:
        return value
    element, _ = detail
    base = element[1][0] if element[0] == _BASE else None
    special = IDL_NAMES.get(base or "", "")
    if special in TYPE_CODES and kind == _SEQUENCE:
        return array.array(TYPE_CODES[special], [_scalar(v, base or "") for v in value])
    if special in TYPE_CODES:
        from launchkit.ros.msgs import _fixed_arrays  # numpy: only for a fixed-size array

        return _fixed_arrays.converter(special)([_scalar(v, base or "") for v in value])
    return [rosidl_value(v, element) for v in value]


def _scalar(value: Any, base: str) -> Any:
    value = _plain(value)
    if base == "byte":
        return value if isinstance(value, bytes) else bytes([value])
    if base == "bool":
        return bool(value)
    return value


def is_message(value: Any) -> bool:
    """Whether ``value`` is a message (of any launchkit message class)."""
    name = getattr(value, "_TYPE_NAME", None) or getattr(value, "__msgtype__", None)
    return isinstance(name, str) and not isinstance(value, type)


def _field_types(msg: Any) -> list[tuple[str, Any]]:
    """(name, field description) of each field of ``msg``."""
    return [(n, d) for n, d in fields_of(message_type_name(msg)) if n != _PLACEHOLDER]


def _fields(msg: Any) -> list[tuple[str, Any, Any]]:
    """(name, field description, value as rosidl holds it) of each field of ``msg``."""
    return [
        (name, desc, rosidl_value(getattr(msg, name), desc)) for name, desc in _field_types(msg)
    ]


# -- repr ---------------------------------------------------------------------------------------


def short_repr(msg: Any) -> str:
    """``pkg.msg.Name(field=value, ...)``: the ``repr`` of rosidl's generated classes, which
    ``ros2 topic pub`` (``publishing #1: ...``) and ``ros2 service call`` print."""
    parts = []
    for name, _, value in _fields(msg):
        if is_message(value):
            text = short_repr(value)
        elif isinstance(value, array.array):
            # rosidl shows a numeric sequence as the list inside ``array('d', [...])``
            text = repr(value.tolist())
        elif isinstance(value, list):
            text = "[" + ", ".join(short_repr(v) if is_message(v) else repr(v) for v in value)
            text += "]"
        else:
            text = repr(value)
        parts.append(f"{name}={text}")
    return f"{message_type_name(msg).replace('/', '.')}({', '.join(parts)})"


def value_text(value: Any, desc: Any) -> str:
    """``str()`` of a field's value as rosidl holds it (``ros2 topic echo --field`` of a field
    that is not a message prints this): ``array('d', [1.0])``, ``[0. 0.]``, ``hello``."""
    held = rosidl_value(value, desc)
    if isinstance(held, list):
        return "[" + ", ".join(short_repr(v) if is_message(v) else repr(v) for v in held) + "]"
    return str(held)


# -- YAML and CSV (rosidl_runtime_py.convert) -----------------------------------------------------
# An array or sequence is cut before it is converted: an image's data is millions of items.


def _held_items(raw: Any, desc: Any, truncate: int | None) -> tuple[Any, bool]:
    """The first ``truncate`` items of an array or sequence field as rosidl holds them, and
    whether there were more."""
    cut = truncate is not None and len(raw) > truncate
    return rosidl_value(raw[:truncate] if cut else raw, desc), cut


def to_data(
    msg: Any,
    truncate: int | None = TRUNCATE_LENGTH,
    *,
    no_arr: bool = False,
    no_str: bool = False,
) -> dict[str, Any]:
    """A message as nested dicts and lists, as ``message_to_ordereddict`` makes it: strings,
    byte values and sequences longer than ``truncate`` cut with ``...``; with ``no_arr`` each
    array or sequence replaced by a summary of its type and length, with ``no_str`` each string
    by its length."""
    out: dict[str, Any] = {}
    for name, desc in _field_types(msg):
        raw = getattr(msg, name)
        if desc[0] in (_ARRAY, _SEQUENCE):
            if no_arr:
                out[name] = _array_summary(len(raw), desc)
                continue
            held, cut = _held_items(raw, desc, truncate)
            items = [_data(_plain(v), truncate, no_arr, no_str) for v in held]
            out[name] = [*items, "..."] if cut else items
        else:
            out[name] = _data(rosidl_value(raw, desc), truncate, no_arr, no_str)
    return out


def _data(value: Any, truncate: int | None, no_arr: bool, no_str: bool) -> Any:
    """One value (a field's, or an item's of an array) as ``_convert_value`` converts it."""
    if isinstance(value, bytes):  # a byte value, shown as characters
        cut = truncate is not None and len(value) > truncate
        text = "".join(chr(c) for c in (value[:truncate] if cut else value))
        return text + "..." if cut else text
    if isinstance(value, str):
        if no_str:
            return f"<string length: <{len(value)}>>"
        return value[:truncate] + "..." if truncate is not None and len(value) > truncate else value
    if is_message(value):
        return to_data(value, truncate, no_arr=no_arr, no_str=no_str)
    return _plain(value)


def _plain(value: Any) -> Any:
    """A numpy scalar (an element of a fixed-size array) as the Python number it holds."""
    numpy = sys.modules.get("numpy")  # a process that never imported numpy holds no numpy value
    return value.item() if numpy is not None and isinstance(value, numpy.generic) else value


def _array_summary(length: int, desc: Any) -> str:
    kind, (element, bound) = desc
    name = _element_type_name(element)
    if kind == _ARRAY:
        return f"<array type: {name}[{bound}]>"
    if bound:
        return f"<sequence type: {name}[{bound}], length: {length}>"
    return f"<sequence type: {name}, length: {length}>"


def _element_type_name(element: Any) -> str:
    kind, detail = element
    if kind == _NAME:
        return str(detail)
    base = str(detail[0])
    if base in ("string", "wstring"):
        return base
    return IDL_NAMES.get(base, base)


def to_yaml(
    msg: Any,
    truncate: int | None = TRUNCATE_LENGTH,
    *,
    no_arr: bool = False,
    no_str: bool = False,
    flow_style: bool = False,
) -> str:
    """A message as ``ros2 topic echo`` prints it (``message_to_yaml``)."""
    return yaml.safe_dump(
        to_data(msg, truncate, no_arr=no_arr, no_str=no_str),
        allow_unicode=True,
        width=sys.maxsize,
        default_flow_style=flow_style,
        sort_keys=False,
    )


def to_csv(
    msg: Any, truncate: int | None = TRUNCATE_LENGTH, *, no_arr: bool = False, no_str: bool = False
) -> str:
    """A message as ``ros2 topic echo --csv`` prints it (``message_to_csv``): every field,
    nested ones flattened, separated by commas."""
    parts = []
    for name, desc in _field_types(msg):
        raw = getattr(msg, name)
        if desc[0] not in (_ARRAY, _SEQUENCE):
            parts.append(_csv(rosidl_value(raw, desc), truncate, no_arr, no_str))
        elif no_arr:
            parts.append(_array_summary(len(raw), desc))
        else:
            held, cut = _held_items(raw, desc, truncate)
            items = [_csv(_plain(v), truncate, no_arr, no_str) for v in held]
            parts.append(_csv_join([*items, "..."] if cut else items))
    return _csv_join(parts)


def _csv_join(parts: list[str]) -> str:
    """Parts joined as message_to_csv joins them: a comma only after something (so an empty
    first part has none after it, as ros2 prints it)."""
    out = ""
    for part in parts:
        if out:
            out += ","
        out += part
    return out


def _csv(value: Any, truncate: int | None, no_arr: bool, no_str: bool) -> str:
    if is_message(value):
        return to_csv(value, truncate, no_arr=no_arr, no_str=no_str)
    if no_str and isinstance(value, str):
        return f"<string length: <{len(value)}>>"
    if isinstance(value, str) and truncate is not None and len(value) > truncate:
        return value[:truncate] + "..."
    if isinstance(value, bytes) and truncate is not None and len(value) > truncate:
        return str(value[:truncate] + b"...")
    return str(value)
