"""Running ``launchkit bag play`` to the end (or Ctrl-C), with ``ros2 bag play``'s keys."""

from __future__ import annotations

import threading
from pathlib import Path

from launchkit.bag.keyboard import KeyboardControls
from launchkit.bag.player import Player, PlayOptions, open_bag
from launchkit.bag.record_run import open_context
from launchkit.bag.signals import POLL, stop_on_signals
from launchkit.ros.logging import RcutilsLogger
from launchkit.ros.node import Node

RATE_STEP = 1.1  # CURSOR_UP / CURSOR_DOWN change the rate by 10 %


def _keyboard(player: Player, log: RcutilsLogger) -> KeyboardControls:
    clock = player.clock

    def toggle() -> None:
        log.info("Pausing play." if clock.toggle() else "Resuming play.")

    def step() -> None:
        if not clock.step():
            log.info("Called play next, but not in paused state.")

    def faster() -> None:
        clock.set_rate(clock.rate * RATE_STEP)
        log.info(f"Set rate to {clock.rate:g}")

    def slower() -> None:
        clock.set_rate(clock.rate / RATE_STEP)
        log.info(f"Set rate to {clock.rate:g}")

    return KeyboardControls(
        {
            "SPACE": toggle,
            "CURSOR_RIGHT": step,
            "s": step,
            "CURSOR_UP": faster,
            "CURSOR_DOWN": slower,
        }
    )


def run_play(
    path: Path,
    options: PlayOptions,
    *,
    remaps: list[str],
    keyboard: bool,
    node_name: str,
    router: str | None,
) -> int:
    """Play the bag at ``path``; 0 once played (or stopped by SIGINT/SIGTERM)."""
    reader = open_bag(path)
    try:
        context = open_context(router)
        try:
            rules = [word for rule in remaps for word in ("-r", rule)]
            node = Node(
                node_name,
                context=context,
                cli_args=["--ros-args", *rules] if rules else None,
                start_parameter_services=False,
            )
            player = Player(node, reader, options)
            return _play(player, node.get_logger(), keyboard)
        finally:
            context.try_shutdown()
    finally:
        reader.close()


def _play(player: Player, log: RcutilsLogger, keyboard: bool) -> int:
    keys = _keyboard(player, log) if keyboard else None
    if keys is not None and keys.start():
        for key, what in (
            ("SPACE", "Pause/Resume"),
            ("CURSOR_RIGHT", "Play Next Message"),
            ("CURSOR_UP", "Increase Rate 10%"),
            ("CURSOR_DOWN", "Decrease Rate 10%"),
        ):
            log.info(f"Press {key} for {what}")
    published: list[int] = []
    playing = threading.Thread(target=lambda: published.append(player.play()), name="player")
    try:
        with stop_on_signals() as stop:
            playing.start()
            while playing.is_alive():
                playing.join(POLL)
                if stop.is_set():
                    player.stop()
    finally:
        if keys is not None:
            keys.close()
    log.info(f"Played {sum(published)} messages")
    return 0
