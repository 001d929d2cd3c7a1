"""Hypothesis strategies for hostile launch files and params files: generated from the
frontends' vocabulary (tags, attributes, substitutions, YAML anchors), in several encodings,
and byte-level mutations of real files.

Nothing generated runs a program: ``$(command)`` is left out of the vocabulary and a mutant that
spells it is discarded (``check`` evaluates the file, and would run it), and ``check`` starts
no process.
"""

from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import quoteattr

import yaml
from hypothesis import assume
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[2]

TAGS = [
    "launch", "let", "arg", "executable", "node", "group", "include", "log", "timer", "set_env",
    "unset_env", "append_env", "push_ros_namespace", "param", "remap", "env", "set_parameter",
    "set_remap", "node_container", "composable_node", "load_composable_node", "reset_env",
]  # fmt: skip
ATTRIBUTES = [
    "name", "value", "default", "cmd", "pkg", "exec", "file", "if", "unless", "message",
    "period", "namespace", "ns", "from", "output", "respawn", "scoped", "description",
    "choices", "args", "launch-prefix", "cwd", "sep", "type", "level", "prepend", "plugin",
]  # fmt: skip
#: Every substitution but ``command`` (which would run a program during the check).
SUBSTITUTIONS = [
    "var", "env", "optenv", "dirname", "filename", "find-pkg-share", "find-pkg-prefix",
    "find-exec", "exec-in-pkg", "anon", "eval", "not", "and", "or", "equals", "not-equals",
]  # fmt: skip
PIECES = [
    "$(", ")", " ", "'", '"', "\\", "$", "(", "x", "true", "false", "1", "-2.5", "/", "a b",
    "$(var x)", "$(var x y)", "$(eval '1+1')", "$(dirname)", "&", "<", "\x1b", "\r", "\n",
    "é", "\u202e", "\U0001f600", "\t", "{", "}", ":", "*", "**", "~",
]  # fmt: skip

value_text = st.lists(
    st.one_of(
        st.sampled_from(PIECES),
        st.sampled_from(SUBSTITUTIONS),
        st.text(max_size=6),
    ),
    max_size=14,
).map("".join)


@st.composite
def element(draw: st.DrawFn, depth: int = 0) -> str:
    """One XML element of the launch vocabulary, with children up to a few levels."""
    tag = draw(st.sampled_from(TAGS) if draw(st.integers(0, 9)) else st.text(min_size=1))
    names = draw(st.lists(st.sampled_from(ATTRIBUTES), max_size=5, unique=True))
    attributes = "".join(f" {name}={quoteattr(draw(value_text))}" for name in names)
    children = draw(st.lists(element(depth + 1), max_size=4)) if depth < 3 else []
    if not children and draw(st.booleans()):
        return f"<{tag}{attributes}/>"
    return f"<{tag}{attributes}>{''.join(children)}</{tag}>"


@st.composite
def xml_launch_file(draw: st.DrawFn) -> bytes:
    """An XML launch file in one of several encodings (declared or not, rightly or not)."""
    body = "".join(draw(st.lists(element(1), max_size=6)))
    if draw(st.integers(0, 4)) == 0:  # deep nesting: of elements, of substitutions
        depth = draw(st.integers(0, 300))
        tag = draw(st.sampled_from(["group", "timer", "launch", "let"]))
        body = f"<{tag}>" * depth + body + f"</{tag}>" * depth
        nested = "$(var " * depth + "x" + ")" * depth
        body += f"<let name='x' value={quoteattr(nested)}/>"
    text = f"<launch>\n{body}\n</launch>\n"
    encoding = draw(st.sampled_from(["utf-8", "utf-16", "latin-1", "utf-8-sig", "cp1252"]))
    declare = draw(st.sampled_from([None, encoding, "UTF-8", "UTF-16", "ISO-8859-1", "bogus"]))
    if declare is not None:
        text = f'<?xml version="1.0" encoding="{declare}"?>\n' + text
    return text.encode(encoding, errors="xmlcharrefreplace")


def yaml_entity(depth: int = 0) -> st.SearchStrategy[object]:
    """One YAML launch action: ``{tag: {attribute: value, children: [...]}}``."""
    scalar = st.one_of(value_text, st.integers(), st.floats(allow_nan=True), st.booleans())
    attributes = st.dictionaries(st.sampled_from(ATTRIBUTES), scalar, max_size=5)
    if depth < 3:
        children = st.lists(st.deferred(lambda: yaml_entity(depth + 1)), max_size=3)
        attributes = st.builds(lambda a, c: {**a, "children": c} if c else a, attributes, children)
    return st.dictionaries(st.sampled_from(TAGS), attributes, min_size=1, max_size=1)


@st.composite
def yaml_launch_file(draw: st.DrawFn) -> bytes:
    """A YAML launch file, sometimes with anchors and aliases spliced into its text."""
    actions = draw(st.lists(yaml_entity(), max_size=6))
    text = yaml.safe_dump({"launch": actions}, allow_unicode=True)
    return draw(spliced(text.encode()))


