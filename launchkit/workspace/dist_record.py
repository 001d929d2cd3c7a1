"""Keeping an installed distribution's ``RECORD`` (the file list ``pip uninstall`` removes)
true after a build moved or replaced what pip installed.

This matters for ``--symlink-install``: once a package folder in ``site-packages`` is a
symlink to the source, a RECORD still listing ``pkg/__init__.py`` would let ``pip uninstall``
delete the user's source files through the link. The rewritten RECORD lists the link itself.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Iterable, Mapping
from pathlib import Path


def find_dist_info(site_packages: Path) -> Path | None:
    """The one ``*.dist-info`` folder pip left in ``site_packages`` (a fresh prefix has one)."""
    found = sorted(site_packages.glob("*.dist-info"))
    return found[0] if found else None


def installed_paths(dist_info: Path) -> list[str]:
    """The paths RECORD lists, relative to site-packages as written there."""
    with open(dist_info / "RECORD", newline="", encoding="utf-8") as stream:
        return [row[0] for row in csv.reader(stream) if row]


def rewrite_record(dist_info: Path, moved: Mapping[str, str], linked: Iterable[str] = ()) -> None:
    """Rename entries as ``moved`` says (old to new path, both as RECORD writes them), and
    replace every entry under a folder of ``linked`` by one entry for that folder's link."""
    record = dist_info / "RECORD"
    with open(record, newline="", encoding="utf-8") as stream:
        rows = [row for row in csv.reader(stream) if row]
    links = list(linked)
    kept: list[list[str]] = []
    for row in rows:
        path = moved.get(row[0], row[0])
        if any(path == link or path.startswith(link + "/") for link in links):
            continue
        kept.append([path, *row[1:]] if path != row[0] else row)
    kept.extend([link, "", ""] for link in links)
    text = io.StringIO()
    csv.writer(text, lineterminator="\n").writerows(kept)
    record.write_text(text.getvalue(), encoding="utf-8")
