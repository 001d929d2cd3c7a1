"""Parse-level tests, one or more per launch tag: inline XML in, recorded actions out."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.errors import LaunchArgumentError, LaunchFileError
from tests.conftest import EvaluateXml


def test_arg_default_and_override(evaluate_xml: EvaluateXml) -> None:
    xml = '<launch><arg name="a" default="one"/><log message="a=$(var a)"/></launch>'
    assert evaluate_xml(xml).messages() == ["a=one"]
    assert evaluate_xml(xml, {"a": "two"}).messages() == ["a=two"]


def test_arg_without_default_is_required(evaluate_xml: EvaluateXml) -> None:
    with pytest.raises(LaunchArgumentError, match="'needed'"):
        evaluate_xml('<launch><arg name="needed"/></launch>')
    assert evaluate_xml('<launch><arg name="needed"/></launch>', {"needed": "x"}).items == []


def test_arg_choices_are_enforced(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch>
      <arg name="mode" default="fast"><choice value="fast"/><choice value="slow"/></arg>
      <log message="$(var mode)"/>
    </launch>"""
    assert evaluate_xml(xml, {"mode": "slow"}).messages() == ["slow"]
    with pytest.raises(LaunchArgumentError, match=r"'medium'.*fast.*slow"):
        evaluate_xml(xml, {"mode": "medium"})


def test_arg_default_outside_choices_is_an_error(evaluate_xml: EvaluateXml) -> None:
    xml = '<launch><arg name="m" default="x"><choice value="y"/></arg></launch>'
    with pytest.raises((LaunchFileError, LaunchArgumentError)):
        evaluate_xml(xml)


