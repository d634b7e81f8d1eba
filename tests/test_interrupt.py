"""Ctrl-C stops the engine inside one long call: SIGINT raises KeyboardInterrupt within 1 s.

The engine runs with the GIL released; the binding lets Python's signal handlers run every
20 ms and stops the engine through its cancellation token (polled every few thousand steps).
Each case runs the engine in a child process that repeats one call lasting seconds (a
4096-gon at a small step: ~2e6 steps, ~2.5 s; a sweep chunk of 4000 impacts), so the signal
lands inside the engine and a binding that only checked signals between calls would fail.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import time

import pytest

CALLS = {
    "simulate": "rs.simulate(scene, theta_deg=30.0)",
    "trace": "rs.simulate(scene, theta_deg=30.0, trace=True)",
    "sweep": "rs.sweep(rs.Scene.paper(dt_factor=1e-4), theta_deg=np.linspace(5, 89, 4000), chunk_size=4000, threads=2)",
}

CHILD = """
import sys, numpy as np, restitution as rs
scene = rs.Scene.paper(shape=rs.RegularPolygon(r=0.01, n=4096), dt_factor=1e-5)  # ~2e6 steps, ~2.5 s
print("ready", flush=True)
while True:
    {call}
"""


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT semantics differ on Windows")
@pytest.mark.parametrize("name", CALLS)
def test_sigint_raises_keyboard_interrupt_within_a_second(name: str) -> None:
    child = subprocess.Popen([sys.executable, "-c", CHILD.format(call=CALLS[name])],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout is not None and child.stdout.readline().strip() == "ready"
        time.sleep(0.5)  # well inside the engine by now
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        _, err = child.communicate(timeout=10)
        elapsed = time.monotonic() - sent
    finally:
        child.kill()
    assert "KeyboardInterrupt" in err, err[-2000:]
    assert elapsed < 1.0, f"{name}: KeyboardInterrupt after {elapsed:.2f} s"
