"""Every file a command writes goes through here, so that no command can lose the user's data.

``Outputs`` is a set of output files committed as one unit (a skill, its JSON twin and its plot):

- each output is first written to a temporary file in its target's folder; ``commit`` renames them
  into place only after every one of them was written, and if a rename fails the ones already
  renamed are put back (an existing file is kept as a hard link until the set is committed);
- nothing that existed before is deleted or changed when a command fails;
- an output that is one of the command's inputs (same file, also through a link), or an output
  given twice, is refused (660) before anything is written;
- devices, FIFOs, sockets, directories and anything under /dev or /proc are refused (661): the
  output must be a regular file or not exist yet;
- a symbolic link is followed: the file it points to is replaced, the link stays;
- a new file gets the permissions the umask allows (0666 & ~umask), a replaced file keeps its mode.

``-`` as a CSV output means standard output (``csv_sink``), streamed and never buffered whole.
"""

from __future__ import annotations

import os
import secrets
import stat
import sys
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any, Union

import numpy as np

from .errors import ERR_IO, ERR_OUTPUT_IS_INPUT, ERR_OUTPUT_SPECIAL, FsError

PathLike = Union[str, "os.PathLike[str]"]
STDOUT = "-"
_SPECIAL_ROOTS = ("/dev/", "/proc/", "/sys/")


