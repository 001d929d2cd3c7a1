"""``~/get_logger_levels`` and ``~/set_logger_levels``: a node's logger levels over services
(rclpy's ``enable_logger_service=True``)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from launchkit.ros.logging import LoggingSeverity, get_logger_level, set_logger_level
from launchkit.ros.msgs import get_message, get_service
from launchkit.ros.qos import qos_profile_services_default

# a node's create_service
MakeService = Callable[..., Any]


class LoggerService:
    """Serves the levels of this process's loggers, by name."""

    def __init__(self, create_service: MakeService, node_name: str) -> None:
        self._level_type = get_message("rcl_interfaces/msg/LoggerLevel")
        self._result_type = get_message("rcl_interfaces/msg/SetLoggerLevelsResult")
        name = node_name
        create_service(
            get_service("rcl_interfaces/srv/GetLoggerLevels"),
            f"{name}/get_logger_levels",
            self._get,
            qos_profile=qos_profile_services_default,
        )
        create_service(
            get_service("rcl_interfaces/srv/SetLoggerLevels"),
            f"{name}/set_logger_levels",
            self._set,
            qos_profile=qos_profile_services_default,
        )

    def _get(self, request: Any, response: Any) -> Any:
        response.levels = [
            self._level_type(name=name, level=int(get_logger_level(name))) for name in request.names
        ]
        return response

    def _set(self, request: Any, response: Any) -> Any:
        results = []
        for item in request.levels:
            result = self._result_type(successful=False, reason="")
            try:
                set_logger_level(item.name, LoggingSeverity(item.level), detailed_error=True)
                result.successful = True
            except ValueError:
                result.reason = "Failed reason: Invalid logger level."
            results.append(result)
        response.results = results
        return response
