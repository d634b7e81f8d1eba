"""A dataset gives back exactly what was computed, or says precisely what is wrong (issue 42).

Each damage is made the way it happens on a shared disk: a part copied over another (a stray
copy, a bad sync), a part from another sweep, a part cut short, a truncated file, an edited
manifest, a replaced cases table. On main (3d9409c) ``read_dataset`` returned rows for all of
them without a word. Now each is a ``RestitutionError`` naming the file and the fix, and a
resumed sweep mends what it can. One writer at a time: two real processes, one killed.
"""

from __future__ import annotations

import json
import shutil
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import polars as pl
import pytest
from polars.testing import assert_frame_equal

import restitution as rs
from restitution.cli import main
from restitution.runs.config import load_config
from restitution.runs.dataset import read_dataset, scan_dataset, sweep_to_dataset

CHEAP = rs.Scene(integrator="verlet", dt_factor=0.09)
AXES = {"theta_deg": np.linspace(5.0, 90.0, 100), "mu": [0.0, 0.3, 0.6, 0.9, 1.2, 1.5, 1.8, 2.1, 2.4, 2.7]}


@pytest.fixture(scope="module")
def pristine(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, pl.DataFrame]:
    """A finished 1000-case dataset in 10 chunks of 100, and the in-memory sweep's rows."""
    d = tmp_path_factory.mktemp("pristine") / "d"
    sweep_to_dataset(CHEAP, d, chunk_size=100, **AXES)
    return d, rs.sweep(CHEAP, **AXES)


@pytest.fixture
def dataset(pristine: tuple[Path, pl.DataFrame], tmp_path: Path) -> Path:
    """A fresh copy of the pristine dataset, to damage."""
    return Path(shutil.copytree(pristine[0], tmp_path / "d"))


def _refused(path: Path, *fragments: str, by_scan: bool = True) -> rs.RestitutionError:
    """``read_dataset``'s refusal (and ``scan_dataset``'s, which reads footers only)."""
    with pytest.raises(rs.RestitutionError) as err:
        read_dataset(path)
    for text in fragments:
        assert text in str(err.value), (text, str(err.value))
    if by_scan:
        with pytest.raises(rs.RestitutionError):
            scan_dataset(path)
    return err.value


def _resume_mends(d: Path, full: pl.DataFrame) -> None:
    sweep_to_dataset(CHEAP, d, resume=True, **AXES)
    assert_frame_equal(read_dataset(d), full, check_exact=True)


def _part(d: Path, k: int) -> Path:
    return d / f"part-{k:06d}.parquet"


def test_a_pristine_dataset_reads_back_exactly(dataset: Path, pristine: tuple[Path, pl.DataFrame]) -> None:
    assert_frame_equal(read_dataset(dataset), pristine[1], check_exact=True)


def test_a_part_copied_over_another_is_named_and_mended(dataset: Path, pristine: tuple[Path, pl.DataFrame]) -> None:
    shutil.copyfile(_part(dataset, 1), _part(dataset, 3))
    _refused(dataset, "part-000003.parquet", "holds chunk 1", "--resume")
    _resume_mends(dataset, pristine[1])


def test_a_part_of_another_sweep_is_named_and_mended(dataset: Path, pristine: tuple[Path, pl.DataFrame],
                                                      tmp_path: Path) -> None:
    other = tmp_path / "other"
    sweep_to_dataset(CHEAP.replace(gamma=0.2), other, chunk_size=100, **AXES)
    shutil.copyfile(_part(other, 4), _part(dataset, 4))
    _refused(dataset, "part-000004.parquet", "another sweep")
    _resume_mends(dataset, pristine[1])


