"""Gzip-compressed recordings (``.csv.gz``, ``.blf.gz``, ``.asc.gz``, ...): decompressed and
handed to the reader of the inner suffix."""

from __future__ import annotations

import gzip
from pathlib import Path

from ..errors import ERR_LINK_LOG, DemoError
from . import Columns, ReadOptions, canlog
from . import csv as csv_reader


def read(path: Path, opts: ReadOptions) -> Columns:
    """A gzip-compressed recording: a CAN log (.blf/.asc/.log/.trc.gz) or a CSV file (.csv.gz)."""
    inner = Path(path.stem).suffix.lower()
    if inner == ".csv":
        try:
            with gzip.open(path, "rb") as f:
                data = f.read()
        except (OSError, EOFError) as e:
            raise DemoError(ERR_LINK_LOG, f"cannot decompress {path.name}: {e}") from None
        return csv_reader.read_bytes(path, data, opts)
    return canlog.read(path, opts)
