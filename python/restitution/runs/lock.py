"""One writer per dataset directory: an operating-system lock on ``DIR/.writer.lock``.

Two processes resuming one directory at once would both compute the missing chunks and race on
each file. The writer holds an exclusive ``flock`` (POSIX; ``msvcrt.locking`` on Windows) on
the lock file for as long as it writes, with its pid written inside for the message another
writer gets. The lock belongs to the open file, so the kernel releases it when the writer ends
in any way, killed by SIGKILL included: a dead writer never leaves a directory locked, and the
lock file that stays behind means nothing by itself (a finished writer removes it). (``flock`` on network file systems is
only as good as the file system's support: NFS v4 and Lustre honour it, some FUSE mounts do not.)
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from types import TracebackType
from typing import IO

from ..errors import RestitutionError

LOCK_FILE = ".writer.lock"
#: Seconds between tries of a writer that waits for the lock on Windows (POSIX waits in the kernel).
_POLL_S = 0.2


class WriterLock:
    """Holds ``out``'s writer lock while active (``with WriterLock(out, wait=False): ...``).

    Creates ``out`` if needed. With ``wait`` it blocks until the holder is done (Ctrl-C stops
    the wait); without, another holder raises :class:`~restitution.RestitutionError` naming
    its pid.
    """

    def __init__(self, out: Path, *, wait: bool = False) -> None:
        self.out, self.wait = Path(out), wait
        self._file: IO[str] | None = None
        self._made = False

    def __enter__(self) -> WriterLock:
        if self.out.exists() and not self.out.is_dir():
            raise ValueError(f"`out` {self.out} exists and is not a directory")
        self._made = not self.out.exists()
        self.out.mkdir(parents=True, exist_ok=True)
        while True:
            f = open(self.out / LOCK_FILE, "a+", encoding="utf-8")  # noqa: SIM115 - held until __exit__
            try:
                self._acquire(f)
            except BaseException:
                f.close()
                self._clean_up()
                raise
            if _same_file(f, self.out / LOCK_FILE):
                break
            f.close()  # the holder removed the file as we waited on it: lock the one there now
        f.seek(0)
        f.truncate()
        f.write(f"{os.getpid()}\n")
        f.flush()
        self._file = f
        return self

    def _acquire(self, f: IO[str]) -> None:
        if _try_lock(f):
            return
        holder = _holder(f)
        if not self.wait:
            raise RestitutionError(
                "out", str(self.out), f"a dataset directory no other process is writing: process {holder} "
                f"holds its lock ({self.out / LOCK_FILE}); wait for it to finish, or pass wait=True (--wait)")
        print(f"waiting for process {holder}, which is writing {self.out} (Ctrl-C to stop waiting)", file=sys.stderr)
        _lock_blocking(f)

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        if self._file is not None:
            # Removed while held (a waiter that then gets the lock sees the file gone and locks
            # the new one), so a finished or refused write leaves the directory as it was.
            (self.out / LOCK_FILE).unlink(missing_ok=True)
            _unlock(self._file)
            self._file.close()
            self._file = None
        self._clean_up()

    def _clean_up(self) -> None:
        """Removes ``out`` again if this lock made it and nothing was written into it."""
        if self._made:
            try:
                self.out.rmdir()
            except OSError:  # not empty: the writer wrote into it, or another lock file is there
                pass


def _same_file(f: IO[str], path: Path) -> bool:
    """Whether ``f`` is still the file at ``path`` (not removed or replaced meanwhile)."""
    try:
        st = os.stat(path)
    except FileNotFoundError:
        return False
    own = os.fstat(f.fileno())
    return (st.st_dev, st.st_ino) == (own.st_dev, own.st_ino)


def writer_of(out: Path) -> str | None:
    """"pid N" of the process writing ``out`` now, or None (nobody; or not known on Windows).
    Asks the lock without taking it for long, and without creating the lock file."""
    if sys.platform == "win32":  # pragma: no cover - a reader cannot read a held msvcrt lock
        return None
    try:
        f = open(out / LOCK_FILE, encoding="utf-8")  # noqa: SIM115 - closed below
    except OSError:
        return None
    with f:
        try:
            fcntl.flock(f.fileno(), fcntl.LOCK_SH | fcntl.LOCK_NB)
        except BlockingIOError:
            return _holder(f)
        fcntl.flock(f.fileno(), fcntl.LOCK_UN)
    return None


def _holder(f: IO[str]) -> str:
    """The pid the holder wrote (a holder that has not written it yet: "unknown")."""
    try:
        f.seek(0)
        text = f.read().strip()
    except OSError:  # Windows: the holder's locked byte cannot be read
        text = ""
    return f"pid {text}" if text.isdigit() else "(pid unknown)"


if sys.platform == "win32":  # pragma: no cover - the tests run on POSIX
    import msvcrt
    import time

    def _try_lock(f: IO[str]) -> bool:
        f.seek(0)
        try:
            msvcrt.locking(f.fileno(), msvcrt.LK_NBLCK, 1)
        except OSError:
            return False
        return True

    def _lock_blocking(f: IO[str]) -> None:
        while not _try_lock(f):
            time.sleep(_POLL_S)

    def _unlock(f: IO[str]) -> None:
        f.seek(0)
        msvcrt.locking(f.fileno(), msvcrt.LK_UNLCK, 1)

else:
    import fcntl

    def _try_lock(f: IO[str]) -> bool:
        try:
            fcntl.flock(f.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            return False
        return True

    def _lock_blocking(f: IO[str]) -> None:
        fcntl.flock(f.fileno(), fcntl.LOCK_EX)  # interrupted by Ctrl-C (KeyboardInterrupt)

    def _unlock(f: IO[str]) -> None:
        fcntl.flock(f.fileno(), fcntl.LOCK_UN)


__all__ = ["LOCK_FILE", "WriterLock"]
