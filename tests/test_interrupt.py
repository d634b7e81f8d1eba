"""Ctrl-C stops the engine inside one long call: SIGINT raises KeyboardInterrupt within 1 s.

The engine runs with the GIL released; every 20 ms of a call the binding lets Python's signal
handlers run (from the engine's own polls when it runs on the calling thread: one impact, a
trace, a sweep on one thread; from the calling thread while a parallel sweep runs on others) and
stops the engine through its cancellation token (polled every few thousand steps).
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
    "sweep, one thread": "rs.sweep(rs.Scene.paper(dt_factor=1e-4), theta_deg=np.linspace(5, 89, 4000), threads=1)",
    # Two 1024-gons: ~0.2 ms a step (their intersection), ~2e4 steps; polled every 4096 steps
    # as the plate is, the engine would not see the signal for most of a second.
    "pair of fine polygons": "rs.simulate(rs.Scene.paper(shape=pair_gon, partner=pair_gon, dt_factor=1e-3), theta_deg=30.0)",
}

CHILD = """
import sys, numpy as np, restitution as rs
scene = rs.Scene.paper(shape=rs.RegularPolygon(r=0.01, n=4096), dt_factor=1e-5)  # ~2e6 steps, ~2.5 s
pair_gon = rs.RegularPolygon(r=0.01, n=1024)
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


class Alarm(Exception):
    """What the test's SIGALRM handler raises."""


@pytest.mark.skipif(sys.platform == "win32", reason="no SIGALRM on Windows")
@pytest.mark.parametrize("threads", [1, 2])
def test_any_error_a_handler_raises_stops_the_call_even_after_a_nested_impact(threads: int) -> None:
    # The handler itself runs an impact (through the same binding, inside the watched call) and
    # then raises: the call must stop with the handler's error, not hang or panic.
    import restitution as rs

    long_scene = rs.Scene.paper(shape=rs.RegularPolygon(r=0.01, n=4096), dt_factor=1e-5)  # ~2.5 s
    nested = []

    def handler(signum: int, frame: object) -> None:
        nested.append(rs.simulate(rs.Scene(), theta_deg=45.0).e_n)
        raise Alarm

    previous = signal.signal(signal.SIGALRM, handler)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.1)
        start = time.monotonic()
        with pytest.raises(Alarm):
            if threads == 1:
                rs.simulate(long_scene, theta_deg=30.0)
            else:
                rs.sweep(long_scene, theta_deg=[30.0, 31.0], threads=threads)
        elapsed = time.monotonic() - start
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert nested == [rs.simulate(rs.Scene(), theta_deg=45.0).e_n]
    assert elapsed < 1.5, f"stopped after {elapsed:.2f} s of a ~2.5 s call"
