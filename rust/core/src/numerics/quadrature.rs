//! A reference quadrature for the tests: the integral of a force over an approach that grows
//! like a power of the depth near touch, independent of the engine's own 8-point rule
//! (`impact/pair/depth.rs`).

/// Gauss-Legendre nodes and weights on [-1, 1], 4 points.
const G4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

/// The integral of `f` over [0, `delta`], in s = delta t^2 (an area growing like a power 3/2
/// of the depth is smooth in t), by 4-point Gauss-Legendre on 40 panels of t in [0, 1].
pub(crate) fn over_depth(f: impl Fn(f64) -> f64, delta: f64) -> f64 {
    let n = 40;
    let mut sum = 0.0;
    for i in 0..n {
        for &(g, w) in &G4 {
            let t = (i as f64 + 0.5 * (g + 1.0)) / n as f64;
            sum += 0.5 * w / n as f64 * f(delta * t * t) * 2.0 * delta * t;
        }
    }
    sum
}
