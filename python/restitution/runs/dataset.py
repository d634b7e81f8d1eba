"""Sweeps streamed to a Parquet dataset: one file per chunk, resumable, memory bounded.

Layout of a dataset directory::

    manifest.json          the spec (scene, shape, axes, chunk size), package version, counts
    cases.parquet          the cases table, for sweeps over an explicit table
    part-000000.parquet    cases 0 .. chunk_size - 1, in case order
    part-000001.parquet    ...

Chunk ``k`` always holds cases ``k * chunk_size`` up to the next multiple, so which rows a file
holds depends on the spec only. A file is written to a hidden temporary name and renamed when
complete, so a file that exists is whole; each carries its chunk index, case range and the
spec's digest in its Parquet key-value metadata (``restitution.chunk``) along with the package
version and the spec. Resuming recomputes exactly the chunks without a valid file, after
checking that the spec is the one in the manifest (else it refuses, naming the first difference).

Reading checks every part against the manifest with the check resume uses
(:mod:`restitution.runs.store`, footers only), and one process writes a directory at a time
(:mod:`restitution.runs.lock`: a second writer is refused, naming the first one's pid, or waits).
"""

from __future__ import annotations

import json
import os
import queue
import re
import threading
import time
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path
from typing import Any, Callable

import polars as pl

from .._core import __version__ as ENGINE_VERSION
from ._progress import Progress, StopOnInterrupt, want_progress
from .. import _engine
from ..scene import Scene
from .lock import LOCK_FILE, WriterLock
from .store import (CASES_FILE, FORMAT, MANIFEST, META_KEY, check_cases_file, check_parts, check_rows,
                    fail, frame_digest, listed_parts, part_files, part_name, part_problem, read_manifest,
                    spec_digest, verified_parts)
from .sweep import DEFAULT_CHUNK, Chunk, SweepSpec, check_chunk_size, check_threads

_TMP = re.compile(r"^\.(part-\d+\.parquet|cases\.parquet|manifest\.json)\.(\d+)\.\d+\.tmp$")
#: The spec goes into each part's metadata too unless it is huge (long explicit axes).
_MAX_SPEC_IN_FILE = 64 * 1024


@dataclass(frozen=True)
class SweepResult:
    """What :func:`sweep_to_dataset` did."""

    path: Path
    n_cases: int
    n_chunks: int
    chunks_written: int
    """Chunks computed and written by this call."""
    chunks_skipped: int
    """Chunks already in the dataset (valid files) when this call started."""
    cases_written: int
    seconds: float

    @property
    def impacts_per_s(self) -> float:
        return self.cases_written / self.seconds if self.seconds > 0 else float("nan")


def sweep_to_dataset(
    scene: Scene | SweepSpec,
    out: str | Path,
    *,
    cases: pl.DataFrame | None = None,
    chunk_size: int | None = None,
    threads: int | None = None,
    progress: bool | None = None,
    resume: bool = False,
    scheduler: Any = None,
    wait: bool = False,
    **axes: Any,
) -> SweepResult:
    """Runs a sweep chunk by chunk into the Parquet dataset directory ``out``.

    Parameters
    ----------
    scene : Scene or SweepSpec
        The scene (with ``axes`` or ``cases`` as in :func:`restitution.sweep`), or a ready spec
        (e.g. from :func:`restitution.config.load_config`).
    out : path
        Dataset directory; created if missing. It must be new or empty unless ``resume``.
    chunk_size : int, optional
        Cases per chunk file (default :data:`restitution.sweep.DEFAULT_CHUNK`, or the
        dataset's own when resuming).
    threads : int, optional
        Engine threads per chunk (default: all cores). Rows do not depend on it.
    progress : bool, optional
        Progress bar (default: for 50 000 impacts or more when stderr is a terminal).
    resume : bool
        Continue the sweep already in ``out``: compute only the chunks without a valid file.
        Refused (``ValueError`` naming the first difference) if the spec is not the manifest's.
    scheduler : str or distributed.Client, optional
        Run the chunks as tasks on a Dask cluster (a scheduler address or a client); the
        files are written here, by this process, as the tasks finish.
    wait : bool
        One process writes a dataset directory at a time (a lock on ``out/.writer.lock``,
        released by the system when the writer ends, even killed). Another writer is refused
        (``RestitutionError`` naming its pid) unless ``wait``, which waits for it to finish.

    Returns
    -------
    SweepResult

    Raises
    ------
    KeyboardInterrupt
        After Ctrl-C, once the chunks in flight are written: every finished chunk is kept and
        ``resume=True`` continues from there.
    """
    spec = _spec_of(scene, cases, axes)
    out = Path(out)
    n_threads = check_threads(threads)
    resume, wait = _engine.boolean("resume", resume), _engine.boolean("wait", wait)
    with WriterLock(out, wait=wait):
        return _write(spec, out, chunk_size, resume, n_threads, progress, scheduler)


