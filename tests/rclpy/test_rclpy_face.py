"""The same small rclpy node files (``nodes/``) print the same on the real rclpy and on
launchkit's.

Each scenario runs once per flavour and its output must be the text below: on launchkit's
rclpy (the face first on ``PYTHONPATH``, a router of the test's own), and, where the ros-jazzy
wheels are installed, on the real rclpy over Fast DDS, which shows that the text is what
rclpy prints (log timestamps are replaced by ``T``).
"""

from __future__ import annotations

import signal
from collections.abc import Callable

import pytest
import scenarios
from rclpy_runs import LAUNCHKIT, REAL, Runs, real_rclpy

FLAVOURS = [LAUNCHKIT, pytest.param(REAL, marks=real_rclpy)]
Make = Callable[[str], Runs]

TALKER_LISTENER = """\
== listener (status 0)
publishers on chatter: 1
-- stderr
[INFO] [T] [listener]: I heard: "Hello World: 0"
[INFO] [T] [listener]: I heard: "Hello World: 1"
[INFO] [T] [listener]: I heard: "Hello World: 2"
[INFO] [T] [listener]: I heard: "Hello World: 3"
[INFO] [T] [listener]: I heard: "Hello World: 4"
== talker (status 0)
-- stderr
[INFO] [T] [talker]: Publishing: "Hello World: 0"
[INFO] [T] [talker]: Publishing: "Hello World: 1"
[INFO] [T] [talker]: Publishing: "Hello World: 2"
[INFO] [T] [talker]: Publishing: "Hello World: 3"
[INFO] [T] [talker]: Publishing: "Hello World: 4"
"""

SERVICE_AND_CLIENT = """\
== caller (status 0)
-- stderr
[INFO] [T] [caller]: sync-style: success=True message='set to True'
[INFO] [T] [caller]: awaited: success=False message='set to False'
== server (status 0)
-- stderr
[INFO] [T] [toggler]: Incoming request: True
[INFO] [T] [toggler]: Incoming request: False
"""

CALLBACK_GROUPS = """\
status 0
mutually exclusive group ran one at a time: True
reentrant group ran callbacks together: True
"""

PARAMETERS = """\
== parameters (status 0)
speed (an override): 3
ParameterAlreadyDeclaredException: Parameter(s) already declared: ['speed']
no error
ParameterNotDeclaredException: Invalid access to undeclared parameter(s): missing
InvalidParameterValueException: Invalid parameter value (20) for parameter. \
Reason: Parameter level out of range. Min: 0, Max: 10, value: 20: level
set: True ''
set: False 'seven is unlucky'
set: False 'Parameter speed out of range. Min: 0, Max: 10, value: 11'
set: False "Wrong parameter type, expected 'Type.INTEGER' got 'Type.DOUBLE'"
set: False 'Parameter gain out of range Min: 0.0, Max: 1.0, value: 1.5'
set: False 'Trying to set a read-only parameter: frame.'
set: True ''
ParameterNotDeclaredException: Invalid access to undeclared parameter(s): []
callbacks saw: ['speed,gain', 'post speed', 'speed,gain', 'anything', 'post anything']
speed now: 5 gain now: 0.25
describe speed: wheel speed
event: new_parameters speed=3
event: new_parameters gain=0.5
event: new_parameters frame='base'
event: new_parameters anything=1
event: new_parameters gain2=1.0
event: new_parameters ratio=2
event: changed_parameters speed=5
event: changed_parameters gain=0.25
-- stderr
"""

ROSOUT = """\
== rosout (status 0)
rosout publishers: ['reader', 'speaker']
rosout qos: TRANSIENT_LOCAL RELIABLE
rosout: 10 speaker 'a debug line' main True
rosout: 20 speaker 'hello rosout' main True
rosout: 30 speaker 'a warning' main True
rosout: 40 speaker 'an error' main True
rosout: 20 speaker.part 'from a child logger' main True
-- stderr
[DEBUG] [T] [speaker]: a debug line
[INFO] [T] [speaker]: hello rosout
[WARN] [T] [speaker]: a warning
[ERROR] [T] [speaker]: an error
[INFO] [T] [speaker.part]: from a child logger
"""

CTRL_C = """\
== stoppable (status 0)
spinning
KeyboardInterrupt; ok(): False
done
-- stderr
"""

EXTERNAL_SHUTDOWN = """\
== stoppable (status 1)
spinning
ExternalShutdownException; ok(): False
-- stderr
"""

UNCAUGHT_CTRL_C = """\
status -2
spinning
first: Traceback (most recent call last):
last: KeyboardInterrupt
"""


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_talker_and_listener(runs: Make, flavour: str) -> None:
    assert scenarios.talker_listener(runs(flavour)) == TALKER_LISTENER


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_service_with_an_async_client_and_a_coroutine_callback(runs: Make, flavour: str) -> None:
    assert scenarios.service_and_client(runs(flavour)) == SERVICE_AND_CLIENT


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_multithreaded_executor_honours_callback_groups(runs: Make, flavour: str) -> None:
    assert scenarios.callback_groups(runs(flavour)) == CALLBACK_GROUPS


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_parameters_descriptors_callbacks_and_events(runs: Make, flavour: str) -> None:
    assert scenarios.parameters(runs(flavour)) == PARAMETERS


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_log_lines_reach_rosout(runs: Make, flavour: str) -> None:
    assert scenarios.rosout(runs(flavour)) == ROSOUT


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_ctrl_c_raises_keyboard_interrupt_from_spin(runs: Make, flavour: str) -> None:
    assert scenarios.stopped(runs(flavour), signal.SIGINT) == CTRL_C


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_a_shutdown_from_outside_raises_external_shutdown(runs: Make, flavour: str) -> None:
    assert scenarios.stopped(runs(flavour), signal.SIGTERM) == EXTERNAL_SHUTDOWN


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_ctrl_c_of_a_node_that_catches_nothing(runs: Make, flavour: str) -> None:
    assert scenarios.uncaught_ctrl_c(runs(flavour)) == UNCAUGHT_CTRL_C
