"""``.txt`` files: python-can's text log (``can.Printer``, what ``can.Logger`` writes for that
suffix) is a format python-can writes but cannot read back, so it is refused by name (691); any
other ``.txt`` file is a text table for the CSV reader."""

from __future__ import annotations

from pathlib import Path

from ..errors import ERR_LINK_LOG, ERR_LOG_UNREADABLE, DemoError
from . import Columns, ReadOptions
from . import csv as csv_reader

#: python-can's text log: every line starts with this.
PRINTER_HEAD = b"Timestamp:"
READABLE = ".asc, .blf, .csv, .db, .log, .mf4 (with asammdf) or .trc"


def read(path: Path, opts: ReadOptions) -> Columns:
    """Refuse python-can's text log (691); read any other ``.txt`` file as a CSV table."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(4096)
    except OSError as e:
        raise DemoError(ERR_LINK_LOG, f"cannot read {path.name}: {e.strerror or e}") from None
    if head.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(PRINTER_HEAD):
        raise DemoError(
            ERR_LOG_UNREADABLE,
            f"{path.name} is a python-can text log (can.Printer, .txt), a format python-can writes "
            f"but cannot read: record or convert the log as {READABLE}",
        )
    return csv_reader.read(path, opts)
