"""An argument parser that reports an unknown option with the usage of the subcommand it was
given to (``launchkit topic echo --bogus`` shows ``topic echo``'s usage, not the top level's).

argparse hands the arguments a subcommand does not know back to the top-level parser, which
then complains with its own usage; this parser remembers the deepest subcommand reached.
"""

from __future__ import annotations

import argparse
import gettext
from collections.abc import Sequence
from typing import Any

# argparse translates every message through gettext.gettext, which looks for the catalogue
# again on each call (about 100 stat()s of locale folders to build launchkit's parser: a third
# of the time it takes). Look it up once; the messages, translated or not, stay the same.
_CATALOGUE = gettext.translation("argparse", fallback=True)
argparse._ = _CATALOGUE.gettext  # type: ignore[attr-defined]
argparse.ngettext = _CATALOGUE.ngettext  # type: ignore[attr-defined]

_DEEPEST = "_launchkit_deepest_parser"


class CommandParser(argparse.ArgumentParser):
    """``argparse.ArgumentParser`` whose subcommands report their own unknown options."""

    def parse_known_args(  # type: ignore[override]
        self, args: Sequence[str] | None = None, namespace: Any = None
    ) -> tuple[argparse.Namespace, list[str]]:
        """As argparse's, noting in the namespace the deepest parser that ran."""
        parsed, extras = super().parse_known_args(args, namespace)
        if not hasattr(parsed, _DEEPEST):
            setattr(parsed, _DEEPEST, self)  # a subcommand's parser finishes first
        return parsed, extras

    def parse_args(  # type: ignore[override]
        self, args: Sequence[str] | None = None, namespace: Any = None
    ) -> argparse.Namespace:
        """As argparse's; an unknown argument is reported by the subcommand it was given to."""
        parsed, extras = self.parse_known_args(args, namespace)
        deepest = getattr(parsed, _DEEPEST, self)
        delattr(parsed, _DEEPEST)
        if extras:
            deepest.error(f"unrecognized arguments: {' '.join(extras)}")
        return parsed