@pytest.mark.parametrize("keep_metadata", [True, False])
def test_a_part_cut_short_is_named_and_mended(dataset: Path, pristine: tuple[Path, pl.DataFrame],
                                              keep_metadata: bool) -> None:
    part = _part(dataset, 6)
    meta = pl.read_parquet_metadata(part)
    pl.read_parquet(part).head(99).write_parquet(part, metadata=meta if keep_metadata else None)
    _refused(dataset, "part-000006.parquet", "99 rows" if keep_metadata else "no `restitution.chunk` metadata")
    _resume_mends(dataset, pristine[1])


def test_a_truncated_part_is_named_not_a_bare_polars_error(dataset: Path, pristine: tuple[Path, pl.DataFrame]) -> None:
    part = _part(dataset, 2)
    part.write_bytes(part.read_bytes()[:5000])
    _refused(dataset, "part-000002.parquet", "footer cannot be read", "--resume")
    _resume_mends(dataset, pristine[1])


def test_an_edited_n_chunks_is_caught_and_mended(dataset: Path, pristine: tuple[Path, pl.DataFrame]) -> None:
    m = json.loads((dataset / "manifest.json").read_text())
    m["n_chunks"] = 5
    (dataset / "manifest.json").write_text(json.dumps(m))
    _refused(dataset, "manifest.json", "n_chunks 5", "do not follow from its spec")
    _resume_mends(dataset, pristine[1])


def test_an_edited_spec_in_the_manifest_is_caught(dataset: Path) -> None:
    m = json.loads((dataset / "manifest.json").read_text())
    m["spec"]["scene"]["mu"] = 0.25
    (dataset / "manifest.json").write_text(json.dumps(m))
    _refused(dataset, "manifest.json", "spec_sha256 (edited)")


def test_a_part_beyond_the_manifest_is_named(dataset: Path) -> None:
    shutil.copyfile(_part(dataset, 9), _part(dataset, 10))
    _refused(dataset, "part-000010.parquet", "delete it")


