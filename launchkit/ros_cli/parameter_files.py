"""Parameter YAML files for ``param dump`` and ``param load``, as ``ros2 param`` writes and
reads them (``NODE: {ros__parameters: {...}}``, dotted names nested)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import yaml

from launchkit.errors import Location, UserError
from launchkit.ros.params import flatten
from launchkit.ros_cli.parameter_values import value_from_text

_WILDCARD = "/**"
_SEPARATOR = "."


class ParameterFileError(UserError):
    """A parameter file that cannot be read or is not shaped as ROS parameter files are."""


def dump_text(node: str, values: dict[str, Any]) -> str:
    """``param dump``'s YAML: the node's parameters under ``ros__parameters``, a dotted name
    nested (``a.b: 1`` as ``a: {b: 1}``), keys sorted as PyYAML sorts them."""
    parameters: dict[str, Any] = {}
    for name, value in values.items():
        *parents, leaf = name.split(_SEPARATOR)
        place = parameters
        for parent in parents:
            place = place.setdefault(parent, {})
        place[leaf] = value
    return yaml.dump({node: {"ros__parameters": parameters}}, default_flow_style=False)


def write_dump(folder: str, node: str, text: str) -> Path:
    """Write ``text`` to ``FOLDER/NODE.yaml`` (``/ns/name`` as ``ns__name``), as the
    deprecated ``--output-dir`` of ros2 param dump did; the file written."""
    if not os.path.isdir(folder):
        raise UserError(f"'{folder}' is not a valid directory.", expected="an existing folder")
    path = Path(folder) / (node.lstrip("/").replace("/", "__") + ".yaml")
    path.write_text(text, encoding="utf-8")
    return path


def parameters_in_file(path: str, node: str, use_wildcard: bool) -> dict[str, Any]:
    """The ParameterValue of each parameter a file gives ``node``: its ``/**`` entry (unless
    ``use_wildcard`` is off) and then its entry for the node, each value typed as
    ``ros2 param load`` types it (its text read as YAML again)."""
    where = Location(path)
    try:
        with open(path, encoding="utf-8") as file:
            document = yaml.safe_load(file)
    except OSError as error:
        raise ParameterFileError(
            f"cannot read the parameter file: {error.strerror}", where
        ) from None
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        place = Location(path, mark.line + 1, mark.column + 1) if mark else where
        raise ParameterFileError(
            f"not valid YAML: {getattr(error, 'problem', error)}", place
        ) from None
    if not isinstance(document, dict):
        raise ParameterFileError(
            "the file has no node entries", where, expected="'/**:' or '/NODE:' keys"
        )
    keys = [_WILDCARD] if use_wildcard and _WILDCARD in document else []
    keys += [k for k in document if k != _WILDCARD and str(k).lstrip("/") == node.lstrip("/")]
    if not keys:
        raise ParameterFileError(
            f"Param file does not contain parameters for {node}",
            where,
            expected=f"an entry '{node}:' (or '/**:'); the file has {list(document)}",
        )
    values: dict[str, Any] = {}
    for key in keys:
        section = document[key]
        if not isinstance(section, dict) or "ros__parameters" not in section:
            raise ParameterFileError(
                f"YAML file is not a valid ROS parameter file for node {key}",
                where,
                expected=f"{key}: {{ros__parameters: {{name: value}}}}",
            )
        values.update(flatten(section["ros__parameters"] or {}))
    return {name: value_from_text(str(value)) for name, value in values.items()}
