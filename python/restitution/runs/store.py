"""A dataset's files and the one check of each: what a reader and a resumed writer both trust.

A dataset directory holds ``manifest.json`` (the spec, its digest and the counts), optionally
``cases.parquet`` (a cases table) and ``part-%06d.parquet``, chunk by chunk. Each part carries,
in its Parquet footer's key-value metadata (``restitution.chunk``), its chunk index, its case
range and the spec's digest. Everything here reads footers and the manifest, never the data:

- :func:`check_manifest`: the manifest's digest matches its own contents (an edited spec, axis
  list, version or cases digest is caught), and its counts follow from its spec (an edited
  ``n_cases``, ``chunk_size`` or ``n_chunks`` is caught);
- :func:`part_problem`: a part is chunk ``k`` of this sweep (index, case range, digest and, for
  a resumed writer, its row count from the footer); a reader checks the row counts of all
  parts at once against the manifest (:func:`check_rows`);
- :func:`check_cases_file`: the cases table is whole and is the one the manifest names.

A failure raises :class:`~restitution.errors.RestitutionFileError` (a
:class:`~restitution.RestitutionError`) naming the file, what is wrong and the fix.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
from pathlib import Path
from typing import Any

import polars as pl

from ..errors import RestitutionFileError
from .lock import writer_of

FORMAT = "restitution-sweep/1"
MANIFEST = "manifest.json"
CASES_FILE = "cases.parquet"
#: Key of each part's metadata: its chunk index, case range and the spec's digest.
META_KEY = "restitution.chunk"
_PART = re.compile(r"^part-(\d+)\.parquet$")
#: How a damaged part is mended: a resumed sweep recomputes every part that fails the check.
RESUME = "resume the sweep (restitution sweep CONFIG --out DIR --resume, or resume=True), which recomputes it"


def fail(path: Path, problem: str, fix: str) -> RestitutionFileError:
    """The error of a damaged, foreign or edited file: ``PATH: PROBLEM; FIX``."""
    return RestitutionFileError("path", str(path), f"{problem}; {fix}")


def part_name(index: int) -> str:
    return f"part-{index:06d}.parquet"


def part_files(path: Path) -> dict[int, Path]:
    """The part files in ``path`` by chunk index (hidden temporary files excluded)."""
    out = {}
    with os.scandir(path) as entries:
        for entry in entries:
            m = _PART.match(entry.name)
            if m:
                out[int(m.group(1))] = Path(entry.path)
    return out


def spec_digest(spec: Any, axes: Any, version: str, cases_sha: str | None) -> str:
    """The spec's SHA-256: its config form, the result's input columns, the package version and
    the cases table's digest. Written into the manifest and into every part."""
    digest = hashlib.sha256()
    digest.update(json.dumps(spec, sort_keys=True).encode())
    digest.update(json.dumps(list(axes)).encode())
    digest.update(version.encode())
    if cases_sha is not None:
        digest.update(cases_sha.encode())
    return digest.hexdigest()


def frame_digest(df: pl.DataFrame) -> str:
    """A content digest of a cases table (names, dtypes, values; stable across polars versions)."""
    h = hashlib.sha256()
    for name in df.columns:
        col = df[name]
        h.update(f"{name}:{col.dtype}:".encode())
        h.update(json.dumps(col.to_list()).encode() if col.dtype == pl.String
                 else col.is_null().to_numpy().tobytes() + col.fill_null(0).to_numpy().tobytes())
    return h.hexdigest()


def read_manifest(path: str | Path) -> dict[str, Any]:
    """The manifest of the dataset at ``path`` (as written; :func:`check_manifest` checks it)."""
    p = Path(path) / MANIFEST
    try:
        m = json.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ValueError(f"{path} is not a sweep dataset (no {MANIFEST})") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
        raise fail(p, f"the manifest cannot be read ({' '.join(str(err).split())})",
                   "restore it from a backup (each part's metadata holds the spec, `restitution.spec`)") from None
    if not isinstance(m, dict):
        raise fail(p, "the manifest is not a JSON object", "restore it from a backup")
    return m