def _umask() -> int:
    """The process umask (read without changing it where /proc allows)."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    old = os.umask(0o022)
    os.umask(old)
    return old


def _suffix(name: str) -> str:
    """The suffix a writer chooses its format by ('.blf', '.csv', or '.asc.gz')."""
    p = Path(name)
    if len(p.suffixes) >= 2 and p.suffixes[-1].lower() == ".gz":
        return "".join(p.suffixes[-2:])
    return p.suffix


def _same_file(a: str, b: str) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


def check_target(path: PathLike, inputs: Iterable[PathLike] = ()) -> Path:
    """The real path an output will replace, or FsError: a special file (661), one of the inputs
    (660), or a folder that does not exist (620)."""
    shown = os.fspath(path)
    if shown == STDOUT:
        raise FsError(ERR_OUTPUT_SPECIAL, "'-' (standard output) is accepted only for CSV outputs")
    absolute = os.path.abspath(shown)
    real = os.path.realpath(shown)
    if absolute.startswith(_SPECIAL_ROOTS) or real.startswith(_SPECIAL_ROOTS):
        raise FsError(
            ERR_OUTPUT_SPECIAL, f"refusing to write to {shown!r}: a device or system file, not a regular file"
        )
    if os.path.lexists(real):
        try:
            st = os.stat(real)
        except OSError as e:
            raise FsError(ERR_IO, f"cannot write {shown!r}: {e.strerror}") from None
        if not stat.S_ISREG(st.st_mode):
            kind = (
                "a directory"
                if stat.S_ISDIR(st.st_mode)
                else "a FIFO"
                if stat.S_ISFIFO(st.st_mode)
                else "a device"
                if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode)
                else "not a regular file"
            )
            raise FsError(ERR_OUTPUT_SPECIAL, f"refusing to write to {shown!r}: {kind}")
    for inp in inputs:
        if os.path.exists(os.fspath(inp)) and os.path.exists(real) and _same_file(os.fspath(inp), real):
            raise FsError(
                ERR_OUTPUT_IS_INPUT,
                f"output {shown!r} is the input {os.fspath(inp)!r}: refusing to overwrite an input",
            )
    folder = os.path.dirname(real)
    if not os.path.isdir(folder):
        raise FsError(ERR_IO, f"output folder does not exist: {os.path.dirname(shown) or '.'!r}")
    return Path(real)


class _Item:
    def __init__(self, shown: str, target: Path, tmp: Path) -> None:
        self.shown = shown
        self.target = target
        self.tmp = tmp


class Outputs:
    """Outputs of one command, all committed or none. Use as a context manager; leaving the block
    without ``commit()`` (an error, Ctrl-C) removes the temporary files and changes nothing."""

    def __init__(self, inputs: Iterable[PathLike] = ()) -> None:
        self.inputs = [os.fspath(p) for p in inputs if os.fspath(p) != STDOUT]
        self._items: list[_Item] = []
        self.committed = False

    def __enter__(self) -> Outputs:
        return self

    def __exit__(self, *exc: object) -> None:
        if not self.committed:
            self.discard()

    def add(self, path: PathLike) -> Path:
        """Check ``path`` and create its temporary file (same folder, same suffix, mode from the
        umask or the existing file); write into the returned path."""
        shown = os.fspath(path)
        target = check_target(shown, self.inputs)
        for it in self._items:
            if it.target == target:
                raise FsError(ERR_OUTPUT_IS_INPUT, f"output {shown!r} is given twice (also as {it.shown!r})")
        mode = 0o666 & ~_umask()
        if target.exists():
            mode = stat.S_IMODE(target.stat().st_mode)
        fd, tmp = _create_temporary(target, shown)
        try:
            os.fchmod(fd, mode)
        finally:
            os.close(fd)
        self._items.append(_Item(shown, target, Path(tmp)))
        return Path(tmp)

    def write_bytes(self, path: PathLike, data: bytes) -> None:
        """Add ``path`` and write ``data`` to its temporary file."""
        tmp = self.add(path)
        try:
            tmp.write_bytes(data)
        except OSError as e:
            raise FsError(ERR_IO, f"cannot write {os.fspath(path)!r}: {e.strerror or e}") from None

    def discard(self) -> None:
        """Remove every temporary file; the targets are untouched."""
        for it in self._items:
            try:
                os.unlink(it.tmp)
            except OSError:
                pass
        self._items = []

    def commit(self) -> None:
        """Rename every temporary file onto its target; on a failure restore the targets renamed so
        far (from hard links kept until now) and raise FsError(620)."""
        done: list[tuple[_Item, Path | None]] = []
        try:
            for it in self._items:
                backup: Path | None = None
                if it.target.exists():
                    backup = it.target.with_name(f".{it.target.name}.{secrets.token_hex(4)}.keep")
                    try:
                        os.link(it.target, backup)
                    except OSError:
                        backup = None
                try:
                    os.replace(it.tmp, it.target)
                except OSError:
                    if backup is not None:
                        os.unlink(backup)
                    raise
                done.append((it, backup))
        except OSError as e:
            for it, backup in reversed(done):
                try:
                    if backup is not None:
                        os.replace(backup, it.target)
                    else:
                        os.unlink(it.target)
                except OSError:
                    pass
            failed = self._items[len(done)].shown if len(done) < len(self._items) else "?"
            self.discard()
            raise FsError(
                ERR_IO, f"cannot write {failed!r}: {e.strerror or e}; nothing was changed"
            ) from None
        for _, backup in done:
            if backup is not None:
                try:
                    os.unlink(backup)
                except OSError:
                    pass
        self._items = []
        self.committed = True


def write_file(path: PathLike, data: bytes, inputs: Iterable[PathLike] = ()) -> None:
    """One output written through ``Outputs`` (temporary file, rename on success)."""
    with Outputs(inputs) as outs:
        outs.write_bytes(path, data)
        outs.commit()


def save_figure(outs: Outputs, fig: Any, path: PathLike, dpi: int = 110) -> None:
    """A matplotlib figure into ``outs`` (format from the target's suffix)."""
    tmp = outs.add(path)
    fmt = Path(os.fspath(path)).suffix.lstrip(".").lower() or "png"
    try:
        fig.savefig(tmp, dpi=dpi, format=fmt)
    except OSError as e:
        raise FsError(ERR_IO, f"cannot write plot {os.fspath(path)!r}: {e.strerror or e}") from None
    except ValueError as e:
        raise FsError(ERR_IO, f"cannot write plot {os.fspath(path)!r}: {e}") from None


def write_figure(fig: Any, path: PathLike, dpi: int = 110, outs: Outputs | None = None) -> None:
    """Lay a matplotlib figure out and write it into ``outs`` (or on its own: temporary file,
    rename on success); the figure is closed either way."""
    import matplotlib.pyplot as plt

    fig.tight_layout()
    try:
        if outs is not None:
            save_figure(outs, fig, path, dpi=dpi)
        else:
            with Outputs() as own:
                save_figure(own, fig, path, dpi=dpi)
                own.commit()
    finally:
        plt.close(fig)


def format_rows(block: np.ndarray) -> str:
    """Rows of a 2-D array as CSV lines (%.17g, round-trip exact), each ending in a newline."""
    if block.size == 0:
        return ""
    return "".join(",".join(f"{v:.17g}" for v in row) + "\n" for row in block.tolist())


@contextmanager
def csv_sink(path: PathLike, inputs: Iterable[PathLike] = ()) -> Iterator[IO[str]]:
    """A text stream for a CSV output: standard output for '-', else a temporary file committed
    when the block ends without an error."""
    if os.fspath(path) == STDOUT:
        yield sys.stdout
        sys.stdout.flush()
        return
    with Outputs(inputs) as outs:
        tmp = outs.add(path)
        try:
            with open(tmp, "w", encoding="ascii", newline="\n") as f:
                yield f
        except OSError as e:
            raise FsError(ERR_IO, f"cannot write {os.fspath(path)!r}: {e.strerror or e}") from None
        outs.commit()


def write_csv(
    path: PathLike, names: Sequence[str], blocks: Iterable[np.ndarray], inputs: Iterable[PathLike] = ()
) -> int:
    """Write a header and the rows of each block (streamed: one block in memory at a time);
    returns the number of rows."""
    n = 0
    with csv_sink(path, inputs) as f:
        f.write(",".join(names) + "\n")
        for block in blocks:
            b = np.asarray(block, dtype=float).reshape(-1, len(names))
            f.write(format_rows(b))
            n += b.shape[0]
    return n


def _create_temporary(target: Path, shown: str) -> tuple[int, str]:
    """A new file beside ``target`` (O_EXCL, random name, same suffix). Not ``tempfile``, which
    imports shutil, random, bz2 and lzma: start-up time of every command that writes."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    suffix = _suffix(target.name) or ".tmp"
    for _ in range(100):
        tmp = target.with_name(f".{target.name}.{secrets.token_hex(4)}{suffix}")
        try:
            return os.open(tmp, flags, 0o600), str(tmp)
        except FileExistsError:
            continue
        except OSError as e:
            raise FsError(ERR_IO, f"cannot write {shown!r}: {e.strerror}") from None
    raise FsError(ERR_IO, f"cannot write {shown!r}: no free temporary name in {str(target.parent)!r}")
