//! What the record examples (`plate_records`, `pair_records`) share: their random polygons,
//! drawn the same way for both, and a record written as the bits of its values.

use restitution_core::{Cell, Record, Shape};

/// The record's values in column order, each as its bits (or its name), space-separated, so
/// that two builds' records compare exactly with `diff`.
pub fn record_bits(rec: &Record) -> String {
    rec.cells()
        .iter()
        .map(|c| match c {
            Cell::F64(x) => format!("{:x}", x.to_bits()),
            Cell::Opt(x) => x.map_or("-".into(), |x| format!("{:x}", x.to_bits())),
            Cell::Int(i) => format!("{i}"),
            Cell::Bool(b) => format!("{b}"),
            Cell::Name(n) => n.to_string(),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// A regular 3- to 200-gon, or with probability `p_convex` a random convex polygon (an ellipse
/// of aspect 0.4 to 1 through random points), of circumradius about `r`.
pub fn random_polygon(r: f64, p_convex: f64, rng: &mut dyn FnMut() -> f64) -> Shape {
    let sizes = [3usize, 4, 5, 7, 12, 24, 60, 120, 200];
    let n = sizes[(rng() * sizes.len() as f64) as usize];
    if rng() < p_convex {
        let aspect = 0.4 + 0.6 * rng();
        let mut a: Vec<f64> = (0..n.max(5))
            .map(|_| rng() * std::f64::consts::TAU)
            .collect();
        a.sort_by(f64::total_cmp);
        a.dedup_by(|x, y| (*x - *y).abs() < 1e-3);
        let v: Vec<[f64; 2]> = a
            .iter()
            .map(|t| [r * t.cos(), r * aspect * t.sin()])
            .collect();
        Shape::convex_polygon(&v).unwrap_or_else(|_| Shape::regular_polygon(r, n).unwrap())
    } else {
        Shape::regular_polygon(r, n).unwrap()
    }
}
