"""What checking a dataset costs when it is read (issue 42): ``rs.read_dataset`` of a 10^7-row
dataset against a bare ``pl.scan_parquet(files).collect()`` of the same files (what
``read_dataset`` did before it checked anything: the floor), timed alternately in one run.

The dataset is made once (``--dir``, kept between runs): a real manifest for a sweep of
10^4 angles x 10^3 values of mu in the default chunks of 8192 cases (1221 parts), each part
holding its cases' input columns and one computed chunk's record columns (the read does not
depend on what the numbers are), written by the writer ``sweep_to_dataset`` uses.

    python benchmarks/dataset_read_bench.py [--dir DIR] [--repeat N]

Prints the median seconds of each and their ratio (target: <= 1.1).
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np
import polars as pl

import restitution as rs
from restitution.runs import dataset as ds
from restitution.runs.store import part_files
from restitution.runs.sweep import DEFAULT_CHUNK, SweepSpec


def make(out: Path) -> None:
    """The 10^7-row dataset in ``out`` (nothing is computed but one chunk)."""
    scene = rs.Scene(integrator="verlet", dt_factor=0.09)
    spec = SweepSpec(scene, axes={"theta_deg": np.linspace(1.0, 90.0, 10_000), "mu": np.linspace(0.0, 1.0, 1_000)})
    manifest = ds.make_manifest(spec, DEFAULT_CHUNK)
    out.mkdir(parents=True)
    ds._write_manifest(out, manifest)
    record = spec.run(0, DEFAULT_CHUNK).drop(list(spec.axis_names))
    meta = ds._file_metadata(manifest)
    for c in spec.chunks(DEFAULT_CHUNK):
        frame = pl.concat([spec.inputs(c.start, c.stop)[1], record.head(c.stop - c.start)], how="horizontal")
        ds._write_part(out, c, frame, manifest["spec_sha256"], meta)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dir", type=Path, default=Path(tempfile.gettempdir()) / "restitution-read-bench")
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    if not (args.dir / ds.MANIFEST).exists():
        t0 = time.perf_counter()
        make(args.dir)
        print(f"made {args.dir} in {time.perf_counter() - t0:.1f} s")
    files = [str(p) for _, p in sorted(part_files(args.dir).items())]
    timings: dict[str, list[float]] = {"bare": [], "checked": []}
    reads = {"bare": lambda: pl.scan_parquet(files).collect().height, "checked": lambda: rs.read_dataset(args.dir).height}
    pl.scan_parquet(files).collect()  # warm the page cache for both
    rows = {}
    for k in range(args.repeat):  # alternated, the order swapped each round: a load on the machine hits both alike
        for name in (("bare", "checked") if k % 2 == 0 else ("checked", "bare")):
            t0 = time.perf_counter()
            rows[name] = reads[name]()
            timings[name].append(time.perf_counter() - t0)
    n_bare, n_checked = rows["bare"], rows["checked"]
    bare, checked = timings["bare"], timings["checked"]
    assert n_bare == n_checked == 10**7
    b, c = statistics.median(bare), statistics.median(checked)
    print(f"{len(files)} parts, {n_checked} rows; median of {args.repeat}: bare read {b:.3f} s, "
          f"read_dataset (checked) {c:.3f} s, ratio {c / b:.3f}")


if __name__ == "__main__":
    main()
