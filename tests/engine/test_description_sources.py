"""Python launch files that include XML, YAML and Python files through the launch description
source classes of Jazzy's ``launch``, ``launch_xml`` and ``launch_yaml`` (each compared with the
real stack: an XML source reads a YAML file too, a Python source reads any file as Python)."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.errors import LaunchFileError
from tests.conftest import EvaluateXml

PARENT = """
import os
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import (
    AnyLaunchDescriptionSource,
    FrontendLaunchDescriptionSource,
    PythonLaunchDescriptionSource,
)
from launch_xml.launch_description_sources import XMLLaunchDescriptionSource
from launch_yaml.launch_description_sources import YAMLLaunchDescriptionSource

HERE = os.path.dirname(__file__)


def include(source, who):
    return IncludeLaunchDescription(source, launch_arguments={'who': who}.items())


def generate_launch_description():
    return LaunchDescription([
        include(YAMLLaunchDescriptionSource(os.path.join(HERE, 'child.launch.yaml')), 'yaml'),
        include(XMLLaunchDescriptionSource(os.path.join(HERE, 'child.launch.xml')), 'xml'),
        include(AnyLaunchDescriptionSource(os.path.join(HERE, 'child.launch.yaml')), 'any'),
        include(
            FrontendLaunchDescriptionSource(launch_file_path=HERE + '/child.launch.xml'),
            'frontend',
        ),
        include(XMLLaunchDescriptionSource(os.path.join(HERE, 'child.launch.yaml')), 'xml on yaml'),
        include(PythonLaunchDescriptionSource([HERE, '/python_child.launch']), 'python'),
    ])
"""

PYTHON_CHILD = """
from launch import LaunchDescription
from launch.actions import LogInfo
from launch.substitutions import LaunchConfiguration


def generate_launch_description():
    return LaunchDescription([LogInfo(msg=['python child: ', LaunchConfiguration('who')])])
"""


@pytest.fixture
def children(tmp_path: Path) -> Path:
    """A YAML, an XML and a Python child (the Python one without a .py suffix)."""
    (tmp_path / "child.launch.yaml").write_text(
        "launch:\n- arg: {name: who}\n- log: {message: 'yaml child: $(var who)'}\n"
    )
    (tmp_path / "child.launch.xml").write_text(
        '<launch><arg name="who"/><log message="xml child: $(var who)"/></launch>'
    )
    (tmp_path / "python_child.launch").write_text(PYTHON_CHILD)
    return tmp_path


def test_every_description_source_includes_its_file(
    evaluate_xml: EvaluateXml, children: Path
) -> None:
    result = evaluate_xml(PARENT, name="parent.launch.py")
    assert result.messages() == [
        "yaml child: yaml",
        "xml child: xml",
        "yaml child: any",
        "xml child: frontend",
        "yaml child: xml on yaml",
        "python child: python",
    ]


def test_a_frontend_source_does_not_read_python(evaluate_xml: EvaluateXml, children: Path) -> None:
    parent = PARENT.replace(
        "PythonLaunchDescriptionSource([HERE, '/python_child.launch'])",
        "FrontendLaunchDescriptionSource([HERE, '/python_child.launch'])",
    ).replace("'python child: '", "'x'")
    (children / "python_child.launch").write_text("# not a frontend file\nimport os\n")
    with pytest.raises(LaunchFileError) as caught:
        evaluate_xml(parent, name="parent.launch.py")
    assert "python_child.launch" in str(caught.value.location)
    assert caught.value.message == "the YAML document is the text 'import os'"


def test_xml_source_lives_in_launch_xml_only(evaluate_xml: EvaluateXml, children: Path) -> None:
    # Jazzy's launch.launch_description_sources has no XMLLaunchDescriptionSource.
    parent = "from launch.launch_description_sources import XMLLaunchDescriptionSource\n"
    with pytest.raises(LaunchFileError, match=r"XMLLaunchDescriptionSource|launch_description_s"):
        evaluate_xml(parent, name="parent.launch.py")