def _write(spec: SweepSpec, out: Path, chunk_size: int | None, resume: bool, n_threads: int,
           progress: bool | None, scheduler: Any) -> SweepResult:
    """:func:`sweep_to_dataset` once this process holds ``out``'s writer lock."""
    manifest = _open_dataset(spec, out, chunk_size, resume)
    chunk_size = manifest["chunk_size"]
    digest = manifest["spec_sha256"]

    chunks = list(spec.chunks(chunk_size))
    done = {c.index for c in chunks if _valid_part(out, c, digest)}
    pending = [c for c in chunks if c.index not in done]
    file_meta = _file_metadata(manifest)
    bar = Progress(spec.n_cases, done=sum(c.stop - c.start for c in chunks if c.index in done),
                   enabled=want_progress(progress, spec.n_cases))
    writer = _Writer(lambda c, frame: _write_part(out, c, frame, digest, file_meta))
    t0 = time.perf_counter()
    tally = _Tally(writer, bar)
    stopped = _run_pending(spec, pending, scheduler, n_threads, tally, writer, bar)
    result = SweepResult(out, spec.n_cases, len(chunks), tally.chunks, len(done), tally.cases,
                         time.perf_counter() - t0)
    if stopped:
        left = len(chunks) - len(done) - tally.chunks
        raise KeyboardInterrupt(f"stopped with {left} of {len(chunks)} chunks left in {out}; "
                                "run again with --resume (resume=True) to finish")
    return result


def _spec_of(scene: Scene | SweepSpec, cases: pl.DataFrame | None, axes: dict[str, Any]) -> SweepSpec:
    """The spec to run: ``scene`` itself when it is one (then no axes or cases may come with it)."""
    if isinstance(scene, SweepSpec):
        if axes or cases is not None:
            raise ValueError("give either a SweepSpec or a scene with axes/cases, not both")
        return scene
    return SweepSpec(scene, axes=axes, cases=cases)


def _open_dataset(spec: SweepSpec, out: Path, chunk_size: int | None, resume: bool) -> dict[str, Any]:
    """Prepares ``out`` for running ``spec`` and returns its manifest.

    A new directory gets the manifest (and the cases table); an existing sweep is resumed only
    when asked to and only with the same spec (and by default its own chunk size, since which
    rows a chunk file holds depends on it). Resuming mends what the spec determines: a manifest
    whose counts were edited and a damaged cases table are written again. Temporary files of
    dead writers are removed.
    """
    old = read_manifest(out) if (out / MANIFEST).exists() else None
    if old is not None and not resume:
        raise ValueError(f"`out` {out} already holds a sweep ({MANIFEST}); resume it (--resume, resume=True) "
                         "or choose another directory")
    if chunk_size is None:
        chunk_size = _old_chunk_size(old) if old is not None else DEFAULT_CHUNK
    chunk_size = check_chunk_size(chunk_size)
    manifest = make_manifest(spec, chunk_size)
    if old is not None:
        check_same_spec(old, manifest, out)
        counts = ("n_cases", "chunk_size", "n_chunks")
        if any(old.get(k) != manifest[k] for k in counts):  # edited counts: the spec's are the true ones
            manifest["created"] = old.get("created", manifest["created"])
            _write_manifest(out, manifest)
    else:
        _create(out, manifest)
    if spec.cases is not None:
        try:
            check_cases_file(out, manifest)
        except ValueError:  # a RestitutionFileError too
            _atomic_write(out / CASES_FILE, lambda tmp: spec.cases.write_parquet(tmp))  # type: ignore[union-attr]
    _remove_stale_tmp(out)
    return manifest


