"""Fixtures for the simulation core tests: the seed robot and fresh worlds."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from launchkit.stock.gazebo_ros.sim.engine import Simulation
from launchkit.stock.gazebo_ros.sim.world import load_world, resolve_world

SEED_URDF = Path(__file__).resolve().parents[2] / "urdf" / "three_wheeled_robot.urdf"


@pytest.fixture(scope="session")
def seed_urdf() -> str:
    """The seed's URDF text."""
    return SEED_URDF.read_text()


@pytest.fixture
def empty_sim() -> Iterator[Simulation]:
    """A world with only the ground plane."""
    sim = Simulation(load_world(resolve_world("empty")))
    yield sim
    sim.close()


@pytest.fixture
def obstacle_sim() -> Iterator[Simulation]:
    """The shipped world with obstacles."""
    sim = Simulation(load_world(resolve_world("obstacles")))
    yield sim
    sim.close()