def test_a_truncated_or_replaced_cases_file_is_named(tmp_path: Path) -> None:
    cases = pl.DataFrame({"theta_deg": np.linspace(10.0, 80.0, 40), "mu": np.linspace(0.0, 1.0, 40)})
    d = tmp_path / "c"
    sweep_to_dataset(CHEAP, d, cases=cases, chunk_size=16)
    full = read_dataset(d)
    f = d / "cases.parquet"
    good = f.read_bytes()
    f.write_bytes(good[: len(good) // 2])
    _refused(d, "cases.parquet", "cannot be read")
    cases.with_columns(pl.col("mu") * 0.5).write_parquet(f)
    _refused(d, "cases.parquet", "cases_sha256")
    cases.head(39).write_parquet(f)
    _refused(d, "cases.parquet", "39 rows")
    sweep_to_dataset(CHEAP, d, cases=cases, resume=True)  # the user's table is the manifest's: written again
    assert_frame_equal(pl.read_parquet(f), cases)
    assert_frame_equal(read_dataset(d), full, check_exact=True)


def test_an_ensemble_dataset_is_checked_too(tmp_path: Path) -> None:
    d = tmp_path / "e"
    rs.ensemble_to_dataset(CHEAP, d, 8, vary={"mu": rs.Uniform(0.0, 1.0)}, seed=3, theta_deg=[30.0, 60.0],
                           chunk_size=4)
    shutil.copyfile(_part(d, 0), _part(d, 2))
    with pytest.raises(rs.RestitutionError, match="part-000002.parquet"):
        rs.read_ensemble(d)


# --- one writer per directory: two real processes -----------------------------------------------

#: A real writer of CONFIG, slowed down (each chunk waits 0.4 s before it runs) to be caught mid-way.
SLOW_WRITER = textwrap.dedent("""
    import sys, time
    import restitution as rs
    from restitution.runs import sweep as s
    from restitution.runs.config import load_config
    run = s.SweepSpec.run
    s.SweepSpec.run = lambda self, *a, **k: (time.sleep(0.4), run(self, *a, **k))[1]
    spec, chunk_size = load_config(sys.argv[2])
    rs.sweep_to_dataset(spec, sys.argv[1], chunk_size=chunk_size, threads=1, progress=False, resume=True)
""")
CONFIG = ('[scene]\nintegrator = "verlet"\ndt_factor = 0.09\n'
          '[axes]\ntheta_deg = { start = 5.0, stop = 90.0, num = 100 }\n[sweep]\nchunk_size = 10\n')


def _start_writer(tmp_path: Path) -> tuple[subprocess.Popen[bytes], Path, Path]:
    """(the writer, its dataset directory, its config)."""
    out, cfg = tmp_path / "w", tmp_path / "c.toml"
    cfg.write_text(CONFIG)
    proc = subprocess.Popen([sys.executable, "-c", SLOW_WRITER, str(out), str(cfg)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    while not (out / "manifest.json").exists():  # the manifest is written under the lock
        if proc.poll() is not None or time.monotonic() > deadline:
            raise AssertionError(f"the writer ended or stalled: {proc.communicate()}")
        time.sleep(0.01)
    return proc, out, cfg


def _in_memory(cfg: Path) -> pl.DataFrame:
    spec, _ = load_config(cfg)
    return rs.sweep(spec.scene, theta_deg=spec.axes["theta_deg"])


def test_a_second_writer_is_refused_naming_the_first_and_a_killed_writer_leaves_no_lock(tmp_path: Path) -> None:
    proc, out, cfg = _start_writer(tmp_path)
    spec, _ = load_config(cfg)
    try:
        with pytest.raises(rs.RestitutionError, match=rf"process pid {proc.pid} holds its lock") as err:
            sweep_to_dataset(spec, out, resume=True)
        assert err.value.parameter == "out" and "wait=True" in str(err.value)
        with pytest.raises(ValueError, match=rf"incomplete: .* process pid {proc.pid} is writing it now"):
            read_dataset(out)  # a reader is told who is writing, not to resume
        assert proc.poll() is None, "the first writer was still writing"
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.communicate(timeout=60)
    assert proc.returncode == -signal.SIGKILL
    done = len(list(out.glob("part-*.parquet")))
    assert done < 10, "killed mid-way"
    result = sweep_to_dataset(spec, out, resume=True)  # the kernel released the lock
    assert (result.chunks_skipped, result.chunks_written) == (done, 10 - done)
    assert_frame_equal(read_dataset(out), _in_memory(cfg), check_exact=True)
    assert not (out / ".writer.lock").exists()


def test_a_second_writer_asked_to_wait_writes_nothing_twice(tmp_path: Path,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    proc, out, cfg = _start_writer(tmp_path)
    try:
        assert main(["sweep", str(cfg), "--out", str(out), "--resume", "--wait", "--no-progress"]) == 0
    finally:
        try:
            proc.communicate(timeout=60)  # it has released the lock; let it exit
        finally:
            if proc.poll() is None:
                proc.kill()
    assert proc.returncode == 0
    captured = capsys.readouterr()
    assert f"waiting for process pid {proc.pid}" in captured.err
    assert "wrote 0, kept 10" in captured.out  # it ran once the first had written all 10 chunks, once each
    assert_frame_equal(read_dataset(out), _in_memory(cfg), check_exact=True)


def test_a_part_with_damaged_data_pages_is_named(dataset: Path, pristine: tuple[Path, pl.DataFrame]) -> None:
    part = _part(dataset, 5)
    data = bytearray(part.read_bytes())
    data[64:4096] = bytes(4096 - 64)  # the first data pages zeroed, the footer intact (a disk fault)
    part.write_bytes(bytes(data))
    _refused(dataset, "part-000005.parquet", "data cannot be read", "delete it and resume", by_scan=False)
    with pytest.raises(pl.exceptions.ComputeError):  # a lazy frame's data are read by its collect
        scan_dataset(dataset).collect()
    part.unlink()
    _resume_mends(dataset, pristine[1])
