"""Parse XML launch files into :class:`LaunchDescription`\\ s: lxml reads the whole file and
keeps each element's line (the column is found in the text, see ``entity.py``)."""

from __future__ import annotations

import re
import stat
from pathlib import Path

from lxml import etree

from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.xml.entity import SourceFile, XmlEntity

#: The largest launch file read (a generous bound: the largest real ones are under 100 kB).
MAX_FILE_SIZE = 256 * 1024 * 1024
_DECLARED_ENCODING = re.compile(rb"""^\s*<\?xml[^>]*encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")


class XmlParser:
    """Parses XML launch text; the tags are read by ``actions``."""

    def __init__(self, actions: ActionParser) -> None:
        self.actions = actions

    def parse_file(self, path: Path, included_from: Location | None = None) -> LaunchDescription:
        """Read and parse ``path``; ``included_from`` locates an error in reading it."""
        try:
            status = path.stat()
            if not stat.S_ISREG(status.st_mode):  # /dev/zero or a FIFO would never end
                raise LaunchFileError(
                    "not a regular file",
                    included_from or Location(str(path)),
                    expected="an XML launch file",
                )
            if status.st_size > MAX_FILE_SIZE:
                raise LaunchFileError(
                    f"the file is {status.st_size} bytes long",
                    included_from or Location(str(path)),
                    expected=f"a launch file of at most {MAX_FILE_SIZE} bytes",
                )
            data = path.read_bytes()
        except OSError as error:
            raise LaunchFileError(
                f"cannot read '{path}': {error.strerror}", included_from
            ) from None
        return self.parse_bytes(data, path)

    def parse_text(self, text: str, path: Path) -> LaunchDescription:
        """Parse launch XML ``text`` as if read from ``path``."""
        return self.parse_bytes(text.encode("utf-8", "surrogatepass"), path)

    def parse_bytes(self, data: bytes, path: Path) -> LaunchDescription:
        """Parse launch XML ``data`` as if read from ``path``: in the encoding its declaration
        or byte order mark names (lxml reads it), else UTF-8; a byte that is not valid in
        that encoding is an error at its line and column."""
        root, encoding = _read_with_lxml(data, path)
        entity = XmlEntity(root, SourceFile(path, _decoded(data, encoding)))
        if entity.tag != "launch":
            raise entity.error(
                f"the root element is <{entity.tag}>", expected="<launch> as the root element"
            )
        deprecated = entity.raw("deprecated")
        entity.assert_fully_read()
        return LaunchDescription(path, self.actions.parse_actions(entity), deprecated)


def _read_with_lxml(data: bytes, path: Path) -> tuple[etree._Element, str | None]:
    """The root element and encoding lxml reads; its error, located, for a malformed file.
    No entity is expanded (no XXE, no "billion laughs"); lxml's ``no_network`` stays on."""
    parser = etree.XMLParser(remove_comments=True, remove_pis=True, resolve_entities=False)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError as error:
        line, col = error.position
        message = str(error.msg or error).split(", line ")[0]
        undecodable = _undecodable(data, path) if "encod" in message.lower() else None
        if undecodable is not None:
            raise undecodable from None
        raise LaunchFileError(
            f"malformed XML: {message}",
            Location(str(path), line, col),
            expected="well-formed XML in the encoding it declares (UTF-8 if none)",
        ) from None
    return root, root.getroottree().docinfo.encoding


def _undecodable(data: bytes, path: Path) -> LaunchFileError | None:
    """The first byte that is not valid in the file's encoding (declared, else UTF-8), at its
    line and column and byte offset; None when there is none (or a byte order mark rules)."""
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        return None
    declared = _DECLARED_ENCODING.match(data[:200])
    encoding = declared.group(1).decode() if declared else "utf-8"
    try:
        data.decode(encoding)
        return None
    except LookupError:
        return None  # lxml named the unknown encoding itself
    except UnicodeDecodeError as error:
        start = error.start
    line = data.count(b"\n", 0, start) + 1
    col = start - (data.rfind(b"\n", 0, start) + 1) + 1
    return LaunchFileError(
        f"byte 0x{data[start]:02x} at offset {start} is not valid {encoding}",
        Location(str(path), line, col),
        expected=f"{encoding} text, or an <?xml encoding=...?> declaration naming the file's",
    )


def _decoded(data: bytes, encoding: str | None) -> str:
    """The text lxml parsed (for columns in messages): ``data`` in its encoding."""
    try:
        return data.decode(encoding or "utf-8")
    except (LookupError, UnicodeDecodeError):  # an encoding Python names otherwise
        return data.decode("utf-8", "replace")
