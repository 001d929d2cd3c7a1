"""launchkit.bag: record and play rosbag2 bags (``launchkit bag record|play|info|reindex``).

Bags are rosbag2 directories (``metadata.yaml`` plus MCAP or sqlite3 files) that ``ros2 bag``,
the ``rosbags`` and ``mcap`` Python readers and Foxglove read. rosbags writes and reads the
storage files; :mod:`launchkit.bag.storage` says what launchkit adds (splitting, file and
message compression, flushing for crash safety, metadata of split bags).

Modules: ``cli`` (arguments), ``record_run``/``recorder``/``writer_thread``/``storage`` (recording),
``play_run``/``player``/``playclock``/``keyboard`` (playing), ``info``, ``reindex`` and
``mcap_repair`` (after a crash), ``metadata``, ``qos``, ``selection``, ``signals``.
"""

from __future__ import annotations

from launchkit.bag.metadata import BagError, BagSummary
from launchkit.bag.storage import BagWriter, WriterOptions

__all__ = ["BagError", "BagSummary", "BagWriter", "WriterOptions"]
