"""Benchmark: ``launchkit check`` of very large launch files (run by hand; results go in
docs/benchmarks.md).

    python bench/big_file.py [--entries 200000] [--repeat 3] [--before DIR]

Writes, in a temporary folder, launch files of about 50 MB with ``--entries`` elements each and
runs ``launchkit check`` on each under ``/usr/bin/time``, taking wall time, CPU time (user +
system: what the check costs, whatever else the machine is doing) and peak RSS. The median of
``--repeat`` runs. The files:

* ``executables``: ``<executable cmd="/bin/true xxx..." name="pN" if="false"/>`` (parsed,
  checked and evaluated; the ``if`` keeps anything from being looked up on PATH);
* ``lets``: ``<let name="vN" value="xxx..."/>`` (parsed and evaluated);
* ``yaml lets``: the same in a YAML launch file.

``--before DIR`` (a folder holding an older ``launchkit`` package, e.g. from ``git archive``)
measures that tree's ``launchkit check`` too, taking turns with this one's on each file, so
both share the machine's load. Commands run from the temporary folder: ``python -m`` puts the
current folder first on ``sys.path``, which from the repository would shadow ``--before``'s
tree with this one.

Issue #17 asked for a 50 MB file to check in under 5 s and under 300 MB.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

PAD = "x" * 200


def write_files(folder: Path, entries: int) -> dict[str, Path]:
    """The three large launch files."""
    files = {
        "executables": folder / "executables.launch.xml",
        "lets": folder / "lets.launch.xml",
        "yaml lets": folder / "lets.launch.yaml",
    }
    pad = PAD[:150]
    with files["executables"].open("w") as out:
        out.write("<launch>\n")
        for i in range(entries):
            out.write(f'  <executable cmd="/bin/true {pad}" name="p{i}" if="false"/>\n')
        out.write("</launch>\n")
    with files["lets"].open("w") as out:
        out.write("<launch>\n")
        for i in range(entries):
            out.write(f'  <let name="v{i}" value="{PAD}"/>\n')
        out.write("</launch>\n")
    with files["yaml lets"].open("w") as out:
        out.write("launch:\n")
        for i in range(entries):
            out.write(f"- let: {{name: v{i}, value: {PAD}}}\n")
    return files


def measure(path: Path, tree: Path | None = None) -> tuple[float, float, float]:
    """Wall seconds, CPU seconds and peak RSS (MB) of one ``launchkit check``, of the
    launchkit package in ``tree`` if given, else the installed one."""
    env = dict(os.environ)
    if tree is not None:
        env["PYTHONPATH"] = str(tree.resolve())
    result = subprocess.run(
        ["/usr/bin/time", "-f", "%e %U %S %M", sys.executable, "-m", "launchkit", "check", path],
        capture_output=True,
        text=True,
        check=False,
        env=env,
        cwd=path.parent,
    )
    if result.returncode != 0:
        raise SystemExit(f"launchkit check {path} failed:\n{result.stderr}")
    wall, user, system, kb = result.stderr.strip().splitlines()[-1].split()
    return float(wall), float(user) + float(system), int(kb) / 1024


def main() -> None:
    """Write the files, check each ``--repeat`` times, print a Markdown table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--entries", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--before", type=Path, help="a folder with an older launchkit package")
    args = parser.parse_args()
    load = os.getloadavg()[0]
    print(
        f"Measured {datetime.datetime.now():%Y-%m-%d %H:%M} on `{platform.node()}` "
        f"({os.cpu_count()} cores, load average {load:.1f}), median of {args.repeat}.\n"
    )
    trees: dict[str, Path | None] = {"": None}
    if args.before is not None:
        trees["before: "] = args.before
    print("| File | Size | Wall | CPU (user + system) | Peak RSS |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for name, path in write_files(Path(folder), args.entries).items():
            runs: dict[str, list[tuple[float, float, float]]] = {label: [] for label in trees}
            for _ in range(args.repeat):
                for label, tree in trees.items():  # taking turns: the same load for both
                    runs[label].append(measure(path, tree))
            size = path.stat().st_size / 1e6
            for label, measured in runs.items():
                wall, cpu, rss = (statistics.median(c) for c in zip(*measured, strict=True))
                print(
                    f"| {label}{args.entries} {name} | {size:.1f} MB | {wall:.2f} s "
                    f"| {cpu:.2f} s | {rss:.0f} MB |"
                )


if __name__ == "__main__":
    main()
