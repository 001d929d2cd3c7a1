"""Cross-references to the docs resolve: every ``docs/NAME.md`` named in the code, tests and docs
exists, every ``docs/NAME.md, "Section"`` names a heading it has, and no ``NAME.md §N`` points at
a numbered section the file does not have. (Paths starting with ``../`` cite notes outside the
repository, like URLs, and are not checked.)"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"

DOC_FILE = re.compile(r"\bdocs/([\w-]+\.md)\b")
DOC_SECTION = re.compile(r'\bdocs/([\w-]+\.md),\s+"([^"]+)"')
NUMBERED = re.compile(r"(?:([\w./-]*[\w-]+\.md)`?\s*)?§\s*(\d+(?:\.\d+)*)")


def sources() -> list[Path]:
    files = [ROOT / "README.md", *DOCS.glob("*.md")]
    for folder in ("launchkit", "tests", "bench", "robot_wheel"):
        files += (ROOT / folder).rglob("*.py")
    here = Path(__file__).resolve()  # this file shows the syntax with made-up references
    return sorted(f for f in files if ".venv" not in f.parts and f.resolve() != here)


def headings(name: str) -> list[str]:
    lines = (DOCS / name).read_text().splitlines()
    return [line.lstrip("#").strip().replace("`", "") for line in lines if line.startswith("#")]


def dangling(text: str) -> list[str]:
    """The references in ``text`` that do not resolve."""
    problems = []
    for match in DOC_FILE.finditer(text):
        if not (DOCS / match.group(1)).is_file():
            problems.append(f"{match.group(0)} does not exist")
    for match in DOC_SECTION.finditer(text):
        name, section = match.group(1), match.group(2).replace("`", "")
        if (DOCS / name).is_file() and not any(h.startswith(section) for h in headings(name)):
            problems.append(f'docs/{name} has no section "{section}"')
    # (the pattern is slow on long runs of word characters: look only where a § is)
    for match in NUMBERED.finditer(text) if "§" in text else ():
        target, number = match.group(1), match.group(2)
        if target is not None and target.startswith("../"):
            continue
        candidates = [DOCS / target, ROOT / target] if target else []
        resolved = next((c for c in candidates if c.is_file()), None)
        pattern = rf"^#+\s*{re.escape(number)}[.\s]"
        if resolved is None or not re.search(pattern, resolved.read_text(), re.MULTILINE):
            problems.append(f"{match.group(0)!r} points at no numbered section")
    return problems


def test_doc_references_resolve() -> None:
    problems = [
        f"{path.relative_to(ROOT)}: {problem}"
        for path in sources()
        for problem in dangling(path.read_text())
    ]
    assert problems == []


def test_the_checker_finds_dangling_references() -> None:
    text = 'See docs/nowhere.md, simulation.md §7, (§4.3) and docs/ros.md, "No such section".'
    assert len(dangling(text)) == 4, dangling(text)
    assert dangling('docs/ros.md, "The network" and ../shared/reference/simulation.md §1') == []
