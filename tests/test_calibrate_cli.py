"""``restitution calibrate CONFIG --out DIR``: outputs, config errors (exit 2 naming the key) and Ctrl-C
(the batch in flight finishes, the unconverged chain is written, exit 130)."""

from __future__ import annotations

import signal
import subprocess
import sys
from pathlib import Path

import polars as pl
import pytest

from restitution import cli

pytest.importorskip("emcee")
ROOT = Path(__file__).resolve().parents[1]

CONFIG = """
[scene]
mu = 0.2
[data]
file = "data.csv"
[free]
mu = {{ dist = "uniform", lo = 0.0, hi = 0.6 }}
[fit]
seed = 3
{extra}
"""


def _setup(tmp_path: Path, extra: str = "") -> Path:
    pl.DataFrame({"theta_deg": [10.0, 20.0], "quantity": ["e_t", "e_t"], "value": [0.932, 0.860],
                  "sigma": [0.01, 0.01]}).write_csv(tmp_path / "data.csv")
    path = tmp_path / "cal.toml"
    path.write_text(CONFIG.format(extra=extra))
    return path


def test_calibrate_writes_samples_report_and_figures(tmp_path, capsys):
    out = tmp_path / "out"
    assert cli.main(["calibrate", str(_setup(tmp_path)), "--out", str(out)]) == 0
    assert "converged" in capsys.readouterr().out
    samples = pl.read_parquet(out / "samples.parquet")
    assert samples.columns == ["mu", "log_prob"] and 0.15 < samples["mu"].median() < 0.25
    report = (out / "report.md").read_text()
    assert "**converged.**" in report and "tol = 0.0001" in report and "p-value" in report
    assert (out / "fit.png").stat().st_size > 0 and (out / "corner.png").stat().st_size > 0


@pytest.mark.parametrize("extra, key", [("likelihood = \"cauchy\"", "likelihood"), ("walkers = 3", "walkers"),
                                        ("speed = 1", "fit.speed")])
def test_calibrate_config_errors_name_the_key(tmp_path, capsys, extra, key):
    assert cli.main(["calibrate", str(_setup(tmp_path, extra)), "--out", str(tmp_path / "o")]) == 2
    assert key in capsys.readouterr().err


def test_calibrate_bad_data_row_is_named(tmp_path, capsys):
    path = _setup(tmp_path)
    pl.DataFrame({"theta_deg": [10.0, 95.0], "quantity": ["e_t", "e_t"], "value": [0.9, 0.8],
                  "sigma": [0.01, 0.01]}).write_csv(tmp_path / "data.csv")
    assert cli.main(["calibrate", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "case 1" in err and "data.theta_deg" in err


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a child process")
def test_ctrl_c_stops_after_the_batch_and_writes_the_unconverged_chain(tmp_path):
    path = _setup(tmp_path, "min_ess = 1e9\nmax_iter = 1000000")  # never converges on its own
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-u", "-m", "restitution", "calibrate", str(path), "--out", str(out),
                             "--progress"], stderr=subprocess.PIPE, stdout=subprocess.PIPE)
    assert proc.stderr is not None
    proc.stderr.read(1)  # the progress line: the sampler is running
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "NOT converged: interrupted" in (out / "report.md").read_text()
    assert pl.read_parquet(out / "samples.parquet").height > 0


def test_the_example_config_is_the_example_script_s_problem():
    from restitution.calibrate import config

    problem, options = config.load(ROOT / "examples" / "calibrate_kharaz.toml")
    sys.path.insert(0, str(ROOT / "examples"))
    try:
        import calibrate_kharaz
    finally:
        sys.path.remove(str(ROOT / "examples"))
    assert problem.scene == calibrate_kharaz.SCENE
    assert problem.free == calibrate_kharaz.FREE and options["seed"] == 1
    assert problem.data.equals(__import__("restitution").datasets.kharaz2001())
