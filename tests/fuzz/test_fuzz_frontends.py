"""The fuzzing harness (issue #17, point 1): generated and mutated XML, YAML and Python launch
files and params files come to success or one located launchkit error, never another
exception, never a hang (see harness.py). Bounded under CI by the ``ci`` profile (conftest.py);
``LAUNCHKIT_FUZZ_PROFILE=fuzz`` searches for long. What it finds goes to tests/hostile."""

from __future__ import annotations

import time

import pytest
from hypothesis import given
from hypothesis import strategies as st

from tests.fuzz import strategies as S
from tests.fuzz.harness import Hung, check_file, load_params, time_bound

XML_SEEDS = S.seeds("launch_xml/*.xml", "tests/hostile/corpus/*.launch.xml")
YAML_SEEDS = S.seeds("tests/corpus/yaml/*.yaml", "tests/hostile/corpus/*.launch.yaml")
PYTHON_SEEDS = S.seeds("tests/corpus/python/demos_*.launch.py", "tests/hostile/corpus/*.py")
PARAMS_SEEDS = S.seeds("tests/corpus/yaml/config/*.yaml", "tests/hostile/corpus/params_*.yaml")


@given(S.xml_launch_file())
def test_generated_xml_launch_files(data: bytes) -> None:
    check_file("fuzz.launch.xml", data)


@given(S.mutant_of(XML_SEEDS))
def test_mutated_xml_launch_files(data: bytes) -> None:
    check_file("fuzz.launch.xml", data)


@given(st.one_of(S.yaml_launch_file(), S.mutant_of(YAML_SEEDS)))
def test_yaml_launch_files(data: bytes) -> None:
    check_file("fuzz.launch.yaml", data)


@given(S.mutant_of(PYTHON_SEEDS))
def test_mutated_python_launch_files(data: bytes) -> None:
    check_file("fuzz.launch.py", data)


@given(S.python_api_misuse())
def test_python_launch_api_misuse(data: bytes) -> None:
    check_file("fuzz.launch.py", data)


@given(st.one_of(S.yaml_launch_file(), st.sampled_from(YAML_SEEDS)).flatmap(S.yaml_with_tags))
def test_yaml_launch_files_with_explicit_tags(data: bytes) -> None:
    check_file("fuzz.launch.yaml", data)


@given(st.one_of(S.params_file(), S.mutant_of(PARAMS_SEEDS)))
def test_params_files(data: bytes) -> None:
    load_params(data)


@given(st.one_of(S.params_file(), st.sampled_from(PARAMS_SEEDS)).flatmap(S.yaml_with_tags))
def test_params_files_with_explicit_tags(data: bytes) -> None:
    load_params(data)


def test_an_alarm_swallowed_where_it_fired_still_fails_the_example() -> None:
    # A long run's only report was an "unraisable" Hung: the alarm had fired inside a garbage
    # collector callback, which swallows exceptions, and the example carried on to pass.
    with pytest.raises(Hung, match="swallowed"), time_bound(0.05):
        deadline = time.monotonic() + 5.0
        while time.monotonic() < deadline:
            try:
                time.sleep(0.01)
            except Hung:
                break  # swallowed, as a gc callback would
