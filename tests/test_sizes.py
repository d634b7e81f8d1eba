"""A size that cannot finish is refused or estimated before it starts (issue 42, item 6).

On main (3d9409c) ``rs.ensemble(scene, 10**12, ...)`` spent minutes (in fact days) in its
up-front check with no output, to end, if ever, out of memory. Now results held in memory are
refused beyond ``MAX_IN_MEMORY_CASES`` before any work, naming the parameter and pointing to the
datasets; a dataset's long up-front check says first how long it will take, counts its progress
and stops on Ctrl-C.
"""

from __future__ import annotations

import select
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path


#: The documented limit (docs/errors.md; ``runs.sweep.MAX_IN_MEMORY_CASES``).
MAX_IN_MEMORY_CASES = 50_000_000


def _refusal(call: str) -> str:
    """The error ``call`` raises in a fresh process, which must end within a minute (where the
    size was not refused up front it would run for days: killed, the test fails)."""
    code = textwrap.dedent(f"""
        import restitution as rs
        scene, vary = rs.Scene(integrator="verlet", dt_factor=0.09), {{"mu": rs.Uniform(0.0, 1.0)}}
        try:
            {call}
        except rs.RestitutionError as err:
            print(err.parameter, "|", err)
    """)
    try:
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, timeout=60, check=True)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"not refused within a minute: {call}") from None
    return done.stdout.decode()


def test_an_ensemble_too_large_for_memory_is_refused_at_once() -> None:
    out = _refusal("rs.ensemble(scene, 10**12, vary=vary, seed=1, theta_deg=[30.0, 60.0])")
    assert out.startswith("n |") and f"{MAX_IN_MEMORY_CASES:,}" in out and "ensemble_to_dataset" in out, out


def test_the_limit_counts_points_times_draws() -> None:
    n = MAX_IN_MEMORY_CASES // 4 + 1
    out = _refusal(f"rs.ensemble(scene, {n}, vary=vary, seed=1, theta_deg=[20.0, 40.0, 60.0, 80.0])")
    assert out.startswith("n |") and "4 points" in out, out


def test_a_sweep_too_large_for_memory_is_refused_at_once() -> None:
    out = _refusal("rs.sweep(scene, theta_deg=[30.0] * 100_000, mu=[0.5] * 1_000)")
    assert out.startswith("theta_deg x mu |") and "sweep_to_dataset" in out, out


BIG = textwrap.dedent("""
    import sys, restitution as rs
    rs.ensemble_to_dataset(rs.Scene(integrator="verlet", dt_factor=0.09), sys.argv[1], 10**12,
                           vary={"mu": rs.Uniform(0.0, 1.0)}, seed=1, theta_deg=[30.0], progress=True, threads=1)
""")


def test_a_long_up_front_check_says_how_long_counts_and_stops_on_ctrl_c(tmp_path: Path) -> None:
    proc = subprocess.Popen([sys.executable, "-c", BIG, str(tmp_path / "big")], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    try:
        ready, _, _ = select.select([proc.stderr], [], [], 60.0)  # main said nothing, for days
        line = proc.stderr.readline().decode() if ready else ""  # type: ignore[union-attr]
        assert "checking 1,000,000,000,000 cases before running any" in line and "days" in line, line
        time.sleep(1.0)
        t0 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    assert time.monotonic() - t0 < 10.0
    assert b"KeyboardInterrupt" in err and b"impacts" in err  # stopped, after a progress count
    assert not (tmp_path / "big").exists(), "nothing was written"
