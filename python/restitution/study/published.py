"""Published curves of the Chung & Ooi (2011) benchmark, digitised, for overlays only.

Chung, Y. C. & Ooi, J. Y. (2011), "Benchmark tests for verifying discrete element modelling
codes at particle impact level", Granular Matter 13:643-656. Test 4's figures carry the DEM
results for alumina ("oxide") and aluminium alloy ("alloy") and the measurements of Kharaz,
Gorham & Salman (2001), Powder Technology 120:281 ("experiment": 5 mm alumina spheres on a
thick soda-lime glass anvil at 3.9 m/s). Test 6's figure carries the DEM results for Al alloy
and nylon.

Source of the numbers: the digitisations distributed with KratosMultiphysics/Kratos,
``applications/DEMApplication/test_examples/basic_benchmarks/paper_data/benchmark4_graph{1,2,3}.dat``
and ``benchmark6_graph1.dat``. They are third-party readings of the printed figures (about
+-0.01 in e_t, +-10 rad/s in spin, +-1 deg in angle), not the authors' data. In that source the
alloy's rebound-angle curve is a copy of the oxide's, so it is left out here. The model is never
tuned to them: ``restitution validate`` only plots them and reports the deviations.

Each curve is ``(x, y)``: Test 4 against the incident angle from the normal (deg); e_t, the
rebound spin (rad/s, negative: forward rolling) and the contact-patch rebound angle (deg);
Test 6 beta against 3.5 mu (1 + e) v_n / V.
"""

from __future__ import annotations

TEST4_E_T = {
    "oxide": ((5.17, 10.16, 14.99, 20.06, 25.05, 30.12, 35.03, 40.02, 50.0, 59.98, 69.96, 80.02, 85.01),
              (0.948, 0.687, 0.624, 0.616, 0.634, 0.684, 0.737, 0.781, 0.845, 0.893, 0.932, 0.966, 0.983)),
    "alloy": ((5.09, 10.0, 15.07, 20.06, 24.97, 30.04, 35.03, 40.02, 49.92, 59.98, 70.04, 80.10, 84.93),
              (0.899, 0.671, 0.613, 0.609, 0.633, 0.683, 0.736, 0.780, 0.844, 0.891, 0.932, 0.966, 0.983)),
    "experiment": ((2.24, 4.22, 9.84, 20.22, 30.36, 39.54, 49.60, 71.07, 79.23, 85.17),
                   (0.797, 0.746, 0.675, 0.599, 0.690, 0.774, 0.848, 0.937, 0.970, 0.979)),
}

TEST4_OMEGA = {
    "oxide": ((4.95, 10.08, 14.97, 19.94, 24.91, 29.96, 34.93, 39.98, 50.0, 60.02, 69.96, 80.06, 85.03),
              (-19.3, -213.0, -377.8, -510.6, -599.4, -616.5, -582.3, -544.8, -457.0, -357.5, -246.2, -126.3,
               -63.1)),
    "alloy": ((4.95, 9.92, 14.97, 20.02, 24.91, 30.04, 34.85, 39.98, 50.0, 60.02, 69.96, 80.06, 85.03),
              (-35.3, -223.7, -389.6, -519.1, -599.4, -617.6, -582.3, -544.8, -458.1, -358.6, -245.1, -125.2,
               -64.2)),
    "experiment": ((5.90, 10.87, 21.12, 31.14, 38.95, 50.24, 60.10, 69.96, 78.56, 84.32),
                   (-134.9, -261.2, -573.7, -612.2, -595.1, -449.5, -375.7, -243.0, -142.4, -70.6)),
}

TEST4_REBOUND_ANGLE = {
    "oxide": ((4.90, 9.96, 14.93, 19.99, 24.96, 29.92, 34.96, 39.92, 49.83, 59.99, 69.74, 79.82, 84.78),
              (3.76, -1.56, -5.54, -7.54, -7.54, -3.55, 3.43, 11.57, 29.35, 47.79, 64.58, 78.70, 84.52)),
    "experiment": ((2.10, 3.94, 9.72, 20.31, 30.16, 39.12, 49.51, 59.90, 70.46, 78.86, 84.78),
                   (0.77, 0.77, -1.06, -8.53, -2.55, 9.91, 30.02, 49.95, 66.90, 78.87, 85.68)),
}

TEST6_BETA = {
    "alloy": ((0.176, 0.352, 0.551, 0.771, 0.969, 1.189, 1.454, 1.740, 2.093, 2.489, 2.996, 3.634, 4.515, 5.749,
               7.819, 11.894, 24.009),
              (-0.820, -0.633, -0.445, -0.243, -0.028, 0.097, 0.119, 0.100, 0.058, 0.005, -0.050, -0.100, -0.140,
               -0.175, -0.208, -0.258, -0.342)),
    "nylon": ((0.176, 0.374, 0.573, 0.749, 0.969, 1.189, 1.454, 1.740, 2.093, 2.511, 2.996, 3.612, 4.515, 5.771,
               7.819, 11.916, 24.009),
              (-0.824, -0.638, -0.443, -0.243, -0.026, 0.093, 0.119, 0.117, 0.095, 0.056, 0.007, -0.056, -0.120,
               -0.159, -0.118, -0.113, -0.116)),
}
