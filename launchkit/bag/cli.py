"""``launchkit bag record|play|info|reindex``: argument parsing (``ros2 bag``'s options)."""

from __future__ import annotations

import argparse
import datetime
from pathlib import Path

from launchkit.bag.metadata import BagError
from launchkit.bag.selection import TopicSelection
from launchkit.bag.storage import COMPRESSION_MODES, PRESETS, STORAGES, WriterOptions
from launchkit.envvars import ROUTER as ROUTER_ENV
from launchkit.ros.names import RemapRule

_NS = 1_000_000_000
DEFAULT_CACHE = 100 * 1024 * 1024


def _positive(text: str) -> float:
    value = float(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f"{text} is not > 0")
    return value


def _not_negative(text: str) -> float:
    value = float(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"{text} is negative")
    return value


def _common(parser: argparse.ArgumentParser, node_name: str | None = None) -> None:
    if node_name is not None:
        parser.add_argument("--router", metavar="tcp/HOST:PORT", help=f"default ${ROUTER_ENV}")
        parser.add_argument("--node-name", default=node_name, help="default %(default)s")
    parser.add_argument("--debug", action="store_true", help=argparse.SUPPRESS)


def _filters(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--topics", nargs="+", default=[], metavar="TOPIC", help="these topics")
    parser.add_argument("-e", "--regex", default="", help="topics matching this regex")
    parser.add_argument(
        "-x", "--exclude-regex", "--exclude", default="", help="leave out topics matching it"
    )
    parser.add_argument("--exclude-topics", nargs="+", default=[], metavar="TOPIC")


def _record_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = commands.add_parser("record", help="record topics to a bag (ros2 bag record)")
    p.add_argument("topics_positional", nargs="*", metavar="TOPIC", help="topics to record")
    p.add_argument("-a", "--all", action="store_true", help="every topic (not hidden ones)")
    _filters(p)
    p.add_argument("--include-hidden-topics", action="store_true")
    p.add_argument("-o", "--output", default="", help="bag folder (default rosbag2_DATE-TIME)")
    p.add_argument("-s", "--storage", default="mcap", choices=sorted(STORAGES))
    p.add_argument("--compression-mode", default="none", choices=COMPRESSION_MODES)
    p.add_argument("--compression-format", default="", choices=["zstd"])
    p.add_argument(
        "--storage-preset-profile",
        default="none",
        choices=list(PRESETS),
        help="MCAP chunk compression (zstd_fast, zstd_small)",
    )
    p.add_argument("-b", "--max-bag-size", type=int, default=0, help="split at BYTES (0: never)")
    p.add_argument(
        "-d", "--max-bag-duration", type=_not_negative, default=0, help="split after SECONDS"
    )
    p.add_argument("--max-cache-size", type=int, default=DEFAULT_CACHE, help="queue bytes")
    p.add_argument("-p", "--polling-interval", type=int, default=100, help="ms between looks")
    p.add_argument("--no-discovery", action="store_true", help="only topics there at start")
    p.add_argument("--use-sim-time", action="store_true", help="stamp messages with /clock")
    p.add_argument("--custom-data", nargs="*", default=[], metavar="KEY=VALUE")
    _common(p, "rosbag2_recorder")
    p.set_defaults(run=_record)


def _play_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = commands.add_parser("play", help="play a bag back (ros2 bag play)")
    p.add_argument("bag_path", type=Path)
    _filters(p)
    p.add_argument("-r", "--rate", type=_positive, default=1.0)
    p.add_argument("-l", "--loop", action="store_true")
    p.add_argument("--start-offset", type=_not_negative, default=0.0, metavar="SECONDS")
    p.add_argument("-m", "--remap", nargs="+", default=[], metavar="FROM:=TO")
    p.add_argument(
        "--clock", type=_positive, nargs="?", const=40.0, default=0.0, metavar="HZ",
        help="publish /clock (default 40 Hz when given); the bag's /clock is not played",
    )  # fmt: skip
    p.add_argument("-d", "--delay", type=_not_negative, default=0.0, metavar="SECONDS")
    p.add_argument("-p", "--start-paused", action="store_true")
    p.add_argument("--disable-keyboard-controls", action="store_true")
    p.add_argument("--read-ahead-queue-size", type=int, default=1000)
    _common(p, "rosbag2_player")
    p.set_defaults(run=_play)


def build_parser() -> argparse.ArgumentParser:
    """The parser of ``launchkit bag``."""
    parser = argparse.ArgumentParser(
        prog="launchkit bag", description="Record and play rosbag2 bags (MCAP or sqlite3)."
    )
    commands = parser.add_subparsers(dest="verb", metavar="VERB", required=True)
    _record_parser(commands)
    _play_parser(commands)
    info = commands.add_parser("info", help="print a bag's summary (ros2 bag info)")
    info.add_argument("bag_path", type=Path)
    info.add_argument("-t", "--topic-name", action="store_true", help="only topic names")
    _common(info)
    info.set_defaults(run=_info)
    reindex = commands.add_parser("reindex", help="rebuild metadata.yaml (ros2 bag reindex)")
    reindex.add_argument("bag_path", type=Path)
    _common(reindex)
    reindex.set_defaults(run=_reindex)
    return parser


def _record(args: argparse.Namespace) -> int:
    from launchkit.bag.record_run import run_record
    from launchkit.bag.recorder import RecorderOptions

    topics = list(args.topics_positional) + list(args.topics)
    selection = TopicSelection.build(
        all_topics=args.all,
        topics=topics,
        regex=args.regex,
        exclude_regex=args.exclude_regex,
        exclude_topics=args.exclude_topics,
        include_hidden=args.include_hidden_topics,
    )
    if selection.empty:
        raise BagError("nothing to record", expected="-a, topic names or --regex")
    if (args.exclude_regex or args.exclude_topics) and not (args.all or args.regex):
        raise BagError("--exclude-regex and --exclude-topics need -a or --regex")
    if args.compression_format and args.compression_mode == "none":
        raise BagError("--compression-format without a compression mode", expected="file")
    custom = {}
    for item in args.custom_data:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise BagError(f"--custom-data {item!r}", expected="KEY=VALUE")
        custom[key] = value
    output = args.output or datetime.datetime.now().strftime("rosbag2_%Y_%m_%d-%H_%M_%S")
    if Path(output).exists():
        raise BagError(f"Output folder '{output}' already exists.", expected="a new folder")
    writer = WriterOptions(
        storage=args.storage,
        compression_mode=args.compression_mode,
        storage_preset_profile=args.storage_preset_profile,
        max_bag_size=args.max_bag_size,
        max_bag_duration=int(args.max_bag_duration * _NS),
        custom_data=custom,
    )
    writer.check()
    recorder = RecorderOptions(
        selection=selection,
        polling_interval=max(args.polling_interval, 1) / 1000,
        no_discovery=args.no_discovery,
        use_sim_time=args.use_sim_time,
    )
    return run_record(
        Path(output),
        writer,
        recorder,
        max_cache_size=args.max_cache_size,
        node_name=args.node_name,
        router=args.router,
    )


def _play(args: argparse.Namespace) -> int:
    from launchkit.bag.play_run import run_play
    from launchkit.bag.player import PlayOptions

    selection = TopicSelection.build(
        all_topics=not (args.topics or args.regex),
        topics=args.topics,
        regex=args.regex,
        exclude_regex=args.exclude_regex,
        exclude_topics=args.exclude_topics,
        include_hidden=True,
    )
    for rule in args.remap:
        RemapRule.parse(rule)  # a malformed rule is a mistake found before connecting
    options = PlayOptions(
        selection=selection,
        rate=args.rate,
        loop=args.loop,
        start_offset=args.start_offset,
        clock_hz=args.clock,
        delay=args.delay,
        start_paused=args.start_paused,
        read_ahead=args.read_ahead_queue_size,
    )
    return run_play(
        args.bag_path,
        options,
        remaps=list(args.remap),
        keyboard=not args.disable_keyboard_controls,
        node_name=args.node_name,
        router=args.router,
    )


def _info(args: argparse.Namespace) -> int:
    from launchkit.bag.info import bag_info

    print(bag_info(args.bag_path, names_only=args.topic_name))
    return 0


def _reindex(args: argparse.Namespace) -> int:
    from launchkit.bag.reindex import reindex

    reindex(args.bag_path)
    return 0


def main(argv: list[str]) -> int:
    """Run ``launchkit bag ARGV...``; user mistakes raise ``UserError`` (exit 2)."""
    args = build_parser().parse_args(argv)
    return int(args.run(args))