ANCHOR_PIECES = [
    b"&a ", b"*a", b"&b [*a, *a, *a]", b"<<: *a", b"!!python/object:os.system", b"!!binary",
    b"---\n", b"[", b"{", b"? ", b"1:0:0:0:0", b"0x" + b"f" * 40, b"\xff\xfe", b"\xe9",
    b"\x00", b"%YAML 1.1\n", b"|\n  ", b'"\\x1b"', b"9" * 2000,
]  # fmt: skip


@st.composite
def spliced(draw: st.DrawFn, data: bytes) -> bytes:
    """``data`` with a few hostile pieces inserted, bytes flipped or removed."""
    out = bytearray(data)
    for _ in range(draw(st.integers(0, 4))):
        at = draw(st.integers(0, len(out)))
        operation = draw(st.integers(0, 3))
        if operation == 0:
            out[at:at] = draw(st.sampled_from(ANCHOR_PIECES))
        elif operation == 1:
            out[at:at] = draw(st.binary(min_size=1, max_size=4))
        elif operation == 2 and out:
            del out[at : at + draw(st.integers(1, 20))]
        elif out:
            out[min(at, len(out) - 1)] = draw(st.integers(0, 255))
    result = bytes(out)
    assume(b"command" not in result)
    return result


def seeds(*patterns: str) -> list[bytes]:
    """The repository's files matching ``patterns`` (relative to its root), as bytes."""
    found = sorted({p for pattern in patterns for p in ROOT.glob(pattern)})
    texts = [path.read_bytes() for path in found]
    return [text for text in texts if b"command" not in text]


def mutant_of(files: list[bytes]) -> st.SearchStrategy[bytes]:
    """A byte-level mutant of one of ``files``."""
    return st.sampled_from(files).flatmap(spliced)


@st.composite
def params_file(draw: st.DrawFn) -> bytes:
    """A ROS params file: nested parameters under node patterns, then spliced."""
    leaf = st.one_of(
        value_text,
        st.integers(),
        st.floats(allow_nan=True),
        st.booleans(),
        st.lists(st.integers(), max_size=4),
        st.none(),
    )
    tree = st.recursive(
        leaf, lambda inner: st.dictionaries(st.sampled_from(ATTRIBUTES), inner, max_size=3)
    )
    sections = draw(
        st.dictionaries(
            st.sampled_from(["/**", "/ns/node", "node", "/*/node", "/other", "ros__parameters"]),
            st.one_of(st.fixed_dictionaries({"ros__parameters": tree}), tree),
            max_size=3,
        )
    )
    return draw(spliced(yaml.safe_dump(sections, allow_unicode=True).encode()))


#: Classes of the Python launch API, with the keyword arguments ROS documents for each and
#: how many positional ones they take first (none of them runs a program during a check).
PYTHON_API: dict[str, tuple[int, tuple[str, ...]]] = {
    "launch.actions.DeclareLaunchArgument": (1, ("default_value", "description", "choices")),
    "launch.actions.LogInfo": (0, ("msg",)),
    "launch.actions.GroupAction": (1, ("scoped", "forwarding", "launch_configurations")),
    "launch.actions.TimerAction": (0, ("period", "actions", "cancel_on_shutdown")),
    "launch.actions.SetLaunchConfiguration": (2, ()),
    "launch.actions.UnsetLaunchConfiguration": (1, ()),
    "launch.actions.SetEnvironmentVariable": (2, ()),
    "launch.actions.AppendEnvironmentVariable": (2, ("prepend", "separator")),
    "launch.actions.ExecuteProcess": (0, ("cmd", "name", "cwd", "env", "additional_env", "output",
                                          "shell", "respawn", "respawn_delay", "sigterm_timeout")),
    "launch.actions.IncludeLaunchDescription": (1, ("launch_arguments",)),
    "launch.actions.RegisterEventHandler": (1, ()),
    "launch.actions.OpaqueFunction": (0, ("function", "args", "kwargs")),
    "launch.actions.Shutdown": (0, ("reason",)),
    "launch.actions.PushLaunchConfigurations": (0, ()),
    "launch.actions.PopLaunchConfigurations": (0, ()),
    "launch.event_handlers.OnProcessExit": (0, ("target_action", "on_exit")),
    "launch.event_handlers.OnProcessStart": (0, ("target_action", "on_start")),
    "launch.launch_description_sources.PythonLaunchDescriptionSource": (1, ()),
    "launch.conditions.IfCondition": (1, ()),
    "launch.conditions.UnlessCondition": (1, ()),
    "launch.conditions.LaunchConfigurationEquals": (2, ()),
    "launch.substitutions.LaunchConfiguration": (1, ("default",)),
    "launch.substitutions.EnvironmentVariable": (1, ("default_value",)),
    "launch.substitutions.PythonExpression": (1, ()),
    "launch.substitutions.PathJoinSubstitution": (1, ()),
    "launch.substitutions.TextSubstitution": (0, ("text",)),
    "launch.substitutions.EqualsSubstitution": (2, ()),
    "launch.substitutions.NotSubstitution": (1, ()),
    "launch_ros.actions.Node": (0, ("package", "executable", "name", "namespace", "parameters",
                                    "remappings", "arguments", "ros_arguments", "output",
                                    "respawn", "exec_name")),
    "launch_ros.actions.PushRosNamespace": (1, ()),
    "launch_ros.actions.SetParameter": (0, ("name", "value")),
    "launch_ros.actions.SetRemap": (0, ("src", "dst")),
    "launch_ros.actions.SetUseSimTime": (1, ()),
    "launch_ros.substitutions.FindPackageShare": (1, ()),
    "launch_ros.parameter_descriptions.ParameterValue": (1, ("value_type",)),
}  # fmt: skip
#: Keyword arguments most actions take.
COMMON_KEYWORDS = ("condition",)
#: Values of every type a launch file might wrongly pass.
PYTHON_VALUES = [
    "'x'", "''", "'a b'", "'$(var x)'", "'true'", "['x']", "[['x']]", "[1, None]", "1", "-1",
    "2.5", "float('nan')", "True", "None", "{'k': 'v'}", "{'k': ['v']}", "{1: 2}", "('a', 'b')",
    "[('a', 'b')]", "b'x'", "object()", "range(3)", "lambda *a, **k: None", "print", "...",
    "10**100", "'\\x00'", "LaunchDescription()", "[LaunchDescription([])]",
]  # fmt: skip


