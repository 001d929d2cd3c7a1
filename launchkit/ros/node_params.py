"""The parameter methods of :class:`launchkit.ros.Node`, with rclpy's names and behaviour, over
the node's :class:`~launchkit.ros.parameter_store.ParameterStore`."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from launchkit.ros.exceptions import (
    InvalidParameterTypeException,
    ParameterAlreadyDeclaredException,
    ParameterNotDeclaredException,
)
from launchkit.ros.parameter_store import ParameterStore, SetParametersResult
from launchkit.ros.params import Parameter, Type

__all__ = [
    "InvalidParameterTypeException",
    "ParameterAlreadyDeclaredException",
    "ParameterMethods",
    "ParameterNotDeclaredException",
    "ParameterStore",
    "SetParametersResult",
]


class ParameterMethods:
    """rclpy's parameter methods, mixed into ``Node``."""

    PARAM_REL_TOL = 1e-6
    _params: ParameterStore

    def declare_parameter(
        self,
        name: str,
        value: Any = None,
        descriptor: Any = None,
        ignore_override: bool = False,
    ) -> Parameter:
        """Declare a parameter; a value from ``-p``/``--params-file``/``<param>`` wins unless
        ``ignore_override``. ``value`` may be a ``Parameter.Type`` (statically typed, no value)."""
        return self._params.declare(name, value, descriptor, ignore_override)

    def declare_parameters(
        self, namespace: str, parameters: Sequence[tuple[Any, ...]], ignore_override: bool = False
    ) -> list[Parameter]:
        """Declare several ``(name[, value][, descriptor])`` under ``namespace.``."""
        return self._params.declare_many(namespace, list(parameters), ignore_override)

    def undeclare_parameter(self, name: str) -> None:
        """Undeclare a (not read-only) parameter."""
        self._params.undeclare(name)

    def has_parameter(self, name: str) -> bool:
        """Whether ``name`` is declared."""
        return name in self._params.params

    def get_parameter(self, name: str) -> Parameter:
        """The declared parameter ``name``."""
        return self._params.get(name)

    def get_parameters(self, names: list[str]) -> list[Parameter]:
        """Several parameters."""
        if not all(isinstance(name, str) for name in names):
            raise TypeError("All names must be instances of type str")
        return [self.get_parameter(name) for name in names]

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        """The parameter, or ``alternative_value`` when it is undeclared or has no value."""
        if alternative_value is None:
            alternative_value = Parameter(name, Type.NOT_SET)
        param = self._params.params.get(name)
        if param is None or param.type_ == Type.NOT_SET:
            return alternative_value
        return param

    def get_parameter_type(self, name: str) -> Any:
        """The type of ``name`` (its ``ParameterType`` number when declared, as rclpy)."""
        if name in self._params.params:
            return self._params.params[name].type_.value
        if self._params.allow_undeclared:
            return Type.NOT_SET
        raise ParameterNotDeclaredException(name)

    def get_parameter_types(self, names: list[str]) -> list[Any]:
        """The types of several parameters."""
        if not all(isinstance(name, str) for name in names):
            raise TypeError("All names must be instances of type str")
        return [self.get_parameter_type(name) for name in names]

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        """Parameters under ``prefix.``, keyed by the rest of their name."""
        head = f"{prefix}." if prefix else ""
        return {n[len(head) :]: p for n, p in self._params.params.items() if n.startswith(head)}

    def set_parameters(self, parameter_list: list[Parameter]) -> list[Any]:
        """Set parameters one by one (each may fail on its own)."""
        return self._params.set(parameter_list)

    def set_parameters_atomically(self, parameter_list: list[Parameter]) -> Any:
        """Set all or none."""
        return self._params.set_atomically(parameter_list)

    def describe_parameter(self, name: str) -> Any:
        """The rcl_interfaces/msg/ParameterDescriptor of ``name``."""
        return self._params.describe(name)

    def describe_parameters(self, names: list[str]) -> list[Any]:
        """The descriptors of several parameters."""
        return [self._params.describe(name) for name in names]

    def set_descriptor(self, name: str, descriptor: Any, alternative_value: Any = None) -> Any:
        """Give ``name`` a new descriptor; its value after (a ParameterValue message)."""
        return self._params.set_descriptor(name, descriptor, alternative_value)

    def list_parameters(self, prefixes: list[str], depth: int) -> Any:
        """rcl_interfaces/msg/ListParametersResult: names under ``prefixes`` to ``depth``
        (0: any depth)."""
        from launchkit.ros.msgs import get_message

        if not isinstance(prefixes, list):
            raise TypeError("The prefixes argument must be a list")
        if not all(isinstance(prefix, str) for prefix in prefixes):
            raise TypeError("All prefixes must be instances of type str")
        if not isinstance(depth, int):
            raise TypeError("The depth must be instance of type int")
        if depth < 0:
            raise ValueError("The depth must be greater than or equal to zero")
        names: list[str] = []
        found: list[str] = []
        recursive = not prefixes and depth == 0

        def shallow(name: str) -> bool:
            return name.count(".") < depth

        for name in self._params.params:
            if not recursive and not (not prefixes and shallow(name)):
                if not any(
                    name == prefix
                    or (
                        name.startswith(prefix + ".")
                        and (depth == 0 or shallow(name[len(prefix) + 1 :]))
                    )
                    for prefix in prefixes
                ):
                    continue
            names.append(name)
            head = name.rpartition(".")[0]
            if "." in name and head not in found:
                found.append(head)
        return get_message("rcl_interfaces/msg/ListParametersResult")(names=names, prefixes=found)

    def add_pre_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], list[Parameter]]
    ) -> None:
        """Have ``callback`` rewrite the list of every ``set_parameters*`` call (first added,
        last called)."""
        self._params.pre_set.insert(0, callback)

    def add_on_set_parameters_callback(self, callback: Callable[[list[Parameter]], Any]) -> None:
        """Have ``callback`` approve or reject every parameter change (a SetParametersResult)."""
        if not callable(callback):
            raise TypeError("Callback must be callable, got {}", type(callback))
        self._params.on_set.insert(0, callback)

    def add_post_set_parameters_callback(self, callback: Callable[[list[Parameter]], None]) -> None:
        """Call ``callback`` with the parameters after every successful declare or set."""
        if not callable(callback):
            raise TypeError("Callback must be callable, got {}", type(callback))
        self._params.post_set.insert(0, callback)

    def remove_pre_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], list[Parameter]]
    ) -> None:
        """Stop calling a "pre set" callback (ValueError if it was not added)."""
        self._params.pre_set.remove(callback)

    def remove_on_set_parameters_callback(self, callback: Callable[[list[Parameter]], Any]) -> None:
        """Stop asking an "on set" callback (ValueError if it was not added)."""
        self._params.on_set.remove(callback)

    def remove_post_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], None]
    ) -> None:
        """Stop calling a "post set" callback (ValueError if it was not added)."""
        self._params.post_set.remove(callback)
