//! The random polygons of the record examples (`plate_records`, `pair_records`), drawn the same
//! way for both so that their records cover the same shapes.

use restitution_core::Shape;

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
