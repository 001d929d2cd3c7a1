"""A node's parameters as rclpy keeps them: values, descriptors, callbacks, events.

Descriptors decide what a set may do (read-only, static or dynamic typing, integer and
floating-point ranges); the "pre set" callbacks may rewrite a set, the "on set" callbacks
approve or reject it, the "post set" callbacks see what was set; every successful declare or
set is reported to ``on_event`` as rcl_interfaces/msg/ParameterEvent's three lists (the node
publishes it on ``/parameter_events``).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from typing import Any

from launchkit.ros.exceptions import (
    InvalidParameterTypeException,
    InvalidParameterValueException,
    ParameterAlreadyDeclaredException,
    ParameterImmutableException,
    ParameterNotDeclaredException,
    ParameterUninitializedException,
)
from launchkit.ros.msgs import get_message
from launchkit.ros.params import Parameter, Type, parameter_from_value

PARAM_REL_TOL = 1e-6  # rclpy's tolerance for floating-point range ends and steps

# (new, changed, deleted) rcl_interfaces/msg/Parameter lists of one successful change
EventHook = Callable[[list[Any], list[Any], list[Any]], None]


def descriptor_message(**fields: Any) -> Any:
    """An rcl_interfaces/msg/ParameterDescriptor."""
    return get_message("rcl_interfaces/msg/ParameterDescriptor")(**fields)


def result_message(successful: bool, reason: str = "") -> Any:
    """An rcl_interfaces/msg/SetParametersResult."""
    return get_message("rcl_interfaces/msg/SetParametersResult")(
        successful=successful, reason=reason
    )


def SetParametersResult(successful: bool = False, reason: str = "") -> Any:
    """rcl_interfaces/msg/SetParametersResult, what an "on set" callback returns."""
    return result_message(successful, reason)


class ParameterStore:
    """Holds a node's parameters, their descriptors and callbacks, and the values given to it
    from outside (``overrides``: ``-p``, params files, a launch file's ``<param>``)."""

    def __init__(
        self,
        overrides: dict[str, Any],
        allow_undeclared: bool,
        on_event: EventHook | None = None,
    ) -> None:
        self.overrides = dict(overrides)
        self.allow_undeclared = allow_undeclared
        self.params: dict[str, Parameter] = {}
        self.descriptors: dict[str, Any] = {}
        self.pre_set: list[Callable[[list[Parameter]], list[Parameter]]] = []
        self.on_set: list[Callable[[list[Parameter]], Any]] = []
        self.post_set: list[Callable[[list[Parameter]], None]] = []
        self.on_event = on_event

    # declaring ------------------------------------------------------------------------------
    def declare(
        self,
        name: str,
        value: Any = None,
        descriptor: Any = None,
        ignore_override: bool = False,
    ) -> Parameter:
        """Declare one parameter (``declare_parameter``)."""
        entry: tuple[Any, ...] = (name,)
        if value is not None or descriptor is not None:
            entry = (name, value, descriptor if descriptor is not None else descriptor_message())
        return self.declare_many("", [entry], ignore_override)[0]

    def declare_many(
        self, namespace: str, entries: list[tuple[Any, ...]], ignore_override: bool = False
    ) -> list[Parameter]:
        """Declare ``(name[, value or Parameter.Type[, descriptor]])`` entries under
        ``namespace.`` (``declare_parameters``)."""
        declared: list[Parameter] = []
        descriptors: dict[str, Any] = {}
        for index, entry in enumerate(entries):
            if not 1 <= len(entry) <= 3:
                raise TypeError(
                    f"Invalid parameter tuple length at index {index} in parameters list: "
                    f"{entry}; expecting length between 1 and 3"
                )
            name = entry[0]
            if not isinstance(name, str):
                raise TypeError(
                    f"First element {name} at index {index} in parameters list is not a str."
                )
            if namespace:
                name = f"{namespace}.{name}"
            second = entry[1] if len(entry) > 1 else None
            descriptor = entry[2] if len(entry) > 2 else descriptor_message()
            if len(entry) == 1:
                warnings.warn(
                    f"when declaring parameter named '{name}', declaring a parameter only "
                    "providing its name is deprecated. You have to either:\n"
                    '\t- Pass a name and a default value different to "PARAMETER NOT SET"'
                    " (and optionally a descriptor).\n"
                    "\t- Pass a name and a parameter type.\n"
                    "\t- Pass a name and a descriptor with `dynamic_typing=True",
                    stacklevel=3,
                )
                descriptor.dynamic_typing = True
            value = None
            if isinstance(second, Type):
                if second == Type.NOT_SET:
                    raise ValueError(
                        f"Cannot declare parameter {{{name}}} as statically typed of type NOT_SET"
                    )
                if descriptor.dynamic_typing:
                    raise ValueError(
                        f"When declaring parameter {{{name}}} passing a descriptor with"
                        "`dynamic_typing=True` is not allowed when the parameter type is provided"
                    )
                descriptor.type = second.value
            else:
                value = second
                if not descriptor.dynamic_typing:
                    descriptor.type = Type.from_parameter_value(value).value
                    if descriptor.type == Type.NOT_SET.value:
                        raise ValueError(
                            "Cannot declare a statically typed parameter with default value "
                            "of type PARAMETER_NOT_SET"
                        )
            if not ignore_override and name in self.overrides:
                value = parameter_from_value(name, self.overrides[name]).value
            declared.append(Parameter(name, value=value))
            descriptors[name] = descriptor
        already = [p.name for p in declared if p.name in self.params]
        if already:
            raise ParameterAlreadyDeclaredException(already)
        for param in declared:
            result = self._set_common([param], descriptors, allow_not_set=True)
            if not result.successful:
                if result.reason.startswith("Wrong parameter type"):
                    expected = Type(descriptors[param.name].type).name
                    raise InvalidParameterTypeException(param, expected)
                raise InvalidParameterValueException(param.name, param.value, result.reason)
        return [self.params[p.name] for p in declared]

    def undeclare(self, name: str) -> None:
        """Forget a declared parameter (not a read-only one)."""
        if name not in self.params:
            raise ParameterNotDeclaredException(name)
        if self.descriptors[name].read_only:
            raise ParameterImmutableException(name)
        del self.params[name]
        del self.descriptors[name]

    # reading --------------------------------------------------------------------------------
    def get(self, name: str) -> Parameter:
        """The parameter ``name`` (``get_parameter``'s errors)."""
        if name in self.params:
            param = self.params[name]
            if param.type_ != Type.NOT_SET or self.descriptors[name].dynamic_typing:
                return param
            raise ParameterUninitializedException(name)
        if self.allow_undeclared:
            return Parameter(name, Type.NOT_SET, None)
        raise ParameterNotDeclaredException(name)

    def describe(self, name: str) -> Any:
        """The descriptor of ``name`` (a blank one for an undeclared name when allowed)."""
        try:
            return self.descriptors[name]
        except KeyError:
            if self.allow_undeclared:
                return descriptor_message()
            raise ParameterNotDeclaredException(name) from None

    # setting --------------------------------------------------------------------------------
    def set(self, params: list[Parameter]) -> list[Any]:
        """Set each parameter on its own; a result each."""
        return [self.set_atomically([param]) for param in params]

    def set_atomically(self, params: list[Parameter]) -> Any:
        """Set all or none (the "pre set" callbacks may change the list first)."""
        if self.pre_set:
            changed: list[Parameter] = []
            for callback in self.pre_set:
                changed.extend(callback(params))
            params = changed
            if not params:
                return result_message(
                    False,
                    "parameter list cannot be empty, this might be due to "
                    "pre_set_parameters_callback modifying the original parameters list.",
                )
        if not all(isinstance(p, Parameter) for p in params):
            raise TypeError(f"parameter must be instance of type '{Parameter!r}'")
        undeclared = (p.name for p in params if p.name not in self.params)
        if not self.allow_undeclared and any(undeclared):
            # the names after the first, as rclpy's generator leaves them
            raise ParameterNotDeclaredException(list(undeclared))
        return self._set_common(params)

    def set_descriptor(self, name: str, descriptor: Any, alternative_value: Any = None) -> Any:
        """Give ``name`` a new descriptor (its value, or ``alternative_value``, must fit it);
        the value after, as rcl_interfaces/msg/ParameterValue."""
        if name not in self.params:
            if not self.allow_undeclared:
                raise ParameterNotDeclaredException(name)
            return self.get(name).get_parameter_value()
        if self.describe(name).read_only:
            raise ParameterImmutableException(name)
        current = self.get(name)
        alternative = current
        if alternative_value is not None:
            alternative = Parameter.from_msg_value(name, alternative_value)
        if not self._apply_and_store(current, descriptor).successful:
            result = self._apply_and_store(alternative, descriptor)
            if not result.successful:
                raise InvalidParameterValueException(name, alternative.value, result.reason)
        self.descriptors[name] = descriptor
        return self.get(name).get_parameter_value()

    def _apply_and_store(self, param: Parameter, descriptor: Any) -> Any:
        result = self._apply_descriptor(param, descriptor, False)
        if result.successful:
            self.params[param.name] = param
        return result

    def _set_common(
        self,
        params: list[Parameter],
        descriptors: dict[str, Any] | None = None,
        allow_not_set: bool = False,
    ) -> Any:
        if descriptors is not None:
            result = self._apply_descriptors(params, descriptors, False)
        else:
            result = self._apply_descriptors(params, self.descriptors, True)
        if not result.successful:
            return result
        for callback in self.on_set:
            result = callback(params)
            if not hasattr(result, "successful"):
                warnings.warn(
                    "Callback returned an invalid type, it should return SetParameterResult.",
                    stacklevel=3,
                )
                result = result_message(False, "Callback returned an invalid type")
            if not result.successful:
                return result
        new: list[Any] = []
        changed: list[Any] = []
        deleted: list[Any] = []
        for param in params:
            if not allow_not_set and param.type_ == Type.NOT_SET:
                deleted.append(param.to_parameter_msg())
                self.params.pop(param.name, None)
                self.descriptors.pop(param.name, None)
                continue
            if descriptors is not None:
                self.descriptors[param.name] = descriptors[param.name]
            elif param.name not in self.descriptors:
                self.descriptors[param.name] = descriptor_message(dynamic_typing=True)
            previous = self.params.get(param.name)
            if previous is None or previous.type_ == Type.NOT_SET:
                new.append(param.to_parameter_msg())
            else:
                changed.append(param.to_parameter_msg())
            self.params[param.name] = param
        if self.on_event is not None:
            self.on_event(new, changed, deleted)
        for post in self.post_set:
            post(params)
        return result_message(True)

    def _apply_descriptors(
        self, params: list[Parameter], descriptors: dict[str, Any], check_read_only: bool
    ) -> Any:
        for param in params:
            if param.name in descriptors:
                result = self._apply_descriptor(param, descriptors[param.name], check_read_only)
                if not result.successful:
                    return result
        return result_message(True)

    def _apply_descriptor(self, param: Parameter, descriptor: Any, check_read_only: bool) -> Any:
        descriptor.name = param.name
        if check_read_only and descriptor.read_only:
            return result_message(False, f"Trying to set a read-only parameter: {param.name}.")
        if descriptor.dynamic_typing:
            descriptor.type = param.type_.value
        elif param.name in self.params and param.type_ == Type.NOT_SET:
            return result_message(False, "Static parameter cannot be undeclared")
        elif param.type_ != Type.NOT_SET and param.type_.value != descriptor.type:
            return result_message(
                False,
                f"Wrong parameter type, expected '{Type(descriptor.type)}' got '{param.type_}'",
            )
        if param.type_ == Type.INTEGER and len(descriptor.integer_range):
            return _integer_in_range(param, descriptor.integer_range[0])
        if param.type_ == Type.DOUBLE and len(descriptor.floating_point_range):
            return _double_in_range(param, descriptor.floating_point_range[0])
        return result_message(True)


def _integer_in_range(param: Parameter, bounds: Any) -> Any:
    low = min(bounds.from_value, bounds.to_value)
    high = max(bounds.from_value, bounds.to_value)
    value = param.value
    if value in (low, high):
        return result_message(True)
    if not low < value < high:
        return result_message(
            False,
            f"Parameter {param.name} out of range. Min: {low}, Max: {high}, value: {value}",
        )
    if bounds.step != 0 and (value - low) % bounds.step != 0:
        return result_message(
            False,
            f"The parameter value for {param.name} is not a valid step. "
            f"Min: {low}, max: {high}, value: {value}, step: {bounds.step}",
        )
    return result_message(True)


def _double_in_range(param: Parameter, bounds: Any) -> Any:
    low = min(bounds.from_value, bounds.to_value)
    high = max(bounds.from_value, bounds.to_value)
    value = param.value
    if math.isclose(value, low, rel_tol=PARAM_REL_TOL) or math.isclose(
        value, high, rel_tol=PARAM_REL_TOL
    ):
        return result_message(True)
    if not low < value < high:
        return result_message(
            False,
            f"Parameter {param.name} out of range Min: {low}, Max: {high}, value: {value}",
        )
    if bounds.step != 0.0:
        steps = round((value - low) / bounds.step)
        if not math.isclose(low + steps * bounds.step, value, rel_tol=PARAM_REL_TOL):
            return result_message(
                False,
                f"The parameter value for {param.name} is not close enough to a valid step. "
                f"Min: {low}, max: {high}, value: {value}, step: {bounds.step}",
            )
    return result_message(True)
