"""turtlesim's interfaces: found through the package index, imported the ROS way, with
rosidl's RIHS01 hashes (Jazzy's, and what rosidl's own pipeline computes from the files)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from launchkit.packages import PackageIndex
from launchkit.ros.msgs._registry import Registry
from launchkit.stock.turtlesim import PACKAGE, SHARE

#: Jazzy's turtlesim hashes: rosidl_generator_type_description run on the files of
#: ros/ros_tutorials' turtlesim (1.8.x, the Jazzy release).
JAZZY_HASHES = {
    "turtlesim/msg/Color": (
        "RIHS01_74492579ec0d734707aede0e742ab76c55ac50d3ff917381e5163624cb657fe5"
    ),
    "turtlesim/msg/Pose": (
        "RIHS01_739beba26bcba6920404ba722b7b8321348512f92ea5be235c47251940dd8aa9"
    ),
    "turtlesim/srv/Kill": (
        "RIHS01_81c7c9131a0802f384e515fbd04867f8da57abaa83ee3a0ec76e39091e54bbc3"
    ),
    "turtlesim/srv/SetPen": (
        "RIHS01_45ca246c7258172a89a58856037d6b4489eb46a18f1d8ee1988c018ef46fcfce"
    ),
    "turtlesim/srv/Spawn": (
        "RIHS01_a71be24836f772debd6187dc8618cc47700d2602c7a3e2228bad67a8f5fd27b4"
    ),
    "turtlesim/srv/TeleportAbsolute": (
        "RIHS01_139aa0f215e25dc085067f070adb3ef65cf3c92d201f5cb750d51ca9322166b6"
    ),
    "turtlesim/srv/TeleportRelative": (
        "RIHS01_6e9e54cb05e1a789f982bf8c93d27fc899cee099746c4ea8c7cb64e8a90297d6"
    ),
    "turtlesim/action/RotateAbsolute": (
        "RIHS01_08ba6dd83d976f1cb548edd1f75f16cf30cca624ce1410b6ce77f44b8a3c2895"
    ),
    "turtlesim/action/RotateAbsolute_Goal": (
        "RIHS01_87a85708e2e85bdd56e4c71f41ff36f4d60ad2318c4faff1f85f417d2040a600"
    ),
    "turtlesim/action/RotateAbsolute_Result": (
        "RIHS01_ebf1053164cbc1314956ebea419d429ba9d3236219308838a2c71b1610baf143"
    ),
}


def registry() -> Registry:
    """A registry that knows turtlesim only as the package index knows it."""
    return Registry(PackageIndex(ament_prefix_path="", python_packages={"turtlesim": PACKAGE}))


def test_the_hashes_are_jazzys() -> None:
    reg = registry()
    assert {name: reg.type_hash(name) for name in JAZZY_HASHES} == JAZZY_HASHES


def test_every_hash_is_what_rosidls_pipeline_computes_from_the_files(tmp_path: Path) -> None:
    pytest.importorskip(
        "rosidl_adapter", reason="rosidl's pipeline comes with the ros-jazzy wheels"
    )
    pytest.importorskip("rosidl_generator_type_description")
    from rosidl_adapter.action import convert_action_to_idl
    from rosidl_adapter.msg import convert_msg_to_idl
    from rosidl_adapter.srv import convert_srv_to_idl

    convert = {
        "msg": convert_msg_to_idl,
        "srv": convert_srv_to_idl,
        "action": convert_action_to_idl,
    }
    idl_dir, out = tmp_path / "idl", tmp_path / "json"
    tuples = []
    for path in sorted(p for kind in convert for p in (SHARE / kind).iterdir()):
        relative = path.relative_to(SHARE)
        kind = relative.parts[0]
        idl = convert[kind](SHARE, "turtlesim", relative, idl_dir / kind)
        tuples.append(f"{idl_dir}:{idl.relative_to(idl_dir)}")
    wheels = Path(sys.prefix) / "share"
    deps = ("builtin_interfaces", "service_msgs", "unique_identifier_msgs", "action_msgs")
    arguments = tmp_path / "arguments.json"
    arguments.write_text(
        json.dumps(
            {
                "package_name": "turtlesim",
                "output_dir": str(out),
                "idl_tuples": tuples,
                "include_paths": [f"{name}:{wheels / name}" for name in deps],
            }
        )
    )
    code = "import sys\nfrom rosidl_generator_type_description import generate_type_hash\n"
    code += "generate_type_hash(sys.argv[1])\n"
    subprocess.run(
        [sys.executable, "-c", code, str(arguments)], check=True, timeout=120, capture_output=True
    )
    expected = {
        entry["type_name"]: entry["hash_string"]
        for path in out.rglob("*.json")
        for entry in json.loads(path.read_text())["type_hashes"]
        if entry["type_name"].startswith("turtlesim/")
    }
    assert len(expected) == 35  # 2 messages, 5 services (x5), 1 action (x18)
    reg = registry()
    assert {name: reg.type_hash(name) for name in expected} == expected


def test_turtlesim_imports_as_ros_code_imports_it() -> None:
    code = (
        "import launchkit.ros.msgs as msgs\n"
        "msgs.install()\n"
        "from turtlesim.msg import Pose, Color\n"
        "from turtlesim.srv import Spawn, SetPen\n"
        "from turtlesim.action import RotateAbsolute\n"
        "print(repr(Pose(x=1.5)))\n"
        "print(repr(Spawn.Request(name='leo')))\n"
        "print(Pose.get_fields_and_field_types())\n"
        "print(RotateAbsolute.Feedback().remaining, Color().r)\n"
    )
    env = {**os.environ, "AMENT_PREFIX_PATH": ""}
    done = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [
        "turtlesim.msg.Pose(x=1.5, y=0.0, theta=0.0, linear_velocity=0.0, angular_velocity=0.0)",
        "turtlesim.srv.Spawn_Request(x=0.0, y=0.0, theta=0.0, name='leo')",
        "{'x': 'float', 'y': 'float', 'theta': 'float', 'linear_velocity': 'float', "
        "'angular_velocity': 'float'}",
        "0.0 0",
    ]
