"""Parse XML launch files into :class:`LaunchDescription`s (both readers keep line numbers): a
small plain file with expat (:mod:`launchkit.frontend.xml.expat_tree`: no lxml import for the
common case), any other with lxml, as a stream (:mod:`launchkit.frontend.xml.stream`: a large
file is never held whole)."""

from __future__ import annotations

import functools
import stat
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import TYPE_CHECKING

from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.xml.entity import SourceFile, XmlEntity, read_root
from launchkit.frontend.xml.expat_tree import MAX_PLAIN_SIZE, read_plain

if TYPE_CHECKING:
    from launchkit.frontend.xml.entity import AnyElement

#: The largest launch file read (a generous bound: the largest real ones are under 100 kB).
MAX_FILE_SIZE = 256 * 1024 * 1024


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
            if status.st_size <= MAX_PLAIN_SIZE:
                return self.parse_bytes(path.read_bytes(), path)
            from launchkit.frontend.xml.stream import CHUNK_SIZE

            with path.open("rb") as stream:
                chunks = iter(functools.partial(stream.read, CHUNK_SIZE), b"")
                return self._parse(chunks, path, path.read_bytes)
        except OSError as error:
            raise LaunchFileError(
                f"cannot read '{path}': {error.strerror}", included_from
            ) from None

    def parse_text(self, text: str, path: Path) -> LaunchDescription:
        """Parse launch XML ``text`` as if read from ``path``."""
        return self.parse_bytes(text.encode("utf-8", "surrogatepass"), path)

    def parse_bytes(self, data: bytes, path: Path) -> LaunchDescription:
        """Parse launch XML ``data`` as if read from ``path``: in the encoding its declaration
        or byte order mark names (lxml reads it), else UTF-8; a byte that is not valid in
        that encoding is an error at its line and column."""
        plain = read_plain(data)
        if plain is not None:
            root, encoding = plain
            source = SourceFile(path, _decoded(data, encoding))
            del data, plain  # its bytes go before its actions are built
            entity = XmlEntity(root, source)
            deprecated = read_root(entity)
            return LaunchDescription(path, self.actions.parse_actions(entity), deprecated)
        from launchkit.frontend.xml.stream import CHUNK_SIZE

        chunks = (data[start : start + CHUNK_SIZE] for start in range(0, len(data), CHUNK_SIZE))
        return self._parse(chunks, path, lambda: data)

    def _parse(
        self, chunks: Iterable[bytes], path: Path, whole: Callable[[], bytes]
    ) -> LaunchDescription:
        """Parse the file as a stream; a file that is not well-formed, or whose encoding is
        not one the stream reads (UTF-16, say), is read again whole (``whole()``), which
        reports its error as it always has."""
        from lxml import etree  # with inspect, typing, gzip: only for a file expat does not read

        from launchkit.frontend.xml.stream import ElementStream, NotStreamable

        stream = ElementStream(self.actions, path)
        try:
            for chunk in chunks:
                stream.feed(chunk)
            return stream.close()
        except (etree.XMLSyntaxError, NotStreamable):
            pass
        return self.parse_whole(whole(), path)

    def parse_whole(self, data: bytes, path: Path) -> LaunchDescription:
        """Parse ``data`` as one tree (the stream's fallback): its errors name the line and
        column, and an undecodable byte its offset."""
        root, encoding = _read_with_lxml(data, path)
        source = SourceFile(path, _decoded(data, encoding))
        del data  # a large file: its bytes go before its actions are built
        entity = XmlEntity(root, source)
        deprecated = read_root(entity)
        return LaunchDescription(path, self.actions.parse_actions(entity), deprecated)


def _read_with_lxml(data: bytes, path: Path) -> tuple[AnyElement, str | None]:
    """The root element and encoding lxml reads; its error, located, for a malformed file."""
    from lxml import etree  # with inspect, typing, gzip: only for a file expat does not read

    from launchkit.frontend.xml.stream import PARSER_OPTIONS

    parser = etree.XMLParser(**PARSER_OPTIONS)
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
    from launchkit.frontend.xml.stream import DECLARED_ENCODING

    declared = DECLARED_ENCODING.match(data[:200])
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
