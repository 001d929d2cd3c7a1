"""Gazebo's named materials (``Gazebo/SkyBlue`` ...) as RGBA, for ``<gazebo reference>`` blocks.

Values are the diffuse colours of Gazebo classic's ``gazebo.material`` script, rounded.
"""

from __future__ import annotations

RGBA = tuple[float, float, float, float]

_COLOURS: dict[str, RGBA] = {
    "White": (1.0, 1.0, 1.0, 1.0),
    "WhiteGlow": (1.0, 1.0, 1.0, 1.0),
    "Grey": (0.7, 0.7, 0.7, 1.0),
    "Gray": (0.7, 0.7, 0.7, 1.0),
    "DarkGrey": (0.175, 0.175, 0.175, 1.0),
    "Black": (0.0, 0.0, 0.0, 1.0),
    "Red": (1.0, 0.0, 0.0, 1.0),
    "RedBright": (0.87, 0.26, 0.07, 1.0),
    "Green": (0.0, 1.0, 0.0, 1.0),
    "Blue": (0.0, 0.0, 1.0, 1.0),
    "SkyBlue": (0.53, 0.81, 0.92, 1.0),
    "Yellow": (1.0, 1.0, 0.0, 1.0),
    "Orange": (1.0, 0.5, 0.088, 1.0),
    "Purple": (1.0, 0.0, 1.0, 1.0),
    "Turquoise": (0.0, 1.0, 1.0, 1.0),
    "Gold": (0.8, 0.7, 0.2, 1.0),
    "Wood": (0.6, 0.4, 0.2, 1.0),
}


def material_rgba(name: str) -> RGBA | None:
    """The colour of a Gazebo material name (``Gazebo/Red`` or ``Red``), or None if unknown."""
    short = name.strip().removeprefix("Gazebo/")
    return _COLOURS.get(short)
