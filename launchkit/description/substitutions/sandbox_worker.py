"""The process that evaluates ``$(eval)`` expressions for a launcher
(:mod:`launchkit.description.substitutions.sandbox_process` starts it and stops it).

It reads one request a line on stdin (``{"expression": ..., "modules": [...], "seconds": ...}``)
and answers one line on stdout (``{"value": str}`` or ``{"error": str, "limit": bool}``). Its
address space is capped (its command line's memory above what it uses once started), and it
dies with the launcher. A stuck evaluation is the launcher's to
end: it kills this process.
"""

from __future__ import annotations

import json
import os
import resource
import signal
import sys
from typing import Any

from launchkit.description.substitutions.sandbox import (
    LimitError,
    Limits,
    SandboxError,
    evaluate,
)
from launchkit.own_process import die_with_parent


def _address_space() -> int:
    """Bytes of address space this process uses now (0 when unknown)."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def _cap_memory(limit: int) -> None:
    used = _address_space()
    if used:
        cap = used + limit
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))


def answer(request: dict[str, Any], memory: int = Limits.memory) -> dict[str, Any]:
    """The answer to one request (``limit``: the error is a limit reached) in a process
    whose growth is capped at ``memory`` bytes."""
    limits = Limits(seconds=float(request.get("seconds", Limits.seconds)), memory=memory)
    try:
        value = evaluate(str(request["expression"]), list(request["modules"]), limits)
        return {"value": str(value)}
    except SandboxError as error:
        return {"error": str(error), "limit": isinstance(error, LimitError)}


def main() -> None:
    """Serve requests until stdin ends (arguments: the launcher's pid, the memory cap)."""
    launcher, memory = int(sys.argv[1]), int(sys.argv[2])
    die_with_parent(signal.SIGKILL)
    if os.getppid() != launcher:
        return  # the launcher died before the line above
    _cap_memory(memory)
    sys.stdout.write("ready\n")
    sys.stdout.flush()
    for line in sys.stdin:
        try:
            reply = answer(json.loads(line), memory)
        except (ValueError, KeyError, TypeError) as error:
            reply = {"error": f"bad request to the evaluator: {error}"}
        sys.stdout.write(json.dumps(reply) + "\n")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