def check_manifest(path: Path, m: dict[str, Any]) -> None:
    """The manifest is one this package wrote and nobody edited (see the module doc)."""
    where = path / MANIFEST
    restore = "restore it from a backup, or recompute the sweep in a new directory"
    if m.get("format") != FORMAT:
        raise fail(where, f"its format is {m.get('format')!r}, this package reads {FORMAT!r}", restore)
    try:
        digest = spec_digest(m["spec"], m["axes"], m["restitution_version"], m["cases_sha256"])
        n_cases, chunk_size, n_chunks = m["n_cases"], m["chunk_size"], m["n_chunks"]
    except (KeyError, TypeError) as err:
        raise fail(where, f"the manifest lacks {err}", restore) from None
    if digest != m.get("spec_sha256"):
        raise fail(where, "its spec, axes, version or cases digest do not match its spec_sha256 (edited)", restore)
    counts = (n_cases, chunk_size, n_chunks)
    if not all(isinstance(x, int) and not isinstance(x, bool) for x in counts) or chunk_size < 1:
        raise fail(where, f"n_cases, chunk_size, n_chunks = {counts} are not counts (edited)", restore)
    spec_chunk = m["spec"].get("sweep", {}).get("chunk_size") if isinstance(m["spec"], dict) else None
    expected = _n_cases(path, m)
    if spec_chunk != chunk_size or (expected is not None and n_cases != expected) or \
            n_chunks != -(-n_cases // chunk_size):
        raise fail(where, f"its counts (n_cases {n_cases}, chunk_size {chunk_size}, n_chunks {n_chunks}) do not "
                   f"follow from its spec ({expected} cases in chunks of {spec_chunk}: "
                   f"{math.ceil(expected / spec_chunk) if expected and spec_chunk else '?'} chunks) (edited)",
                   restore)


def _n_cases(path: Path, m: dict[str, Any]) -> int | None:
    """The number of cases the manifest's spec describes (None for a cases table: its rows are
    checked with the file, :func:`check_cases_file`)."""
    spec = m["spec"]
    axes = spec.get("axes")
    if not isinstance(axes, dict):
        return None
    draws = spec.get("ensemble", {}).get("n", 1)
    return math.prod(len(v) for v in axes.values()) * draws


def check_cases_file(path: Path, m: dict[str, Any]) -> None:
    """A cases table's file is whole (its footer reads), has the rows the manifest counts and is
    the table the manifest's digest names."""
    if m.get("cases_sha256") is None:
        return
    f = path / CASES_FILE
    restore = (f"restore it from your copy of the cases table (the manifest's digest checks it), or recompute "
               f"the sweep in a new directory")
    try:
        cases = pl.read_parquet(f)
    except (OSError, pl.exceptions.PolarsError) as err:
        raise fail(f, f"the cases table cannot be read ({_one_line(err)})", restore) from None
    draws = m["spec"].get("ensemble", {}).get("n", 1)
    if cases.height * draws != m["n_cases"]:
        raise fail(f, f"it has {cases.height} rows, the manifest counts {m['n_cases'] // draws}", restore)
    if frame_digest(cases) != m["cases_sha256"]:
        raise fail(f, "its contents do not match the manifest's cases_sha256 (edited or replaced)", restore)


def part_problem(path: Path, index: int, start: int, stop: int, digest: str, *, count_rows: bool) -> str | None:
    """What makes the file ``path`` not chunk ``index`` (cases ``start:stop``) of the sweep with
    ``digest``, or None when it is. Reads the footer only; ``count_rows`` compares its row count
    too (a reader counts all parts' rows at once instead: :func:`check_rows`)."""
    try:
        raw = pl.read_parquet_metadata(path).get(META_KEY)
    except (OSError, pl.exceptions.PolarsError) as err:
        return f"its Parquet footer cannot be read, truncated or not Parquet ({_one_line(err)})"
    if raw is None:
        return f"it has no `{META_KEY}` metadata: sweep_to_dataset did not write it"
    try:
        info = json.loads(raw)
        got = (info["spec_sha256"], info["index"], info["start"], info["stop"])
    except (TypeError, KeyError, ValueError):
        return f"its `{META_KEY}` metadata is not what sweep_to_dataset writes ({raw!r:.80})"
    if got[0] != digest:
        return f"it belongs to another sweep (spec digest {str(got[0])[:12]}..., this dataset's {digest[:12]}...)"
    if got[1:] != (index, start, stop):
        return (f"it holds chunk {got[1]} (cases {got[2]}..{got[3]}), not chunk {index} (cases {start}..{stop}): "
                f"a copy of another part")
    if count_rows:
        rows = _rows(path)
        if rows != stop - start:
            return f"it has {rows} rows, chunk {index} has {stop - start}"
    return None


def check_rows(files: dict[int, Path], m: dict[str, Any], total: int) -> None:
    """``total`` rows were read from ``files``; if that is not the rows their chunks hold, names
    the first part whose own row count is wrong (counted from its footer)."""
    size, n = m["chunk_size"], m["n_cases"]
    expected = sum(min((k + 1) * size, n) - k * size for k in files)
    if total == expected:
        return
    for k in sorted(files):
        rows = _rows(files[k])
        if rows != min((k + 1) * size, n) - k * size:
            raise fail(files[k], f"it has {rows} rows, chunk {k} has {min((k + 1) * size, n) - k * size}", RESUME)
    raise fail(files[min(files)].parent, f"read {total} rows, its chunks hold {expected}", RESUME)


def _rows(path: Path) -> int | None:
    try:
        return int(pl.scan_parquet(path).select(pl.len()).collect().item())
    except (OSError, pl.exceptions.PolarsError):
        return None


def _one_line(err: BaseException) -> str:
    text = " ".join(str(err).split())
    return text if len(text) <= 160 else text[:157] + "..."


def verified_parts(path: Path, *, allow_partial: bool) -> tuple[dict[str, Any], dict[int, Path]]:
    """The manifest and the part files of the dataset at ``path``, by chunk index, each checked
    against the manifest (:func:`part_problem`, footers only), with the manifest itself and the
    cases table. An unfinished dataset raises ``ValueError`` unless ``allow_partial``."""
    m, parts = listed_parts(path, allow_partial=allow_partial)
    check_parts(parts, m)
    return m, parts


def listed_parts(path: Path, *, allow_partial: bool) -> tuple[dict[str, Any], dict[int, Path]]:
    """:func:`verified_parts` but for the parts' footers (:func:`check_parts`): the manifest and
    the cases table checked, the parts listed, none missing unless ``allow_partial``."""
    m = read_manifest(path)
    check_manifest(path, m)
    check_cases_file(path, m)
    n_chunks = m["n_chunks"]
    parts = part_files(path)
    extra = sorted(k for k in parts if k >= n_chunks)
    if extra:
        raise fail(parts[extra[0]], f"the manifest counts {n_chunks} chunks, this file would be chunk {extra[0]}",
                   "delete it if it does not belong here (or restore the manifest if it was edited)")
    missing = [k for k in range(n_chunks) if k not in parts]
    if missing and not allow_partial:
        writer = writer_of(path)
        how = (f"process {writer} is writing it now: wait for it" if writer else "finish it with --resume")
        raise ValueError(f"dataset {path} is incomplete: {len(missing)} of {n_chunks} chunks missing "
                         f"(first: {missing[0]}); {how}, or pass allow_partial=True")
    if not parts:
        raise ValueError(f"dataset {path} has no chunk files yet")
    return m, parts


def check_parts(parts: dict[int, Path], m: dict[str, Any]) -> None:
    """Every part is its chunk of the manifest's sweep (:func:`part_problem`, footers only)."""
    size, n, digest = m["chunk_size"], m["n_cases"], m["spec_sha256"]
    for k in sorted(parts):
        problem = part_problem(parts[k], k, k * size, min((k + 1) * size, n), digest, count_rows=False)
        if problem:
            raise fail(parts[k], problem, RESUME)


__all__ = ["CASES_FILE", "FORMAT", "MANIFEST", "META_KEY", "check_manifest", "check_parts", "listed_parts",
           "part_problem", "read_manifest", "verified_parts"]