def _old_chunk_size(old: dict[str, Any]) -> Any:
    """A dataset's chunk size as its spec states it (covered by the digest), else the manifest's count."""
    spec = old.get("spec")
    sweep = spec.get("sweep") if isinstance(spec, dict) else None
    size = sweep.get("chunk_size") if isinstance(sweep, dict) else None
    return size if size is not None else old.get("chunk_size")


class _Tally:
    """The ``finished`` callback of the chunk loop: hands each chunk to the writer and counts
    what this call computed (for :class:`SweepResult` and the progress bar)."""

    def __init__(self, writer: _Writer, bar: Progress) -> None:
        self._writer, self._bar = writer, bar
        self.chunks = 0
        self.cases = 0

    def finished(self, c: Chunk, frame: pl.DataFrame) -> None:
        self._writer.put(c, frame)
        self.chunks += 1
        self.cases += c.stop - c.start
        self._bar.update(c.stop - c.start)


def _run_pending(spec: SweepSpec, pending: list[Chunk], scheduler: Any, n_threads: int, tally: _Tally,
                 writer: _Writer, bar: Progress) -> bool:
    """Runs the pending chunks here or on a Dask cluster; returns whether Ctrl-C stopped them.

    Whatever happens, every finished chunk is written before this returns or raises: the first
    Ctrl-C only stops between chunks, and an error (or a second Ctrl-C) is re-raised after the
    writer has drained.
    """
    error: BaseException | None = None
    with StopOnInterrupt() as stop:
        try:
            if scheduler is not None:
                from .distributed import run_chunks

                run_chunks(spec, pending, scheduler, n_threads, tally.finished, lambda: stop.stopped)
            else:
                for c in pending:
                    if stop.stopped:
                        break
                    tally.finished(c, spec.run(c.start, c.stop, n_threads))
        except BaseException as err:  # noqa: BLE001 - re-raised below, after the drain
            error = err
        finally:
            try:
                writer.close()  # every finished chunk is written before we return or raise
            except BaseException as err:  # noqa: BLE001
                error = error or err
            bar.close()
    if error is not None:
        raise error
    return stop.stopped


def make_manifest(spec: SweepSpec, chunk_size: int) -> dict[str, Any]:
    """The manifest of ``spec`` cut in chunks of ``chunk_size`` (``created`` aside, a pure function)."""
    body = spec.to_dict(chunk_size, CASES_FILE if spec.cases is not None else None)
    cases_sha = frame_digest(spec.cases) if spec.cases is not None else None
    return {
        "format": FORMAT,
        "restitution_version": ENGINE_VERSION,
        "spec": body,
        "axes": list(spec.axis_names),
        "cases_sha256": cases_sha,
        "spec_sha256": spec_digest(body, spec.axis_names, ENGINE_VERSION, cases_sha),
        "n_cases": spec.n_cases,
        "chunk_size": chunk_size,
        "n_chunks": spec.n_chunks(chunk_size),
        "integrator": spec.scene.integrator,
        "created": datetime.now(timezone.utc).isoformat(timespec="seconds"),
    }


def check_same_spec(old: dict[str, Any], new: dict[str, Any], where: Path) -> None:
    """Refuses (ValueError) to resume ``where`` with a spec other than its manifest's."""
    head = f"refusing to resume {where}:"
    if old.get("format") != FORMAT:
        raise ValueError(f"{head} its format is {old.get('format')!r}, this package writes {FORMAT!r}")
    if old.get("restitution_version") != new["restitution_version"]:
        raise ValueError(f"{head} it was written by restitution {old.get('restitution_version')}, this is "
                         f"{new['restitution_version']} (results may differ); start a new directory")
    diffs = _diff(old.get("spec", {}), new["spec"], "")
    if old.get("axes") != new["axes"]:
        diffs.insert(0, f"axis order (dataset: {old.get('axes')}, now: {new['axes']})")
    if old.get("cases_sha256") != new["cases_sha256"]:
        diffs.append(f"the cases table (dataset's copy: {where / CASES_FILE})")
    if not diffs and old.get("spec_sha256") != new["spec_sha256"]:
        diffs.append(f"spec_sha256 (dataset: {old.get('spec_sha256')}, now: {new['spec_sha256']})")
    if diffs:
        more = f"; and {len(diffs) - 1} more: {', '.join(d.split(' (')[0] for d in diffs[1:])}" if len(diffs) > 1 else ""
        raise ValueError(f"{head} the spec differs at {diffs[0]}{more}")


