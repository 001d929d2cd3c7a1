"""A node's parameter store: declare, get, set, with overrides and type checks (rclpy rules),
and the parameter methods :class:`launchkit.ros.Node` offers over it."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from launchkit.ros.params import Parameter, ParameterType


class ParameterNotDeclaredException(Exception):
    """A parameter was read or set before it was declared."""


class ParameterAlreadyDeclaredException(Exception):
    """``declare_parameter`` for a name that exists."""


class InvalidParameterTypeException(Exception):
    """A value whose type differs from the declared one."""


@dataclass
class SetParametersResult:
    """Whether setting parameters succeeded (rcl_interfaces/msg/SetParametersResult)."""

    successful: bool
    reason: str = ""


SetCallback = Callable[[list[Parameter]], SetParametersResult]


class ParameterStore:
    """Holds a node's parameters and the values given to it from outside."""

    def __init__(self, overrides: dict[str, Any], allow_undeclared: bool) -> None:
        self.overrides = dict(overrides)
        self.allow_undeclared = allow_undeclared
        self.params: dict[str, Parameter] = {}
        self.descriptors: dict[str, Any] = {}
        self.on_set: list[SetCallback] = []
        self.post_set: list[Callable[[list[Parameter]], None]] = []

    def declare(
        self,
        name: str,
        default: Any = None,
        descriptor: Any = None,
        ignore_override: bool = False,
    ) -> Parameter:
        """Declare ``name``; an override from the command line or a file wins over ``default``."""
        if name in self.params:
            raise ParameterAlreadyDeclaredException(f"parameter '{name}' is already declared")
        if isinstance(default, Parameter):
            default = default.value
        value = default
        if not ignore_override and name in self.overrides:
            value = self.overrides[name]
        declared_type = ParameterType.from_value(default) if default is not None else None
        param = Parameter(name, value=value)
        if declared_type is not None and param.type_ != declared_type:
            # as rclpy: no conversion, not even of an integer to a double
            raise InvalidParameterTypeException(
                f"Trying to set parameter '{name}' to '{value}' of type "
                f"'{param.type_.name}', expecting type '{declared_type.name}': {name}"
            )
        result = self._check([param])
        if not result.successful:
            raise InvalidParameterTypeException(f"parameter '{name}' rejected: {result.reason}")
        self.params[name] = param
        self.descriptors[name] = declared_type
        for callback in self.post_set:
            callback([param])
        return param

    def get(self, name: str) -> Parameter:
        """The parameter ``name`` (undeclared: error unless undeclared ones are allowed)."""
        if name in self.params:
            return self.params[name]
        if self.allow_undeclared:
            return Parameter(name, ParameterType.NOT_SET, None)
        raise ParameterNotDeclaredException(f"parameter '{name}' is not declared")

    def set(self, params: list[Parameter]) -> list[SetParametersResult]:
        """Set each parameter in turn; each gets its own result."""
        return [self.set_atomically([p]) for p in params]

    def set_atomically(self, params: list[Parameter]) -> SetParametersResult:
        """Set all or none."""
        for param in params:
            if param.name not in self.params and not self.allow_undeclared:
                return SetParametersResult(False, f"parameter '{param.name}' is not declared")
            declared = self.descriptors.get(param.name)
            if (
                declared is not None
                and param.type_ != declared
                and param.type_ != ParameterType.NOT_SET
            ):
                return SetParametersResult(
                    False,
                    f"Wrong parameter type, expected 'Type.{declared.name}' "
                    f"got 'Type.{param.type_.name}'",
                )
        result = self._check(params)
        if not result.successful:
            return result
        for param in params:
            if param.type_ == ParameterType.NOT_SET:
                self.params.pop(param.name, None)
            else:
                self.params[param.name] = param
                self.descriptors.setdefault(param.name, param.type_)
        for callback in self.post_set:
            callback(params)
        return SetParametersResult(True)

    def _check(self, params: list[Parameter]) -> SetParametersResult:
        for callback in self.on_set:
            result = callback(params)
            if not getattr(result, "successful", False):
                return SetParametersResult(False, str(getattr(result, "reason", "")))
        return SetParametersResult(True)


class ParameterMethods:
    """The parameter methods of :class:`launchkit.ros.Node`, with rclpy's names, over the
    node's :class:`ParameterStore`."""

    _params: ParameterStore

    def declare_parameter(
        self,
        name: str,
        value: Any = None,
        descriptor: Any = None,
        ignore_override: bool = False,
    ) -> Parameter:
        """Declare a parameter; a value from ``-p``/``--params-file``/``<param>`` wins."""
        return self._params.declare(name, value, descriptor, ignore_override)

    def declare_parameters(
        self, namespace: str, parameters: Sequence[tuple[Any, ...]], ignore_override: bool = False
    ) -> list[Parameter]:
        """Declare several ``(name, default[, descriptor])`` under ``namespace.``."""
        prefix = f"{namespace}." if namespace else ""
        return [
            self.declare_parameter(
                prefix + entry[0],
                entry[1] if len(entry) > 1 else None,
                entry[2] if len(entry) > 2 else None,
                ignore_override,
            )
            for entry in parameters
        ]

    def has_parameter(self, name: str) -> bool:
        """Whether ``name`` is declared."""
        return name in self._params.params

    def get_parameter(self, name: str) -> Parameter:
        """The declared parameter ``name``."""
        return self._params.get(name)

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        """The parameter, or ``alternative_value`` when it is not declared."""
        if name in self._params.params:
            return self._params.params[name]
        return alternative_value or Parameter(name, Parameter.Type.NOT_SET, None)

    def get_parameters(self, names_: list[str]) -> list[Parameter]:
        """Several parameters."""
        return [self.get_parameter(n) for n in names_]

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        """Parameters under ``prefix.``, keyed by the rest of their name."""
        head = f"{prefix}." if prefix else ""
        return {n[len(head) :]: p for n, p in self._params.params.items() if n.startswith(head)}

    def set_parameters(self, parameter_list: list[Parameter]) -> list[SetParametersResult]:
        """Set parameters one by one (each may fail on its own)."""
        return self._params.set(parameter_list)

    def set_parameters_atomically(self, parameter_list: list[Parameter]) -> SetParametersResult:
        """Set all or none."""
        return self._params.set_atomically(parameter_list)

    def add_on_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], SetParametersResult]
    ) -> None:
        """Have ``callback`` approve or reject every parameter change."""
        self._params.on_set.append(callback)

    def remove_on_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], SetParametersResult]
    ) -> None:
        """Stop asking ``callback``."""
        self._params.on_set.remove(callback)
