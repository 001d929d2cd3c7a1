"""A package's own interface files: ``msg/``, ``srv/`` and ``action/`` found through the package
index, with constants, defaults, bounds and types of another package; their RIHS01 hashes
against rosidl's own pipeline (rosidl_adapter + rosidl_generator_type_description, from the
wheels); and the located errors a malformed file gets."""

from __future__ import annotations

import array
import json
import os
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy
import pytest

from launchkit.packages import PackageIndex
from launchkit.ros.msgs import InterfaceFileError
from launchkit.ros.msgs._registry import Registry

THING = "string<=8 label 'abc'\nfloat64[3] xyz [1.0, 2.0, 3.0]\n"
READING = """\
# a reading, as a user writes one
uint8 KIND_RAW=0
uint8 KIND_FILTERED=1
string UNIT="m/s"
std_msgs/Header header
other_pkg/Thing thing
uint8 kind 1
float32 value -1.5
string<=16 sensor "front"
int16[<=4] samples [1, 2]
float64[9] covariance
other_pkg/Thing[] things
bool[2] flags [true, false]
byte code 7
char letter 65
"""
MEASURE = "Reading reading\nbool strict false\n---\nbool ok\nstring<=32 message\n"
MOVE = "# goal\nfloat64 distance 1.0\n---\nfloat64 travelled\n---\nfloat32 progress\nReading last\n"

FILES = {
    "other_pkg": {"msg/Thing.msg": THING},
    "my_pkg": {"msg/Reading.msg": READING, "srv/Measure.srv": MEASURE, "action/Move.action": MOVE},
}


def make_prefix(root: Path, packages: dict[str, dict[str, str]]) -> Path:
    """An ament prefix (as `launchkit build` or colcon lays one out) holding ``packages``."""
    for pkg, files in packages.items():
        marker = root / "share" / "ament_index" / "resource_index" / "packages" / pkg
        marker.parent.mkdir(parents=True, exist_ok=True)
        marker.write_text("")
        for relative, text in files.items():
            path = root / "share" / pkg / relative
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
    return root


@pytest.fixture
def prefixes(tmp_path: Path) -> str:
    """Two prefixes: other_pkg in one, my_pkg (which uses other_pkg's Thing) in the other."""
    first = make_prefix(tmp_path / "first", {"other_pkg": FILES["other_pkg"]})
    second = make_prefix(tmp_path / "second", {"my_pkg": FILES["my_pkg"]})
    return os.pathsep.join([str(second), str(first)])


def registry_of(ament_prefix_path: str) -> Registry:
    return Registry(PackageIndex(ament_prefix_path=ament_prefix_path, python_packages={}))


def test_messages_have_the_files_constants_defaults_and_bounds(prefixes: str) -> None:
    reg = registry_of(prefixes)
    Reading = reg.message_class("my_pkg/msg/Reading")
    reading = Reading()
    assert (Reading.KIND_FILTERED, Reading.UNIT, reading.KIND_RAW) == (1, "m/s", 0)
    assert (reading.kind, reading.value, reading.sensor) == (1, -1.5, "front")
    assert reading.samples == array.array("h", [1, 2]) and reading.flags == [True, False]
    assert (reading.code, reading.letter) == (b"\x07", 65)
    assert isinstance(reading.covariance, numpy.ndarray) and reading.covariance.shape == (9,)
    assert reading.thing.label == "abc" and list(reading.thing.xyz) == [1.0, 2.0, 3.0]
    assert type(reading.header).__module__ == "std_msgs.msg._header"
    assert Reading.get_fields_and_field_types()["sensor"] == "string<16>"
    assert Reading.get_fields_and_field_types()["samples"] == "sequence<int16, 4>"
    assert Reading.get_fields_and_field_types()["things"] == "sequence<other_pkg/Thing>"
    assert repr(Reading.SENSOR__DEFAULT) == "'front'"
    with pytest.raises(AssertionError, match="string value not longer than 16"):
        Reading(check_fields=True, sensor="x" * 17)
    too_long = re.escape("'samples' array.array() must have a size <= 4")
    with pytest.raises(AssertionError, match=too_long):
        Reading(check_fields=True).samples = array.array("h", [0] * 5)
    assert repr(reading).startswith("my_pkg.msg.Reading(header=std_msgs.msg.Header(")


