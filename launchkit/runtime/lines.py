"""A child's output bytes cut into lines, with a bounded line length.

Whatever a child writes, what is held for it is at most :data:`MAX_LINE_BYTES`: a longer line
(or output without any newline, such as ``head -c 200M /dev/zero``) is passed on in pieces of
that size, each but the last marked with :data:`SPLIT_MARK`. Every byte is looked at once, so
the cost is linear in the output, however it is cut into reads.
"""

from __future__ import annotations

MAX_LINE_BYTES = 64 * 1024
SPLIT_MARK = f" [line split: longer than {MAX_LINE_BYTES} bytes]"


class LineBuffer:
    """The unfinished line of one output stream."""

    def __init__(self, max_line: int = MAX_LINE_BYTES) -> None:
        self.max_line = max_line
        self._pending = b""

    @property
    def pending(self) -> int:
        """How many bytes wait for the end of their line."""
        return len(self._pending)

    def feed(self, chunk: bytes) -> list[str]:
        """The lines ``chunk`` completes (and the pieces of over-long ones)."""
        data = self._pending + chunk if self._pending else chunk
        end = data.rfind(b"\n")
        lines: list[str] = []
        if end >= 0:
            # one decode for every complete line (a newline is never inside a UTF-8 character)
            text = data[:end].decode("utf-8", errors="replace")
            lines = text.split("\n")
            if "\r" in text:
                lines = [line.rstrip("\r") for line in lines]
            if max(map(len, lines)) * 4 > self.max_line:  # some line may be too long: check
                lines = [piece for line in lines for piece in self._pieces(line.encode())]
        rest = data[end + 1 :]
        if len(rest) > self.max_line:
            *pieces, rest = self._cut(rest)
            lines.extend(_decode(piece) + SPLIT_MARK for piece in pieces)
        self._pending = rest
        return lines

    def finish(self) -> list[str]:
        """At the end of the stream: the last line, if it had no newline."""
        rest, self._pending = self._pending, b""
        return self._pieces(rest) if rest else []

    def _pieces(self, line: bytes) -> list[str]:
        if len(line) <= self.max_line:
            return [_decode(line)]
        *pieces, last = self._cut(line)
        return [_decode(p) + SPLIT_MARK for p in pieces] + [_decode(last)]

    def _cut(self, data: bytes) -> list[bytes]:
        """``data`` in pieces of at most ``max_line`` bytes, cut between UTF-8 characters; the
        last piece may be short."""
        pieces: list[bytes] = []
        start = 0
        while len(data) - start > self.max_line:
            end = start + self.max_line
            back = end
            # a UTF-8 continuation byte (10xxxxxx) belongs to the character before it
            while back > end - 4 and data[back] & 0xC0 == 0x80:
                back -= 1
            end = back if back > end - 4 else end
            pieces.append(data[start:end])
            start = end
        pieces.append(data[start:])
        return pieces


def _decode(data: bytes) -> str:
    return data.decode("utf-8", errors="replace").rstrip("\r")
