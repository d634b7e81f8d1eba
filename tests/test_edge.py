"""The binding's edge: what a call costs beyond the engine's own work.

Checked by count, not by time (a loaded machine makes any time threshold flaky): the binding
reports, per call, how often it went back to wait for a poll after the engine had returned
(``_core.last_call_diagnostics``). Issue 27: the Ctrl-C watcher, woken by the finished worker,
could miss the wake-up and wait a whole 20 ms poll period, in 10-50 % of calls.
"""

from __future__ import annotations

import time

import numpy as np

import restitution as rs
from restitution import _core


def waits_after_engine() -> int:
    return int(_core.last_call_diagnostics()["waits_after_engine"])


def test_no_simulate_call_waits_after_its_engine_returns() -> None:
    scenes = [rs.Scene(), rs.Scene.paper()]
    waits = []
    for scene in scenes:
        for theta in range(4, 90):
            rs.simulate(scene, theta_deg=float(theta))
            waits.append(waits_after_engine())
        rs.simulate(scene, theta_deg=30.0, trace=True)
        waits.append(waits_after_engine())
    assert sum(waits) == 0, f"{sum(waits)} waits after the engine returned in {len(waits)} calls"


def test_no_sweep_call_waits_after_its_engine_returns() -> None:
    scene = rs.Scene()
    waits = []
    for threads in (1, 2):
        for k in range(40):
            rs.sweep(scene, theta_deg=np.array([20.0 + k, 60.0]), threads=threads)
            waits.append(waits_after_engine())
    assert sum(waits) == 0, f"{sum(waits)} waits after the engine returned in {len(waits)} calls"


def test_the_diagnostics_time_the_engine() -> None:
    # The engine's own time lies inside the call's, and the 120-gon's impact (~5x the disc's
    # cost per impact) takes longer than the disc's: the diagnostic times the work.
    engine = {}
    for name, scene in {"disc": rs.Scene(), "120-gon": rs.Scene.paper()}.items():
        times = []
        for _ in range(5):
            start = time.perf_counter()
            rs.simulate(scene, theta_deg=45.0)
            wall = time.perf_counter() - start
            times.append(_core.last_call_diagnostics()["engine_s"])
            assert 0.0 < times[-1] <= wall
        engine[name] = min(times)
    assert engine["disc"] < engine["120-gon"]
