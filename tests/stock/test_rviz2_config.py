"""Reading .rviz display configs: fixed frame, displays and their topics, clear errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.errors import UserError
from launchkit.stock.rviz2.config import Display, default_config, load_config, parse_config

SHIPPED = Path(__file__).parents[2] / "config" / "robot.rviz"  # robot_wheel's

CONFIG = """
Panels:
  - Class: rviz_common/Displays
Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz_default_plugins/Grid
      Name: Grid
      Enabled: true
    - Class: rviz_default_plugins/RobotModel
      Name: RobotModel
      Enabled: true
      Description Source: Topic
      Description Topic:
        Value: /robot_description
    - Class: rviz_common/Group
      Name: Sensors
      Displays:
        - Class: rviz_default_plugins/LaserScan
          Name: LaserScan
          Enabled: true
          Topic:
            Value: /scan
        - Class: rviz_default_plugins/Image
          Name: Camera
          Enabled: false
          Topic:
            Value: /camera/image_raw
  Global Options:
    Fixed Frame: odom
"""


def test_fixed_frame_displays_and_topics() -> None:
    config = parse_config(CONFIG)
    assert config.fixed_frame == "odom"
    assert Display("rviz_default_plugins/LaserScan", "LaserScan", True, "/scan") in config.displays
    assert config.topics == ["/robot_description", "/scan"]


def test_shipped_config_reads() -> None:
    config = load_config(SHIPPED)
    assert config.fixed_frame == "odom"
    assert "/robot_description" in config.topics


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("Visualization Manager: [unclosed", "not valid YAML"),
        ("Panels: []\n", "no 'Visualization Manager' mapping"),
        ("- just a list\n", "no 'Visualization Manager' mapping"),
    ],
)
def test_malformed_configs_are_user_errors(text: str, message: str) -> None:
    with pytest.raises(UserError, match=message) as caught:
        parse_config(text, "robot.rviz")
    assert caught.value.format().startswith("robot.rviz")


def test_missing_file_names_the_path(tmp_path: Path) -> None:
    with pytest.raises(UserError, match="cannot read the display config") as caught:
        load_config(tmp_path / "nope.rviz")
    assert str(tmp_path / "nope.rviz") in caught.value.format()


def test_command_line_options_and_ros_args() -> None:
    from launchkit.stock.rviz2.cli import parse_args

    args = parse_args(["-d", "robot.rviz", "--ros-args", "-r", "__node:=viz", "--", "--port", "9"])
    assert (args.display_config, args.port, args.fixed_frame) == (Path("robot.rviz"), 9, None)
    assert parse_args(["-f", "odom"]).fixed_frame == "odom"


def test_real_rviz2_options_are_accepted_and_set_aside() -> None:
    # rviz2's own (Jazzy's QCommandLineParser: -s, -l, -t, --fullscreen), ROS 1 rviz's that
    # launch files still pass, and Qt's: none means anything to the browser viewer
    from launchkit.stock.rviz2.cli import parse_args

    args = parse_args(
        ["-d", "robot.rviz", "-s", "splash.png", "--splash-screen=logo.png", "-l", "--ogre-log",
         "-t", "{NAMESPACE} - RViz2", "--fullscreen", "--opengl", "210", "--disable-anti-aliasing",
         "--no-stereo", "--stereo", "-platform", "xcb", "-f", "odom",
         "--ros-args", "-r", "__node:=viz", "--"]
    )  # fmt: skip
    assert (args.display_config, args.fixed_frame) == (Path("robot.rviz"), "odom")
    assert args.ignored == [
        "-s", "splash.png", "--splash-screen=logo.png", "-l", "--ogre-log",
        "-t", "{NAMESPACE} - RViz2", "--fullscreen", "--opengl", "210",
        "--disable-anti-aliasing", "--no-stereo", "--stereo", "-platform", "xcb",
    ]  # fmt: skip
    assert parse_args([]).ignored == []


def test_bad_option_is_a_user_error() -> None:
    from launchkit.stock.rviz2.cli import parse_args

    with pytest.raises(UserError, match="unrecognized arguments: --bogus") as caught:
        parse_args(["--bogus"])
    text = caught.value.format()  # the usage on one line, however long argparse wraps it
    assert "\n" not in text and "\\n" not in text


def test_port_default_comes_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    from launchkit.stock.rviz2.cli import PORT_ENV, parse_args

    monkeypatch.setenv(PORT_ENV, "9100")
    assert parse_args([]).port == 9100
    assert parse_args(["--port", "9200"]).port == 9200
    monkeypatch.setenv(PORT_ENV, "http")
    with pytest.raises(UserError, match="LAUNCHKIT_VIEWER_PORT is 'http'"):
        parse_args([])


def test_global_options_and_display_options_for_the_page() -> None:
    text = CONFIG.replace(
        "    Fixed Frame: odom\n",
        "    Fixed Frame: odom\n    Frame Rate: 15\n    Background Color: 10; 20; 30\n",
    ).replace(
        "          Name: LaserScan\n", "          Name: LaserScan\n          Size (m): 0.05\n"
    )
    page = parse_config(text).to_page()
    assert (page["fixedFrame"], page["frameRate"], page["background"]) == (
        "odom",
        15.0,
        [10, 20, 30],
    )
    scan = next(d for d in page["displays"] if d["class"] == "LaserScan")
    assert scan == {
        "class": "LaserScan",
        "name": "LaserScan",
        "enabled": True,
        "topic": "/scan",
        "options": {"Size (m)": 0.05},
    }


def test_bad_global_options_fall_back_to_rviz_defaults() -> None:
    text = CONFIG.replace(
        "    Fixed Frame: odom\n",
        "    Fixed Frame: odom\n    Frame Rate: 0\n    Background Color: red\n",
    )
    config = parse_config(text)
    assert (config.frame_rate, config.background) == (30.0, (48, 48, 48))


def test_without_a_config_the_view_shows_grid_robot_and_tf() -> None:
    config = default_config()
    assert config.fixed_frame == "map"
    assert [d.class_name.rsplit("/", 1)[1] for d in config.displays] == ["Grid", "RobotModel", "TF"]
    assert config.topics == ["/robot_description"]