def test_services_and_actions_expand_as_rosidls(prefixes: str) -> None:
    reg = registry_of(prefixes)
    Measure = reg.service_class("my_pkg/srv/Measure")
    assert Measure.Request().strict is False and Measure.Response().message == ""
    assert Measure.Request.__module__ == "my_pkg.srv._measure"
    event = Measure.Event()
    assert event.request == [] and type(event.info).__name__ == "ServiceEventInfo"
    Move = reg.action_class("my_pkg/action/Move")
    assert Move.Goal().distance == 1.0 and Move.Feedback().last.kind == 1
    request = Move.Impl.SendGoalService.Request()
    assert repr(request) == (
        "my_pkg.action.Move_SendGoal_Request(goal_id=unique_identifier_msgs.msg.UUID(uuid="
        "array([0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0], dtype=uint8)), "
        "goal=my_pkg.action.Move_Goal(distance=1.0))"
    )
    assert list(Move.Impl.SendGoalService.Response.get_fields_and_field_types()) == [
        "accepted",
        "stamp",
    ]
    assert list(Move.Impl.GetResultService.Response.get_fields_and_field_types()) == [
        "status",
        "result",
    ]
    assert list(Move.Impl.FeedbackMessage.get_fields_and_field_types()) == ["goal_id", "feedback"]
    assert Move.Impl.CancelGoalService.__name__ == "CancelGoal"
    assert Move.Impl.GoalStatusMessage.__name__ == "GoalStatusArray"
    with pytest.raises(NotImplementedError, match="Action classes can not be instantiated"):
        Move()


def test_custom_messages_round_trip(prefixes: str) -> None:
    reg = registry_of(prefixes)
    Reading = reg.message_class("my_pkg/msg/Reading")
    Thing = reg.message_class("other_pkg/msg/Thing")
    reading = Reading(sensor="rear", samples=[3, -4, 5], things=[Thing(label="b"), Thing()])
    reading.covariance[4] = 2.5
    codec = reg.codec("my_pkg/msg/Reading")
    back = codec.deserialize(codec.serialize(reading))
    assert repr(back) == repr(reading) and back == reading


def rosidl_hashes(root: Path, prefix: str, pkg: str, deps: dict[str, Path]) -> dict[str, str]:
    """The RIHS01 hashes rosidl computes for ``pkg``'s files (rosidl_adapter writes .idl,
    rosidl_generator_type_description hashes them): every hash its JSON files list."""
    from rosidl_adapter.action import convert_action_to_idl
    from rosidl_adapter.msg import convert_msg_to_idl
    from rosidl_adapter.srv import convert_srv_to_idl

    convert = {
        "msg": convert_msg_to_idl,
        "srv": convert_srv_to_idl,
        "action": convert_action_to_idl,
    }
    share = Path(prefix) / "share" / pkg
    idl_dir, out = root / f"{pkg}_idl", root / f"{pkg}_json"
    tuples = []
    for relative in FILES[pkg]:
        kind = relative.split("/")[0]
        idl = convert[kind](share, pkg, Path(relative), idl_dir / kind)
        tuples.append(f"{idl_dir}:{idl.relative_to(idl_dir)}")
    arguments = root / f"{pkg}_args.json"
    arguments.write_text(
        json.dumps(
            {
                "package_name": pkg,
                "output_dir": str(out),
                "idl_tuples": tuples,
                "include_paths": [f"{name}:{path}" for name, path in deps.items()],
            }
        )
    )
    code = (
        "import sys\n"
        "from rosidl_generator_type_description import generate_type_hash\n"
        "generate_type_hash(sys.argv[1])\n"
    )
    subprocess.run([sys.executable, "-c", code, str(arguments)], check=True, timeout=120)
    found: dict[str, str] = {}
    for path in out.rglob("*.json"):
        for entry in json.loads(path.read_text())["type_hashes"]:
            found[entry["type_name"]] = entry["hash_string"]
    return found


