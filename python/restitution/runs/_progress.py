"""Long jobs: a progress line (impacts done, impacts/s, ETA) and a clean stop on Ctrl-C."""

from __future__ import annotations

import signal
import sys
import threading
import time
from types import FrameType, TracebackType
from typing import Any

from ..errors import RestitutionTypeError


class Progress:
    """tqdm when installed, else a one-line counter on stderr; does nothing when disabled.

    ``done`` counts impacts already finished before this run (a resumed sweep), so the ETA
    only extrapolates the work left at the rate measured in this run.
    """

    def __init__(self, total: int, *, done: int = 0, enabled: bool = True) -> None:
        self.total, self.done, self.enabled = total, done, enabled
        self._start_done, self.t0, self._last_print = done, time.perf_counter(), 0.0
        self.bar: Any = None
        if not enabled:
            return
        try:
            from tqdm import tqdm  # type: ignore[import-untyped, unused-ignore]
        except ImportError:
            return
        self.bar = tqdm(total=total, initial=done, unit="impact", unit_scale=True, dynamic_ncols=True)

    def update(self, k: int) -> None:
        self.done += k
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.update(k)
            return
        now = time.perf_counter()
        if now - self._last_print < 0.5 and self.done < self.total:
            return  # a terminal line per chunk would flood a log for small chunks
        self._last_print = now
        rate = (self.done - self._start_done) / max(now - self.t0, 1e-9)
        eta = (self.total - self.done) / rate if rate > 0 else float("inf")
        print(f"\r{self.done}/{self.total} impacts, {rate:,.0f}/s, ETA {eta:,.0f} s  ", end="", file=sys.stderr,
              flush=True)

    def close(self) -> None:
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.close()
        else:
            print(file=sys.stderr)


def want_progress(progress: bool | None, total: int) -> bool:
    """Default: a bar for sweeps of 50 000 impacts or more when stderr is a terminal."""
    if progress is None:
        return total >= 50_000 and sys.stderr.isatty()
    if not isinstance(progress, bool):
        raise RestitutionTypeError("progress", f"{type(progress).__name__} {progress!r:.80}", "True, False or None")
    return progress


class StopOnInterrupt:
    """While active, the first Ctrl-C only sets ``stopped`` so the job can finish (and keep) the
    chunk in flight and stop between chunks; a second Ctrl-C interrupts at once as usual.

    The engine runs with the GIL released, so Python sees the signal when the chunk returns
    anyway; handling it here turns "an exception somewhere" into "stop after this chunk".
    Signal handlers exist only in the main thread: elsewhere this is a no-op.
    """

    def __init__(self) -> None:
        self.stopped = False
        self._old: Any = None

    def _handler(self, signum: int, frame: FrameType | None) -> None:
        self.stopped = True
        signal.signal(signal.SIGINT, self._old)
        print("\ninterrupt: stopping after the chunk in flight (Ctrl-C again to abort at once)", file=sys.stderr)

    def __enter__(self) -> StopOnInterrupt:
        if threading.current_thread() is threading.main_thread():
            self._old = signal.signal(signal.SIGINT, self._handler)
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        if self._old is not None and threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, self._old)