def python_call(depth: int = 0) -> st.SearchStrategy[str]:
    """One call of the Python launch API whose arguments are anything, calls included."""
    value = st.sampled_from(PYTHON_VALUES)
    if depth < 2:
        inner = st.deferred(lambda: python_call(depth + 1))
        value = st.one_of(
            value, inner, st.lists(inner, max_size=2).map(lambda c: f"[{', '.join(c)}]")
        )

    @st.composite
    def call(draw: st.DrawFn) -> str:
        name = draw(st.sampled_from(sorted(PYTHON_API)))
        positional, keywords = PYTHON_API[name]
        args = draw(st.lists(value, min_size=0, max_size=positional + 1))
        chosen = draw(st.lists(st.sampled_from((*keywords, *COMMON_KEYWORDS)), unique=True,
                               max_size=3))  # fmt: skip
        kwargs = [f"{key}={draw(value)}" for key in chosen]
        return f"{name}({', '.join([*args, *kwargs])})"

    return call()


@st.composite
def python_api_misuse(draw: st.DrawFn) -> bytes:
    """A Python launch file whose actions get arguments of any type, as a user might pass
    them by mistake (a list as an argument name, a string as a condition, ...)."""
    calls = draw(st.lists(python_call(), min_size=1, max_size=4))
    body = "".join(f"        {call},\n" for call in calls)
    text = (
        "import launch, launch.actions, launch.conditions, launch.event_handlers\n"
        "import launch.launch_description_sources, launch.substitutions\n"
        "import launch_ros.actions, launch_ros.substitutions, launch_ros.parameter_descriptions\n"
        "from launch import LaunchDescription\n\n\n"
        "def generate_launch_description():\n"
        f"    return LaunchDescription([\n{body}    ])\n"
    )
    return text.encode()


#: Explicit YAML tags, valid and not, for scalars and collections.
YAML_TAGS = [
    "!!timestamp x", "!!timestamp 2001-12-14", "!!bool maybe", "!!bool yes", "!!int ''",
    "!!int 0x", "!!int 12", "!!float abc", "!!float .inf", "!!null x", "!!str 1", "!!binary '@@'",
    "!!binary aGk=", "!!python/name:os.system x", "!!python/object/apply:os.system [id]",
    "!!set {a: 1}", "!!omap [a: 1]", "!!pairs [a: 1]", "!!map [1]", "!!seq {a: 1}", "!foo x",
    "!<tag:yaml.org,2002:int> x", "!!merge x", "!!str [1]", "!!int [1]", "! x",
]  # fmt: skip


@st.composite
def yaml_with_tags(draw: st.DrawFn, text: bytes) -> bytes:
    """``text`` (YAML) with explicit tags put in place of some of its values."""
    lines = text.split(b"\n")
    for _ in range(draw(st.integers(1, 3))):
        at = draw(st.integers(0, max(0, len(lines) - 1)))
        line = lines[at]
        if b": " in line:
            key = line.split(b": ", 1)[0]
            lines[at] = key + b": " + draw(st.sampled_from(YAML_TAGS)).encode()
        else:
            lines.insert(at, b"- " + draw(st.sampled_from(YAML_TAGS)).encode())
    return b"\n".join(lines)
