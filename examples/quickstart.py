"""A first tour: one impact, its trace, a small sweep, and the rigid-body check.

Run: python examples/quickstart.py
"""

import numpy as np

import restitution as rs

# The study's preset on an exact disc (r = 1 cm, v = 3.57 cm/s, E = 10 MPa, gamma = 0.33).
scene = rs.Scene(mu=0.1)
rec = rs.simulate(scene, theta_deg=20.0)
print(f"one impact at 20 deg, mu = 0.1: e_N = {rec.e_n:.5f}, e_T = {rec.e_t:.5f}, "
      f"e_kin = {rec.e_kin:.5f}, omega_out = {rec.omega_out:.4f} rad/s")

# Sliding throughout: rigid-body theory (the study's Eq. 2) with the measured e_N.
theory = 1.0 - scene.mu * (1.0 + rec.e_n) * np.tan(np.radians(20.0))
print(f"  sliding theory 1 - mu (1 + e_N) tan(theta) = {theory:.5f}")
print(f"  {rec.steps} steps over {rec.contact_time * 1e3:.3f} ms; energy residual {rec.energy_residual:.1e}")

# Inside the contact: every step as a polars frame.
trace = rs.simulate(scene.replace(mu=1.0), theta_deg=70.0, trace=True).trace
print(trace.select("t", "depth", "f_n", "f_t", "stick").describe())

# A sweep: theta x mu, run in Rust on all cores, returned as a polars frame.
df = rs.sweep(scene, theta_deg=np.arange(5.0, 90.0, 5.0), mu=[0.0, 0.5, 1.0])
print(df.select("theta_deg", "mu", "e_n", "e_t", "e_kin", "omega_out").head(6))
