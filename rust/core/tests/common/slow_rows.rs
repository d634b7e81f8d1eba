/// (n, theta_deg, mu, gamma, E, v) of issue 14's table of slow impacts; r = 0.01, rho = 2500,
/// gear5 at dt_factor 0.01. Shared by `tests/bounded.rs` and `examples/long_runs.rs`.
pub const ROWS: [(usize, f64, f64, f64, f64, f64); 7] = [
    (3, 21.4, 0.0, 0.0, 4.8e11, 7.7e-5),
    (4, 17.5, 3e-4, 0.0, 1.75e9, 3.7e-4),
    (120, 2.8, 0.0029, 3.44, 1.3e11, 2.45e-5),
    (3, 65.2, 1e-5, 0.0, 2.2e11, 5.5e-6),
    (4, 0.47, 0.0, 0.0, 5.2e11, 3.7e-5),
    (120, 21.2, 0.0049, 0.158, 8.1e10, 1.36e-6),
    (3, 90.0, 1e-6, 0.0, 1e3, 1e-6),
];
