"""Run a ``*.launch.py`` file's ``generate_launch_description()`` against the stand-in modules."""

from __future__ import annotations

import runpy
from pathlib import Path

from launchkit.description.actions.base import Action
from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, LaunchkitError, Location
from launchkit.frontend.python import launch_api as L
from launchkit.frontend.python.modules import stand_in_modules
from launchkit.frontend.python.values import error_location, loading


def load_python_launch(path: Path, included_from: Location | None = None) -> LaunchDescription:
    """The description ``path``'s ``generate_launch_description()`` returns."""
    where = Location(str(path))
    with loading(path, stand_in_modules()):
        try:
            namespace = runpy.run_path(str(path), run_name="__launch__")
            generate = namespace.get("generate_launch_description")
            if not callable(generate):
                raise LaunchFileError(
                    f"'{path.name}' has no generate_launch_description()",
                    where,
                    expected="a Python launch file defining generate_launch_description()",
                )
            result = generate()
        except LaunchkitError:
            raise
        except SyntaxError as error:  # the user's file, or a module it imports
            raise LaunchFileError(
                f"invalid Python: {error.msg}",
                Location(error.filename or str(path), error.lineno or 0, error.offset or 0),
                expected="a Python launch file",
            ) from None
        except ImportError as error:
            raise LaunchFileError(
                f"'{path.name}' imports {error.name or error}, which launchkit does not provide",
                error_location(error) or where,
                expected="launch, launch_ros, ament_index_python and installed Python modules",
            ) from None
        except SystemExit as error:  # sys.exit() in a launch file must not end launchkit
            raise LaunchFileError(
                f"'{path.name}' called sys.exit({error.code!r}) while building its launch "
                "description",
                error_location(error) or where,
                expected="generate_launch_description() returning a LaunchDescription",
            ) from None
        except Exception as error:
            raise LaunchFileError(
                f"'{path.name}' failed while building its launch description: "
                f"{type(error).__name__}: {error}",
                error_location(error) or where,
            ) from None
    if not isinstance(result, L.LaunchDescription):
        raise LaunchFileError(
            "generate_launch_description() did not return a LaunchDescription",
            where,
            expected="return LaunchDescription([...])",
        )
    actions: list[Action] = []
    for entity in result.entities:
        if isinstance(entity, L.LaunchDescription):
            actions.extend(L.flatten(entity, "generate_launch_description()"))
            continue
        if not isinstance(entity, Action):
            raise LaunchFileError(
                f"'{type(entity).__name__}' in the LaunchDescription is not an action",
                where,
                expected="launch actions (DeclareLaunchArgument, Node, ExecuteProcess, ...)",
            )
        actions.append(entity)
    return LaunchDescription(path, actions, None)
