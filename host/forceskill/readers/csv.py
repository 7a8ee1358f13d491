"""The CSV reader: text tables with a header row, parsed by numpy block by block.

Accepted: a UTF-8 BOM; ``#`` comments (whole lines or the end of a line); blank lines; the
delimiter sniffed from the header row (``,`` ``;`` tab, else runs of spaces), with ``;`` files
allowed to use a decimal comma; header names matched with or without their unit suffix (``t [s]``
is ``t``, ``Fz (N)`` is ``Fz``), exactly first, then ignoring case. The time column (``t`` unless
told) is scaled by ``--time-unit``, else by the unit in its header (``t [ms]``), else read as
seconds; with ``--rate`` there is no time column and sample n is at n/rate. The recording's span is
checked against the duration limit from its first and last rows, before the body is parsed.

Parsing: files above one block are read by numpy's own text parser (the C parser of
``numpy.loadtxt``, fed through the open file so that the progress bar follows it), keeping only the
columns asked for, into one array preallocated for the rows the first and last 64 KiB promise
(``numpy.loadtxt`` grows its array as it fills, which costs it time); the columns are views of that
array: no Python object per row, no copy, faster than ``numpy.loadtxt`` and about the kept columns
in memory (``bench/long_recording.py`` prints both). Smaller files, and a large one that parser
refuses (a decimal comma, a bad line) or a numpy without it, go block by block: the bytes of a
block are turned into one whitespace-separated string and read by ``np.fromstring``; a block whose
value count does not match rows x columns is re-read line by line only to name the first bad line;
the rows are counted first and preallocated (memory: the parsed columns plus one block). A
progress bar shows after 2 s. A python-can CSV log (``timestamp,arbitration_id,...``) is handed to
the CAN log reader.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path
from typing import IO, Any

import numpy as np

from ..errors import ERR_DEMO_COLUMN, ERR_DEMO_FILE, ERR_DEMO_FORMAT, ERR_READ_ARGS, DemoError, FsError
from . import SECONDS_ASSUMED_KEY, TIME_UNITS_S, Columns, ReadOptions, check_duration, progress_bar

BLOCK_BYTES = 8 << 20
#: what a large file's layout is read from: its first and last bytes (more of the start when the
#: header row is not within them)
_HEAD_BYTES = 1 << 16
_TAIL_BYTES = 1 << 16
#: the first rows after the header: the span check and the median step of its hint
_FIRST_BYTES = 4096
#: what numpy's parser is handed a read at least (it asks 16 KiB: a quarter of the Python calls;
#: far larger pieces parse slower)
_FEED_BYTES = 1 << 16
#: the row count numpy's parser preallocates: the rows the shortest mean line of the first and
#: last bytes gives, with this margin (fewer rows: the file is counted and parsed again)
_ROWS_MARGIN = 1.05
_BOM = b"\xef\xbb\xbf"
_UNIT = re.compile(r"^(.*?)\s*[\[(]\s*([^\])]*?)\s*[\])]\s*$")
_TIME_UNIT_ALIASES = {
    "s": "s",
    "sec": "s",
    "ms": "ms",
    "us": "us",
    "\u00b5s": "us",
    "\u03bcs": "us",
    "ns": "ns",
}


def split_name(name: str) -> tuple[str, str]:
    """('t', 's') for 't [s]' or 't (s)'; (name, '') without a unit suffix."""
    m = _UNIT.match(name)
    return (m.group(1), m.group(2)) if m and m.group(1) else (name, "")


def time_unit_of(name: str) -> str | None:
    """The time unit a column's name gives: 'ms' for 't [ms]', 'time (ms)', 'time_ms' or
    't_ms'; None when it names none."""
    bare, unit = split_name(name)
    if unit:
        return _TIME_UNIT_ALIASES.get(unit)
    stem, sep, suffix = bare.rpartition("_")
    return _TIME_UNIT_ALIASES.get(suffix.lower()) if sep and stem else None


#: The time column without --time-column: the first of these names (as find_column matches them,
#: and with a unit suffix such as time_ms) found in the header.
DEFAULT_TIME_COLUMNS = ("t", "time")


def find_time_column(names: list[str], wanted: str | None) -> int | None:
    """Index of the time column: ``wanted`` as find_column matches it; without it ``t``, else
    ``time``, also as ``t_ms``/``time_ms`` (a unit after an underscore)."""
    if wanted is not None:
        return find_column(names, wanted)
    for cand in DEFAULT_TIME_COLUMNS:
        j = find_column(names, cand)
        if j is not None:
            return j
        for j, n in enumerate(names):
            stem = split_name(n)[0].rpartition("_")[0]
            if stem.lower() == cand and time_unit_of(n):
                return j
    return None


def find_column(names: list[str], wanted: str) -> int | None:
    """Index of ``wanted`` among header ``names``: the full name, then the name without its unit
    suffix, then both ignoring case; None when absent."""
    bare = [split_name(n)[0] for n in names]
    w_bare = split_name(wanted)[0]
    for cands, key in ((names, wanted), (bare, w_bare)):
        if key in cands:
            return cands.index(key)
    low = wanted.lower()
    for cands, key in ((names, low), (bare, w_bare.lower())):
        hits = [i for i, n in enumerate(cands) if n.lower() == key]
        if hits:
            return hits[0]
    return None


class _Layout:
    """Header and delimiter of one CSV file."""

    def __init__(self, path: Path, head: bytes) -> None:
        self.path = path
        found = _find_header(head)
        if found is None:
            raise DemoError(ERR_DEMO_FORMAT, f"demonstration {str(path)!r} is empty (no header row)")
        header, self.header_line_no, self.body_offset = found
        try:
            htext = header.decode("utf-8")
        except UnicodeDecodeError:
            raise DemoError(
                ERR_DEMO_FORMAT, f"demonstration {str(path)!r} is not a UTF-8 text CSV file"
            ) from None
        counts = {d: htext.count(d) for d in (",", ";", "\t")}
        delim = max(counts, key=lambda d: counts[d])
        self.delim: str | None = delim if counts[delim] else None
        cells = htext.split(self.delim) if self.delim else htext.split()
        self.names = [c.strip().strip('"').strip("'").strip() for c in cells]
        if any(_is_number(c) for c in self.names):
            raise DemoError(
                ERR_DEMO_FORMAT,
                f"demonstration {str(path)!r} has no header row (first row: {htext.strip()[:80]})",
            )
        if len(set(self.names)) != len(self.names) or not all(self.names):
            raise DemoError(
                ERR_DEMO_FORMAT,
                f"{path.name}: empty or repeated column names in the header ({', '.join(self.names)})",
            )
        self.ncols = len(self.names)
        # bytes -> one whitespace-separated string: delimiter and CR become spaces; a ';' file may
        # write decimals with a comma
        src = (self.delim or "").encode() + b"\r"
        self._table = bytes.maketrans(src, b" " * len(src))
        self._comma_table = bytes.maketrans(b",", b".") if self.delim == ";" else None

    def parse(self, block: bytes, first_line_no: int) -> np.ndarray:
        """Rows of ``block`` (whole lines) as an (n, ncols) array; refuses a bad line (601)."""
        if b"#" in block:
            block = b"\n".join(ln.split(b"#", 1)[0] for ln in block.split(b"\n"))
        if self._comma_table is not None and b"," in block:
            block = block.translate(self._comma_table)
        flat = block.translate(self._table)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                values = np.fromstring(flat, sep=" ") if flat.strip() else np.zeros(0)
        except (ValueError, DeprecationWarning):
            values = None
        if values is None or values.size % self.ncols:
            self._locate(block, first_line_no)
            raise DemoError(
                ERR_DEMO_FORMAT,
                f"{self.path.name}: lines from {first_line_no} do not parse as {self.ncols} numbers",
            )
        n_rows = values.size // self.ncols
        # blank lines, or ragged rows that add up
        if _count_lines(flat) != n_rows and any(
            len(ln.split()) != self.ncols for ln in flat.split(b"\n") if ln.strip()
        ):
            self._locate(block, first_line_no)
        return values.reshape(n_rows, self.ncols)

    def _locate(self, block: bytes, first_line_no: int) -> None:
        """Raise the one-line error for the first line of ``block`` that is not ncols numbers."""
        for i, raw in enumerate(block.split(b"\n")):
            text = raw.decode("utf-8", errors="replace").strip()
            if not text:
                continue
            cells = text.split(self.delim) if self.delim else text.split()
            line = first_line_no + i
            if len(cells) != self.ncols:
                raise DemoError(
                    ERR_DEMO_FORMAT,
                    f"{self.path.name}: line {line} has {len(cells)} fields, header has {self.ncols}",
                )
            for name, cell in zip(self.names, cells, strict=False):
                if not _is_number(cell.strip()):
                    raise DemoError(
                        ERR_DEMO_FORMAT,
                        f"{self.path.name}: line {line}, column {name!r}: not a number: {cell.strip()!r}",
                    )


def _find_header(head: bytes) -> tuple[bytes, int, int] | None:
    """The first line of ``head`` with text outside a comment: (its text, its line number, the
    offset after it); None when there is none. Only whole lines count, unless ``head`` has no
    newline at all (a one-line file)."""
    whole = b"\n" in head
    pos = 0
    line_no = 1
    while pos < len(head) or not pos:
        end = head.find(b"\n", pos)
        if end < 0:
            if whole:
                return None
            end = len(head)
        text = head[pos:end].split(b"#", 1)[0].strip()
        if text:
            return text, line_no, end + 1
        pos = end + 1
        line_no += 1
    return None


def _count_lines(buf: bytes) -> int:
    """Lines in ``buf``, a last one without its newline included (an upper bound on rows)."""
    return buf.count(b"\n") + (0 if not buf or buf.endswith(b"\n") else 1)


def _is_number(s: str) -> bool:
    try:
        float(s)
    except ValueError:
        return False
    return True


def _tail(fh: IO[bytes], size: int) -> bytes:
    fh.seek(max(0, size - _TAIL_BYTES))
    return fh.read()


def _last_row(tail: bytes) -> bytes:
    for raw in reversed(tail.split(b"\n")):
        text = raw.split(b"#", 1)[0].strip()
        if text:
            return text
    return b""


def _head(fh: IO[bytes], size: int) -> bytes:
    """The file's start: all of a small file; of a large one the first _HEAD_BYTES, or up to
    BLOCK_BYTES when no header row is within them (a long preamble of comments)."""
    head = fh.read(min(size, BLOCK_BYTES if size <= BLOCK_BYTES else _HEAD_BYTES))
    if len(head) < min(size, BLOCK_BYTES) and _find_header(head) is None:
        head += fh.read(min(size, BLOCK_BYTES) - len(head))
    return head


def _is_can_log(names: list[str]) -> bool:
    return [n.lower() for n in names[:2]] == ["timestamp", "arbitration_id"]


def read(path: Path, opts: ReadOptions) -> Columns:
    """Columns ``t`` (s) and the requested ones (``opts.columns``, ``opts.optional`` when present)."""
    try:
        fh = open(path, "rb")  # noqa: SIM115 (closed by the with below)
    except OSError as e:
        raise DemoError(ERR_DEMO_FILE, f"cannot read demonstration {str(path)!r}: {e.strerror}") from None
    with fh:
        size = path.stat().st_size
        return _read(path, fh, size, _head(fh, size), opts)


def read_bytes(path: Path, data: bytes, opts: ReadOptions) -> Columns:
    """The same as ``read`` for a file already in memory (a decompressed .csv.gz)."""
    import io

    fh = io.BytesIO(data)
    return _read(path, fh, len(data), _head(fh, len(data)), opts)


def _read(path: Path, fh: IO[bytes], size: int, head: bytes, opts: ReadOptions) -> Columns:
    bom = len(_BOM) if head.startswith(_BOM) else 0
    lay = _Layout(path, head[bom:])
    if _is_can_log(lay.names):
        from .canlog import read as read_can

        return read_can(path, opts)
    # the columns to keep: time (unless --rate) and the requested ones
    keep: dict[str, int] = {}
    t_unit = opts.time_unit
    unit_told = True
    if opts.rate_hz is None:
        j = find_time_column(lay.names, opts.time_column)
        if j is None:
            wanted = opts.time_column or " or ".join(repr(c) for c in DEFAULT_TIME_COLUMNS)
            raise DemoError(
                ERR_DEMO_COLUMN,
                f"time column {wanted if opts.time_column is None else repr(wanted)} not in {path.name} "
                f"(available: {', '.join(lay.names)}): name it with --time-column, or give --rate HZ",
            )
        keep["t"] = j
        if t_unit is None:
            t_unit = time_unit_of(lay.names[j])
            unit_told = t_unit is not None
            t_unit = t_unit or "s"
        else:
            unit_told = True
    for name in opts.columns:
        j = find_column(lay.names, name)
        if j is None:
            raise DemoError(
                ERR_DEMO_COLUMN, f"column {name!r} not in {path.name} (available: {', '.join(lay.names)})"
            )
        keep[name] = j
    for name in opts.optional:
        j = find_column(lay.names, name)
        if j is not None and name not in keep:
            keep[name] = j
    if not opts.columns and not opts.optional:  # nothing asked: every column
        keep.update({n: j for j, n in enumerate(lay.names) if n not in keep})
    scale = TIME_UNITS_S[t_unit or "s"]
    body0 = bom + lay.body_offset
    first_line = lay.header_line_no + 1
    if len(head) < min(size, body0 + _FIRST_BYTES):  # a header far into a large file
        fh.seek(len(head))
        head += fh.read(min(size, body0 + _FIRST_BYTES) - len(head))
    tail = _tail(fh, size) if size > BLOCK_BYTES or "t" in keep else b""
    # the span from the first and last rows, before the body is parsed
    if "t" in keep:
        first = head[body0 : body0 + _FIRST_BYTES]
        rows = [r for r in (ln.split(b"#", 1)[0].strip() for ln in first.split(b"\n")[:-1]) if r]
        try:
            span = (lay.parse(_last_row(tail), 0)[0, keep["t"]] - lay.parse(rows[0], 0)[0, keep["t"]]) * scale
        except (DemoError, IndexError):
            span = 0.0  # the full parse names the bad line
        # the median step only for the refusal's hint
        too_long = float(span) > opts.max_duration_s
        step = _first_step(lay, rows, keep["t"], scale) if too_long and not unit_told else None
        check_duration(float(span), opts.max_duration_s, path.name, step)
    if size <= BLOCK_BYTES:
        body = head[body0:] if len(head) == size else head[body0:] + fh.read()
        data = lay.parse(body, first_line)
        cols = {name: np.ascontiguousarray(data[:, j]) for name, j in keep.items()}
    else:
        rows_max = _rows_estimate((head[body0:], tail), size - body0, len(lay.names))
        cols = _read_blocks(path, fh, size, body0, first_line, lay, keep, opts, rows_max)
    n = next(iter(cols.values())).size if cols else 0
    if "t" in cols:
        if scale != 1.0:
            cols["t"] *= scale
        if n:  # again, for a file whose first or last row did not parse on its own
            duration = float(cols["t"][-1] - cols["t"][0])
            step = None
            if duration > opts.max_duration_s and n > 1 and not unit_told:
                step = float(np.median(np.diff(cols["t"][: 1 << 16])))
            check_duration(duration, opts.max_duration_s, path.name, step)
        if not unit_told:
            cols[SECONDS_ASSUMED_KEY] = np.ones(1)
    else:
        cols["t"] = np.arange(n, dtype=float) / float(opts.rate_hz or 1.0)
        check_duration(float(cols["t"][-1]) if n else 0.0, opts.max_duration_s, path.name)
    if n == 0:
        raise DemoError(ERR_DEMO_FORMAT, f"demonstration {str(path)!r} has a header but no rows")
    return cols


def _first_step(lay: _Layout, rows: list[bytes], j: int, scale: float) -> float | None:
    """The median time step (s) of the first rows, None when they do not parse."""
    try:
        t = lay.parse(b"\n".join(rows[:64]), 0)[:, j] * scale
    except DemoError:
        return None
    return float(np.median(np.diff(t))) if t.size > 1 else None


def _blocks(fh: IO[bytes], start: int, size: int) -> list[tuple[int, int, int]]:
    """(offset, length, lines) of blocks of whole lines covering bytes start..size."""
    out = []
    pos = start
    while pos < size:
        fh.seek(pos)
        buf = fh.read(BLOCK_BYTES)
        if pos + len(buf) < size:
            cut = buf.rfind(b"\n")
            if cut < 0:
                raise FsError(ERR_READ_ARGS, f"a line longer than {BLOCK_BYTES} bytes at byte {pos}")
            buf = buf[: cut + 1]
        out.append((pos, len(buf), _count_lines(buf)))
        pos += len(buf)
    return out


def _read_blocks(
    path: Path,
    fh: IO[bytes],
    size: int,
    start: int,
    first_line: int,
    lay: _Layout,
    keep: dict[str, int],
    opts: ReadOptions,
    rows_max: int,
) -> Columns:
    """Large files: numpy's parser (``_parse_whole``), else count the rows, preallocate the kept
    columns and fill them block by block."""
    whole = _parse_whole(path, fh, size, start, lay, keep, opts, rows_max)
    if whole is not None:
        return whole
    blocks = _blocks(fh, start, size)
    n = sum(lines for _, _, lines in blocks)  # >= rows: blank and comment lines are counted too
    if "t" not in keep and opts.rate_hz:
        check_duration((n - 1) / opts.rate_hz, opts.max_duration_s, path.name)
    out = {name: np.empty(n) for name in keep}
    bar = progress_bar(path, opts, total=size)
    row = 0
    line = first_line
    try:
        for off, length, lines in blocks:
            fh.seek(off)
            data = lay.parse(fh.read(length), line)
            m = data.shape[0]
            if row + m > n:
                raise DemoError(ERR_DEMO_FORMAT, f"{path.name} changed while it was read")
            for name, j in keep.items():
                out[name][row : row + m] = data[:, j]
            row += m
            line += lines
            bar.update(length)
    finally:
        bar.close()
    return {name: a[:row] for name, a in out.items()}


def _rows_estimate(samples: tuple[bytes, ...], body_bytes: int, ncols: int) -> int:
    """Rows to preallocate for ``body_bytes`` of lines: from the shortest mean line of the whole
    lines in ``samples`` with _ROWS_MARGIN, at most one row per 2*ncols bytes (a number and a
    separator per column); 0 when no sample holds a whole line."""
    means = [(cut + 1) / s.count(b"\n", 0, cut + 1) for s in samples if (cut := s.rfind(b"\n")) >= 0]
    if not means:
        return 0
    return min(int(body_bytes / min(means) * _ROWS_MARGIN) + 16, body_bytes // (2 * ncols) + 1)


def _count_rows(fh: IO[bytes], start: int, size: int) -> int:
    """Lines from byte ``start`` (a last one without its newline included): at least the rows."""
    fh.seek(start)
    buf = bytearray(1 << 20)
    view = np.frombuffer(buf, np.uint8)
    n = 0
    last = b"\n"
    while k := fh.readinto(buf):  # type: ignore[attr-defined]
        n += int(np.count_nonzero(view[:k] == 10))
        last = bytes(buf[k - 1 : k])
    return n + (last != b"\n")


class _Feed:
    """The file from ``start`` as numpy's parser reads it, the progress bar fed by its reads."""

    def __init__(self, fh: IO[bytes], start: int, bar: Any) -> None:
        fh.seek(start)
        self._fh = fh
        self._bar = bar

    def read(self, n: int = -1) -> bytes:
        data = self._fh.read(max(n, _FEED_BYTES) if n >= 0 else n)
        self._bar.update(len(data))
        return data


