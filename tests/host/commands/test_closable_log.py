"""The log writer of record and run: a frame the notifier's thread hands out after the writer is
stopped is dropped, not written to the closed file (python-can's remove_listener does not wait for
a dispatch under way)."""

from __future__ import annotations

import threading
import time
from pathlib import Path

import can

from forceskill.commands._common import close_log, open_log
from forceskill.outputs import Outputs


def test_frames_after_stop_are_dropped_and_the_log_reads_back(tmp_path: Path) -> None:
    path = tmp_path / "run.asc"
    with Outputs() as outs:
        log = open_log(outs, str(path))
        stop = threading.Event()

        def feed() -> None:  # the notifier's thread, still dispatching while the command stops
            i = 0
            while not stop.is_set():
                log.on_message_received(
                    can.Message(arbitration_id=0x100, data=[i & 0xFF], timestamp=i * 1e-3)
                )
                i += 1

        t = threading.Thread(target=feed)
        t.start()
        try:
            time.sleep(0.05)  # frames flowing
            close_log(log)  # while frames keep arriving: before, "I/O operation on closed file"
            log.on_message_received(can.Message(arbitration_id=0x101, data=[1]))
        finally:
            stop.set()
            t.join()
        outs.commit()
    frames = list(can.ASCReader(str(path)))
    assert frames and all(m.arbitration_id == 0x100 for m in frames)