def test_let_sets_a_configuration(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch><let name="x" value="1"/><let name="y" value="$(var x)2"/>
      <log message="$(var y)"/></launch>"""
    assert evaluate_xml(xml).messages() == ["12"]


def test_group_scopes_configurations_and_environment(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch>
      <let name="x" value="outer"/>
      <group>
        <let name="x" value="inner"/>
        <set_env name="ONLY_INSIDE" value="1"/>
        <log message="in:$(var x):$(env ONLY_INSIDE '-')"/>
      </group>
      <log message="out:$(var x):$(env ONLY_INSIDE '-')"/>
    </launch>"""
    assert evaluate_xml(xml).messages() == ["in:inner:1", "out:outer:-"]


def test_unscoped_group_leaks_like_ros(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch>
      <group scoped="false"><let name="x" value="leaked"/></group>
      <log message="$(var x)"/>
    </launch>"""
    assert evaluate_xml(xml).messages() == ["leaked"]


def test_group_without_forwarding_keeps_only_kept_names(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch>
      <let name="a" value="A"/><let name="b" value="B"/>
      <group forwarding="false">
        <keep name="a" value="$(var a)"/>
        <keep name="c" value="C"/>
        <log message="$(var a)$(var c)"/>
        <log message="$(var b 'b is not forwarded')"/>
      </group>
    </launch>"""
    assert evaluate_xml(xml).messages() == ["AC", "b is not forwarded"]


def test_group_without_forwarding_starts_from_the_launch_environment(
    evaluate_xml: EvaluateXml,
) -> None:
    # As ROS's GroupAction: the environment is reset to what the launch began with, the
    # <keep>s are evaluated after that reset, and the group's own changes stay inside it
    # (compared with the real Jazzy stack).
    xml = """<launch>
      <set_env name="OUTER" value="set before"/>
      <group forwarding="false">
        <keep name="k" value="$(env OUTER 'unset')"/>
        <set_env name="INNER" value="x"/>
        <log message="in: $(env OUTER 'unset') $(env BASE) k=$(var k)"/>
        <executable cmd="true" name="inside"/>
      </group>
      <log message="out: $(env OUTER 'unset') $(env INNER 'unset')"/>
    </launch>"""
    result = evaluate_xml(xml, env={"BASE": "base"})
    assert result.messages() == ["in: unset base k=unset", "out: set before unset"]
    assert "OUTER" not in result.process("inside").env


def test_group_keeps_are_lets_when_forwarding_or_unscoped(evaluate_xml: EvaluateXml) -> None:
    # ROS accepts <keep> in any group: inside a forwarding scoped group it sets the
    # configuration for the scope; an unscoped group ignores forwarding="false" and its
    # <keep>s leak like <let>s.
    xml = """<launch>
      <let name="a" value="A"/>
      <set_env name="OUTER" value="o"/>
      <group><keep name="k" value="kept"/><log message="$(var k) $(var a)"/></group>
      <log message="after: $(var k 'none')"/>
      <group scoped="false" forwarding="false">
        <keep name="k3" value="kept3"/>
        <log message="$(var a) $(env OUTER) $(var k3)"/>
      </group>
      <log message="after: $(var k3)"/>
    </launch>"""
    assert evaluate_xml(xml).messages() == [
        "kept A",
        "after: none",
        "A o kept3",
        "after: kept3",
    ]


def test_group_if_and_unless(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch>
      <arg name="on" default="true"/>
      <group if="$(var on)"><log message="if"/></group>
      <group unless="$(var on)"><log message="unless"/></group>
    </launch>"""
    assert evaluate_xml(xml).messages() == ["if"]
    assert evaluate_xml(xml, {"on": "false"}).messages() == ["unless"]


@pytest.mark.parametrize(
    "element",
    [
        '<log message="x" {c}/>',
        '<let name="v" value="1" {c}/><log message="$(var v none)"/>',
        '<set_env name="V" value="1" {c}/><log message="$(env V none)"/>',
        '<arg name="v" default="1" {c}/><log message="$(var v none)"/>',
        '<executable cmd="true" {c}/>',
        '<timer period="1" {c}><log message="x"/></timer>',
        '<group {c}><log message="x"/></group>',
        '<include file="$(dirname)/child.launch.xml" {c}/>',
        "<shutdown {c}/>",
    ],
)
def test_if_and_unless_work_on_every_tag(
    evaluate_xml: EvaluateXml, tmp_path: Path, element: str
) -> None:
    (tmp_path / "child.launch.xml").write_text('<launch><log message="child"/></launch>')
    skipped = evaluate_xml("<launch>" + element.format(c='if="false"') + "</launch>")
    kept = evaluate_xml("<launch>" + element.format(c='unless="false"') + "</launch>")
    assert [i for i in skipped.items if i.text != "[INFO] [launch.user]: none"] == []
    assert kept.items != [] and "none" not in kept.messages()


def test_if_and_unless_together_is_an_error(evaluate_xml: EvaluateXml) -> None:
    with pytest.raises(LaunchFileError, match=r"if.*unless|unless.*if"):
        evaluate_xml('<launch><log message="x" if="true" unless="false"/></launch>')


def test_reset_clears_configurations_but_keeps_named(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch>
      <let name="a" value="A"/><let name="b" value="B"/>
      <reset><keep name="b" value="$(var b)"/></reset>
      <log message="$(var b)"/>
      <log message="$(var a)"/>
    </launch>"""
    with pytest.raises(Exception, match="'a'"):
        evaluate_xml(xml)


def test_include_passes_args_and_does_not_scope(evaluate_xml: EvaluateXml, tmp_path) -> None:
    (tmp_path / "child.launch.xml").write_text(
        """<launch><arg name="who" default="nobody"/><let name="set_by_child" value="yes"/>
        <log message="hello $(var who)"/></launch>"""
    )
    xml = """<launch>
      <include file="$(dirname)/child.launch.xml"><arg name="who" value="world"/></include>
      <log message="after include: $(var set_by_child)"/>
    </launch>"""
    assert evaluate_xml(xml).messages() == ["hello world", "after include: yes"]


def test_include_inside_group_is_scoped(evaluate_xml: EvaluateXml, tmp_path) -> None:
    (tmp_path / "child.launch.xml").write_text('<launch><let name="leak" value="yes"/></launch>')
    xml = """<launch>
      <group><include file="$(dirname)/child.launch.xml"/></group>
      <log message="$(var leak 'no')"/>
    </launch>"""
    assert evaluate_xml(xml).messages() == ["no"]


def test_include_sees_command_line_arguments(evaluate_xml: EvaluateXml, tmp_path) -> None:
    (tmp_path / "child.launch.xml").write_text(
        '<launch><arg name="shared" default="child"/><log message="$(var shared)"/></launch>'
    )
    xml = '<launch><include file="$(dirname)/child.launch.xml"/></launch>'
    assert evaluate_xml(xml, {"shared": "cli"}).messages() == ["cli"]


def test_include_of_missing_file_is_found_before_running(evaluate_xml: EvaluateXml) -> None:
    with pytest.raises(LaunchFileError, match=r"nope\.launch\.xml' does not exist") as caught:
        evaluate_xml('<launch>\n  <include file="$(dirname)/nope.launch.xml"/>\n</launch>')
    assert caught.value.location is not None and caught.value.location.line == 2


def test_conditional_include_of_missing_file_is_fine_when_skipped(
    evaluate_xml: EvaluateXml,
) -> None:
    xml = '<launch><group if="false"><include file="$(dirname)/nope.launch.xml"/></group></launch>'
    assert evaluate_xml(xml).items == []


def test_executable_attributes(evaluate_xml: EvaluateXml, tmp_path) -> None:
    xml = f"""<launch>
      <executable cmd="echo hi there" cwd="{tmp_path}" name="talker" output="screen"
          emulate_tty="true" sigterm_timeout="1.5" sigkill_timeout="2.5" respawn="true"
          respawn_delay="0.5" respawn_max_retries="3" on_exit="shutdown"
          launch-prefix="nice -n 5">
        <env name="GREETING" value="hi"/>
      </executable>
    </launch>"""
    spec = evaluate_xml(xml).process("talker")
    assert spec.cmd == ["nice", "-n", "5", "echo", "hi", "there"]
    assert spec.cwd == str(tmp_path)
    assert spec.output == "screen"
    assert spec.emulate_tty is True
    assert (spec.sigterm_timeout, spec.sigkill_timeout) == (1.5, 2.5)
    assert (spec.respawn, spec.respawn_delay, spec.respawn_max_retries) == (True, 0.5, 3)
    assert spec.on_exit_shutdown is True
    assert spec.env["GREETING"] == "hi"
    assert spec.env_changes["GREETING"] == "hi"


def test_executable_defaults_follow_ros(evaluate_xml: EvaluateXml) -> None:
    spec = evaluate_xml('<launch><executable cmd="sleep 1"/></launch>').processes[0]
    assert spec.name == "sleep"
    assert spec.output == "log"
    assert (spec.sigterm_timeout, spec.sigkill_timeout) == (5.0, 5.0)
    assert spec.respawn is False
    assert spec.env["PYTHONUNBUFFERED"] == "1"


def test_quoted_substitution_stays_inside_its_word(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch><let name="v" value="a b"/>
      <executable cmd="printf '%s|' 'x $(var v) y' z"/></launch>"""
    assert evaluate_xml(xml).processes[0].cmd == ["printf", "%s|", "x a b y", "z"]


def test_shell_true_keeps_the_quoting(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch><executable shell="true" cmd="echo 'a  b' | tr a A"/></launch>"""
    spec = evaluate_xml(xml).processes[0]
    assert spec.cmd[-1] == "echo 'a  b' | tr a A"
    assert spec.cmd[:2] == ["/bin/sh", "-c"]


def test_output_must_be_a_known_mode(evaluate_xml: EvaluateXml) -> None:
    with pytest.raises(LaunchFileError, match="output"):
        evaluate_xml('<launch><executable cmd="true" output="loud"/></launch>')


def test_timer_keeps_its_group_scope(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch>
      <group>
        <let name="x" value="inside"/>
        <timer period="2"><log message="$(var x)"/></timer>
      </group>
    </launch>"""
    result = evaluate_xml(xml)
    assert result.items[0].kind == "timer" and result.items[0].delay == 2.0
    assert result.messages() == ["inside"]


def test_environment_tags(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch>
      <set_env name="A" value="1"/>
      <append_env name="P" value="/x"/>
      <append_env name="P" value="/y"/>
      <append_env name="P" value="/first" prepend="true"/>
      <append_env name="Q" value="b" separator=","/>
      <unset_env name="HOME"/>
      <executable cmd="env" name="one"/>
      <reset_env/>
      <executable cmd="env" name="two"/>
    </launch>"""
    result = evaluate_xml(xml, env={"HOME": "/root", "Q": "a", "PATH": "/bin"})
    one = result.process("one").env
    assert one["A"] == "1"
    assert one["P"] == "/first:/x:/y"
    assert one["Q"] == "a,b"
    assert "HOME" not in one
    two = result.process("two").env
    assert "A" not in two and two["HOME"] == "/root"


def test_log_levels_and_shutdown(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch><log level="WARNING" message="careful"/>
      <shutdown reason="done here"/></launch>"""
    result = evaluate_xml(xml)
    assert result.logs == ["[WARNING] [launch.user]: careful"]
    assert [i.kind for i in result.items] == ["log", "shutdown"]
    assert result.items[1].text == "done here"


def test_unknown_tag_lists_the_known_ones(evaluate_xml: EvaluateXml) -> None:
    with pytest.raises(LaunchFileError, match=r"unknown tag <rosparam>") as caught:
        evaluate_xml('<launch>\n\n  <rosparam file="x.yaml"/>\n</launch>')
    assert caught.value.location is not None
    assert (caught.value.location.line, caught.value.location.col) == (3, 3)
    assert caught.value.hint is not None and "param" in caught.value.hint


def test_unknown_attribute_names_the_allowed_ones(evaluate_xml: EvaluateXml) -> None:
    with pytest.raises(LaunchFileError, match="unknown attribute 'levle'") as caught:
        evaluate_xml('<launch>\n<log message="x" levle="INFO"/></launch>')
    assert "level" in (caught.value.expected or "")
    assert caught.value.location is not None and caught.value.location.line == 2