def _diff(a: Any, b: Any, key: str) -> list[str]:
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in list(a) + [k for k in b if k not in a]:
            sub = f"{key}.{k}" if key else k
            if k not in a or k not in b:
                out.append(f"{sub} (dataset: {_show(a.get(k, '<absent>'))}, now: {_show(b.get(k, '<absent>'))})")
            else:
                out.extend(_diff(a[k], b[k], sub))
        return out
    if a == b:
        return []
    if isinstance(a, list) and isinstance(b, list) and len(a) > 6:
        if len(a) != len(b):
            return [f"{key} (dataset: {len(a)} values, now: {len(b)})"]
        i = next(i for i, (x, y) in enumerate(zip(a, b)) if x != y)
        return [f"{key}[{i}] (dataset: {a[i]!r}, now: {b[i]!r})"]
    return [f"{key} (dataset: {_show(a)}, now: {_show(b)})"]


def _show(v: Any) -> str:
    s = json.dumps(v)
    return s if len(s) <= 80 else s[:77] + "..."


def missing_chunks(path: str | Path) -> list[int]:
    """Chunk indices of the dataset at ``path`` that have no file yet."""
    m = read_manifest(path)
    have = _part_files(Path(path))
    return [k for k in range(m["n_chunks"]) if k not in have]


def scan_dataset(path: str | Path, *, allow_partial: bool = False) -> pl.LazyFrame:
    """The dataset as a lazy frame, rows in case order (chunk files in index order).

    Checked before it is returned, from the files' footers and the manifest, never their data
    (:mod:`restitution.runs.store`, the check a resumed sweep makes): the manifest and the cases
    table, each part's chunk index, case range and spec digest, and their row counts. A damaged
    or foreign file raises :class:`~restitution.RestitutionError` naming it and the fix. An
    unfinished dataset raises ``ValueError`` (saying how many chunks are missing) unless
    ``allow_partial``, which reads the chunks that exist.
    """
    path = Path(path)
    m, parts = verified_parts(path, allow_partial=_engine.boolean("allow_partial", allow_partial))
    lazy = pl.scan_parquet([str(parts[k]) for k in sorted(parts)])
    check_rows(parts, m, _collect(parts, lazy.select(pl.len())).item())
    return lazy


def read_dataset(path: str | Path, *, allow_partial: bool = False) -> pl.DataFrame:
    """The dataset as one frame, rows in case order (what :func:`restitution.sweep` returns).

    Checked as :func:`scan_dataset` checks it (the row counts from the rows read): either the
    rows that were computed, or a :class:`~restitution.RestitutionError` naming the file at
    fault and the fix (``--resume`` recomputes a damaged part). The parts' footers are checked
    while their data are read (polars reads without the GIL), so the check adds little."""
    path = Path(path)
    m, parts = listed_parts(path, allow_partial=_engine.boolean("allow_partial", allow_partial))
    lazy = pl.scan_parquet([str(parts[k]) for k in sorted(parts)])
    read: dict[str, Any] = {}

    def collect() -> None:
        try:
            read["frame"] = _collect(parts, lazy)
        except BaseException as err:  # noqa: BLE001 - raised below, after the footers' check
            read["error"] = err

    reader = threading.Thread(target=collect, name="restitution-read", daemon=True)
    reader.start()
    try:
        check_parts(parts, m)  # a damaged or foreign part is named before any polars error
    finally:
        reader.join()
    if "error" in read:
        raise read["error"]
    frame: pl.DataFrame = read["frame"]
    check_rows(parts, m, frame.height)
    return frame


def _collect(parts: dict[int, Path], lazy: pl.LazyFrame) -> pl.DataFrame:
    """``lazy.collect()``; a part whose data pages do not read is named (not a bare polars error)."""
    try:
        return lazy.collect()
    except (OSError, pl.exceptions.PolarsError) as err:
        for k in sorted(parts):
            try:
                pl.read_parquet(parts[k])
            except (OSError, pl.exceptions.PolarsError) as one:
                raise fail(parts[k], f"its data cannot be read ({' '.join(str(one).split())[:160]})",
                           "delete it and resume the sweep (--resume, resume=True), which recomputes it (a resumed "
                           "sweep reads footers, not data, so it does not see this damage itself)") from None
        raise fail(next(iter(parts.values())).parent, f"the parts cannot be read together ({err})",
                   "report it: each part reads alone") from None