def test_hashes_of_a_users_package_are_rosidls(tmp_path: Path, prefixes: str) -> None:
    pytest.importorskip(
        "rosidl_adapter", reason="rosidl's pipeline comes with the ros-jazzy wheels"
    )
    pytest.importorskip("rosidl_generator_type_description")
    wheels = Path(sys.prefix) / "share"
    deps = {
        name: wheels / name
        for name in ("std_msgs", "builtin_interfaces", "service_msgs", "unique_identifier_msgs")
    }
    second, first = prefixes.split(os.pathsep)
    expected = rosidl_hashes(tmp_path, first, "other_pkg", deps)
    deps["other_pkg"] = tmp_path / "other_pkg_json"
    expected.update(rosidl_hashes(tmp_path, second, "my_pkg", deps))
    assert "my_pkg/action/Move_SendGoal_Event" in expected and "my_pkg/srv/Measure" in expected
    reg = registry_of(prefixes)
    assert {name: reg.type_hash(name) for name in expected} == expected


BAD_FILES = [
    ("msg/Bad.msg", "int32 a\nint32 = 5\n", 2, 1, "cannot read 'int32 = 5'"),
    ("msg/Bad.msg", "int32 a\nint32 b c d e\n", 2, 1, "'c d e' is not a valid int32 value"),
    ("msg/Bad.msg", "int32 ok\n\nnope_pkg/Missing m\n", 3, 1, "unknown message type"),
    ("msg/Bad.msg", "int32 ok\n  Missing m\n", 2, 3, "'my_pkg/msg/Missing'"),
    ("msg/Bad.msg", "int32 Upper\n", 1, 1, "field name 'Upper' is not allowed"),
    ("msg/Bad.msg", "int32 a\nfloat64 a\n", 2, 1, "'a' is defined twice (first on line 1)"),
    ("msg/Bad.msg", "uint8 a 300\n", 1, 1, "300 is not a valid uint8 value"),
    ("msg/Bad.msg", "int8 small=1\n", 1, 1, "cannot read"),
    ("msg/Bad.msg", "string<=3 s 'toolong'\n", 1, 1, "longer than 3"),
    ("msg/Bad.msg", "int32[2] a [1, 2, 3]\n", 1, 1, "default has 3 values"),
    ("msg/Bad.msg", "wstring w\n", 1, 1, "wide strings are not supported"),
    ("srv/Bad.srv", "int32 a\n", 1, 1, "0 '---' separator lines in a service"),
    ("srv/Bad.srv", "int32 a\n---\nint32 b\n---\n", 4, 1, "2 '---' separator lines"),
    ("srv/Bad.srv", "int32 a\n---\n# the answer\nGhost g\n", 4, 1, "'my_pkg/msg/Ghost'"),
    ("action/Bad.action", "int32 a\n---\nint32 b\n", 1, 1, "1 '---' separator lines"),
]


@pytest.mark.parametrize(("relative", "text", "line", "col", "words"), BAD_FILES)
def test_malformed_files_get_located_errors(
    tmp_path: Path, relative: str, text: str, line: int, col: int, words: str
) -> None:
    prefix = make_prefix(tmp_path, {"my_pkg": {relative: text, "msg/Good.msg": "int32 x\n"}})
    reg = registry_of(str(prefix))
    kind, name = relative.split("/")
    with pytest.raises(InterfaceFileError) as caught:
        reg.spec(f"my_pkg/{kind}/{name.split('.')[0]}" + ("_Request" if kind == "srv" else ""))
    path = prefix / "share" / "my_pkg" / relative
    assert str(caught.value).startswith(f"{path}:{line}:{col}: error: "), str(caught.value)
    assert words in str(caught.value)
    assert reg.message_class("my_pkg/msg/Good")().x == 0  # one bad file hides nothing else