def _parse_whole(
    path: Path,
    fh: IO[bytes],
    size: int,
    start: int,
    lay: _Layout,
    keep: dict[str, int],
    opts: ReadOptions,
    rows_max: int,
) -> Columns | None:
    """The body from byte ``start`` parsed at once by the C parser behind ``numpy.loadtxt`` (only
    the kept columns) into one array of ``rows_max`` rows, preallocated (a growing one is
    reallocated as it fills: slower); when it fills up, the lines are counted and the body parsed
    again. The columns are views of that array (no copies). None when this numpy has no such
    parser or it refuses the text (the block reader then reads it or names the bad line)."""
    try:
        from numpy._core._multiarray_umath import _load_from_filelike
    except ImportError:
        return None
    used = sorted(set(keep.values()))
    counted = rows_max <= 0
    if counted:
        rows_max = _count_rows(fh, start, size)
    while True:
        bar = progress_bar(path, opts, total=size)
        bar.update(start)
        try:
            with warnings.catch_warnings():
                # numpy notes that blank lines do not count towards max_rows: known, not for the user
                warnings.simplefilter("ignore", UserWarning)
                data = _load_from_filelike(
                    _Feed(fh, start, bar),
                    delimiter=lay.delim,
                    comment="#",
                    quote=None,
                    imaginary_unit="j",
                    usecols=used,
                    skiplines=0,
                    max_rows=rows_max,
                    converters=None,
                    dtype=np.dtype(np.float64),
                    encoding="utf-8",
                    filelike=True,
                    byte_converters=False,
                )
        except (ValueError, TypeError, UnicodeDecodeError):
            return None
        finally:
            bar.close()
        data = np.asarray(data, dtype=np.float64).reshape(-1, len(used))
        if counted or data.shape[0] < rows_max:
            break
        del data  # filled up: rows beyond the estimate
        rows_max, counted = _count_rows(fh, start, size), True
    return {name: data[:, used.index(j)] for name, j in keep.items()}