_part_files = part_files  # the name other modules import


def _create(out: Path, manifest: dict[str, Any]) -> None:
    if any(name != LOCK_FILE for name in os.listdir(out)):
        raise ValueError(f"`out` {out} exists, is not empty and holds no sweep ({MANIFEST}); "
                         "choose a new or empty directory")
    _write_manifest(out, manifest)


def _write_manifest(out: Path, manifest: dict[str, Any]) -> None:
    text = json.dumps(manifest, indent=1)
    _atomic_write(out / MANIFEST, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))


def _file_metadata(manifest: dict[str, Any]) -> dict[str, str]:
    spec = json.dumps(manifest["spec"])
    return {
        "restitution.version": manifest["restitution_version"],
        "restitution.integrator": manifest["integrator"],
        "restitution.spec": spec if len(spec) <= _MAX_SPEC_IN_FILE else f"(long: see {MANIFEST})",
        "restitution.axes": json.dumps(manifest["axes"]),
    }


def _valid_part(out: Path, c: Chunk, digest: str) -> bool:
    """Whether chunk ``c``'s file is valid (the one check readers make too,
    :func:`~restitution.runs.store.part_problem`, with its row count); an invalid file is removed."""
    path = out / part_name(c.index)
    if not path.exists():
        return False
    if part_problem(path, c.index, c.start, c.stop, digest, count_rows=True) is None:
        return True
    path.unlink()  # recomputed below; a stale file must not be read back as part of the sweep
    return False


def _write_part(out: Path, c: Chunk, frame: pl.DataFrame, digest: str, meta: dict[str, str]) -> None:
    info = json.dumps({"index": c.index, "start": c.start, "stop": c.stop, "spec_sha256": digest})
    _atomic_write(out / part_name(c.index), lambda tmp: frame.write_parquet(tmp, metadata={**meta, META_KEY: info}))


def _atomic_write(final: Path, write: Callable[[Path], Any]) -> None:
    """Writes through a hidden temporary file and renames it: a visible file is always whole."""
    tmp = final.with_name(f".{final.name}.{os.getpid()}.{threading.get_ident()}.tmp")
    try:
        write(tmp)
        with open(tmp, "rb+") as f:
            os.fsync(f.fileno())
        os.replace(tmp, final)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def _remove_stale_tmp(out: Path) -> None:
    """Temporary files of writers that died (killed mid-write); a live writer's are left alone."""
    for entry in os.scandir(out):
        m = _TMP.match(entry.name)
        if m and not _pid_alive(int(m.group(2))):
            Path(entry.path).unlink(missing_ok=True)


def _pid_alive(pid: int) -> bool:
    if pid == os.getpid():
        return False  # this process has no write in flight yet
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


class _Writer:
    """Writes finished chunks on a thread, so the engine computes the next chunk meanwhile
    (both release the GIL). The queue is short: memory holds at most a few chunks."""

    def __init__(self, write: Callable[[Chunk, pl.DataFrame], None], depth: int = 2) -> None:
        self._write, self._q = write, queue.Queue(maxsize=depth)  # type: ignore[var-annotated]
        self._err: BaseException | None = None
        self._thread = threading.Thread(target=self._loop, name="restitution-writer", daemon=True)
        self._thread.start()

    def _loop(self) -> None:
        while True:
            item = self._q.get()
            if item is None:
                return
            if self._err is None:
                try:
                    self._write(*item)
                except BaseException as err:  # noqa: BLE001 - handed to the main thread
                    self._err = err

    def put(self, c: Chunk, frame: pl.DataFrame) -> None:
        if self._err is not None:
            raise self._err
        self._q.put((c, frame))

    def close(self) -> None:
        self._q.put(None)
        self._thread.join()
        if self._err is not None:
            raise self._err


__all__ = ["SweepResult", "missing_chunks", "read_dataset", "read_manifest", "scan_dataset", "sweep_to_dataset"]