def test_the_cli_reports_a_bad_file_on_one_line(tmp_path: Path) -> None:
    prefix = make_prefix(tmp_path, {"my_pkg": {"msg/Bad.msg": "int32 a\nint32 = 5\n"}})
    env = {**os.environ, "AMENT_PREFIX_PATH": str(prefix)}
    done = subprocess.run(
        [sys.executable, "-m", "launchkit", "interface", "show", "my_pkg/msg/Bad"],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    path = prefix / "share" / "my_pkg" / "msg" / "Bad.msg"
    assert done.returncode == 2, done.stderr
    assert done.stderr.strip().splitlines()[0].startswith(f"{path}:2:1: error: cannot read")
    assert "Traceback" not in done.stderr


def test_launchkit_prefix_serves_user_packages(prefixes: str) -> None:
    code = (
        "from launchkit.ros.msgs.my_pkg.msg import Reading\n"
        "from launchkit.ros.msgs.my_pkg.action import Move\n"
        "print(Reading().sensor, Move.Goal().distance)\n"
    )
    env: dict[str, Any] = {**os.environ, "AMENT_PREFIX_PATH": prefixes}
    done = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["front", "1.0"]


HOOK_PROBE = """
import sys
import launchkit.ros.msgs as msgs
msgs.install()
from std_msgs.msg import String
from std_msgs.msg._string import String as same_string
from launchkit.ros.msgs.std_msgs.msg import String as prefixed
from example_interfaces.srv import AddTwoInts
from my_pkg.action import Move
from my_pkg.msg import Reading
import std_msgs
print(msgs.is_message(String()), String is same_string is prefixed)
print(std_msgs.__spec__.loader is sys.meta_path[0], repr(String(data="hi")))
print(AddTwoInts.Request(a=1, b=2), Move.Goal().distance, Reading().sensor)
"""


def test_the_import_hook_shadows_installed_message_packages(prefixes: str) -> None:
    """In a fresh process with the hook installed, ``std_msgs.msg`` is launchkit's even where
    the real one is installed (the test venv has the ros-jazzy wheels), and a user's package
    from AMENT_PREFIX_PATH imports the rclpy way."""
    env = {**os.environ, "AMENT_PREFIX_PATH": prefixes}
    done = subprocess.run(
        [sys.executable, "-c", HOOK_PROBE], env=env, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [
        "True True",
        "True std_msgs.msg.String(data='hi')",
        "example_interfaces.srv.AddTwoInts_Request(a=1, b=2) 1.0 front",
    ]


def test_the_cli_lists_and_shows_a_users_interfaces(prefixes: str) -> None:
    env = {**os.environ, "AMENT_PREFIX_PATH": prefixes}

    def launchkit(*args: str) -> list[str]:
        done = subprocess.run(
            [sys.executable, "-m", "launchkit", "interface", *args],
            env=env,
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert done.returncode == 0, done.stderr
        return done.stdout.splitlines()

    listed = [line.strip() for line in launchkit("list")]
    assert {"my_pkg/msg/Reading", "my_pkg/srv/Measure", "my_pkg/action/Move"} <= set(listed)
    assert listed.index("my_pkg/action/Move") > listed.index("Actions:")
    # the file as ros2 interface show prints it: comments and defaults kept, the nested type's
    # fields under its field
    assert launchkit("show", "my_pkg/action/Move")[:6] == [
        "# goal",
        "float64 distance 1.0",
        "---",
        "float64 travelled",
        "---",
        "float32 progress",
    ]
