//! A convex polygon's edges summed once, so that the part below the plate of a polygon with
//! many vertices there (a fine polygon deep in a soft plate) is measured in a few operations
//! rather than by a walk over every submerged vertex.
//!
//! The shoelace sums of the chain P, p_f, ..., p_l, Q (P and Q where the chain's outer edges
//! cross the plate) split into the sums over the chain's own edges, which a rotation leaves
//! alone or moves as a whole, and the two end edges: with p_j = R v_j + t, t = (0, y),
//! cross(p_j, p_j+1) = cross(v_j, v_j+1) - y (R (v_j+1 - v_j))_x, and the first moments'
//! sum of (p_j + p_j+1) cross(p_j, p_j+1) = R a + 2 t c - y R M r_x - 2 t y (p_l - p_f)_x,
//! with c, a, M the cumulative sums of cross(v_j, v_j+1), (v_j + v_j+1) cross(v_j, v_j+1)
//! and (v_j + v_j+1) (v_j+1 - v_j)^T, and r_x = (cos, -sin) the rotation's first row.

use super::overlap::{Corners, Overlap};
use super::polygon::crossing_x;
use nalgebra::Vector2;

/// Cumulative sums over a polygon's edges (v_j, v_j+1), j = 0 .. n-1 (v_n = v_0): entry k
/// holds the sums over the edges before k.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ChainSums {
    cross: Vec<f64>,
    moment: Vec<[f64; 2]>,
    outer: Vec<[f64; 4]>,
}

impl ChainSums {
    /// The sums of the polygon with body-frame vertices `v`.
    pub fn new(v: &[Vector2<f64>]) -> Self {
        let n = v.len();
        let mut sums = ChainSums {
            cross: vec![0.0; n + 1],
            moment: vec![[0.0; 2]; n + 1],
            outer: vec![[0.0; 4]; n + 1],
        };
        for j in 0..n {
            let (p, q) = (v[j], v[(j + 1) % n]);
            let c = p.x * q.y - p.y * q.x;
            let (s, d) = (p + q, q - p);
            let (m, o) = (sums.moment[j], sums.outer[j]);
            sums.cross[j + 1] = sums.cross[j] + c;
            sums.moment[j + 1] = [m[0] + s.x * c, m[1] + s.y * c];
            sums.outer[j + 1] = [
                o[0] + s.x * d.x,
                o[1] + s.x * d.y,
                o[2] + s.y * d.x,
                o[3] + s.y * d.y,
            ];
        }
        sums
    }

    /// (cross, moment, outer) summed over the `count` edges from edge `from` (cyclic).
    fn range(&self, from: usize, count: usize) -> (f64, [f64; 2], [f64; 4]) {
        let n = self.cross.len() - 1;
        let upto = |k: usize| (self.cross[k], self.moment[k], self.outer[k]);
        let diff = |a: (f64, [f64; 2], [f64; 4]), b: (f64, [f64; 2], [f64; 4])| {
            (
                b.0 - a.0,
                [b.1[0] - a.1[0], b.1[1] - a.1[1]],
                std::array::from_fn(|i| b.2[i] - a.2[i]),
            )
        };
        if from + count <= n {
            return diff(upto(from), upto(from + count));
        }
        let (tail, head) = (diff(upto(from), upto(n)), upto(from + count - n));
        (
            tail.0 + head.0,
            [tail.1[0] + head.1[0], tail.1[1] + head.1[1]],
            std::array::from_fn(|i| tail.2[i] + head.2[i]),
        )
    }

    /// The overlap with the plate of the polygon with vertices `v` (these sums'), its centroid
    /// at height `y` and orientation (sin, cos) `sc`, when exactly the `len` >= 1 vertices
    /// from `first` lie at or below the plate, their lowest being `low`: the same as the
    /// half-plane clip's up to rounding (the sums carry ~1e-16 of the polygon's own area,
    /// so this is for chains deep enough that their overlap is a good part of it).
    pub fn overlap(
        &self,
        v: &[Vector2<f64>],
        (first, len, low): (usize, usize, usize),
        y: f64,
        (s, c): (f64, f64),
    ) -> Overlap {
        let n = v.len();
        let world = |k: usize| {
            let p = &v[k % n];
            (c * p.x - s * p.y, y + s * p.x + c * p.y)
        };
        let last = first + len - 1;
        let (pf, pl) = (world(first), world(last));
        let xp = crossing_x(world(first + n - 1), pf);
        let xq = crossing_x(pl, world(last + 1));
        let (cr, mo, out) = self.range(first % n, len - 1);
        let rot = |a: [f64; 2]| [c * a[0] - s * a[1], s * a[0] + c * a[1]];
        // The chain's edges, then P -> p_f and p_l -> Q (Q -> P lies on the plate).
        let spread = pl.0 - pf.0;
        let area2 = cr - y * spread + xp * pf.1 - pl.1 * xq;
        let m_rx = [out[0] * c - out[1] * s, out[2] * c - out[3] * s];
        let (ra, rm) = (rot(mo), rot(m_rx));
        let chain = [
            ra[0] - y * rm[0],
            ra[1] + 2.0 * y * cr - y * rm[1] - 2.0 * y * y * spread,
        ];
        let (w_p, w_q) = (xp * pf.1, -pl.1 * xq);
        let mx = chain[0] + (xp + pf.0) * w_p + (pl.0 + xq) * w_q;
        let my = chain[1] + pf.1 * w_p + pl.1 * w_q;
        let (area, cx, cy) = (0.5 * area2, mx / (3.0 * area2), my / (3.0 * area2));
        let lowest = world(low);
        Overlap {
            area,
            cx,
            cy,
            chord: xq - xp,
            x_mid: 0.5 * (xp + xq),
            depth: -lowest.1,
            x_low: lowest.0,
            first_moment: -area * cy,
            corners: Corners {
                first: (first % n) as u32,
                count: len as u32,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::polygon::Polygon;

    /// The summed chain's overlap equals the half-plane clip's for deep and shallow chains
    /// of a fine and a coarse polygon at many orientations.
    #[test]
    fn chain_sums_give_the_clips_overlap() {
        for n in [12, 120, 4096] {
            let p = Polygon::regular(0.01, n).unwrap();
            for k in 0..40 {
                let phi = 0.37 * k as f64;
                let y = 0.01 * (0.999 - 0.012 * k as f64);
                // The clip's own sine and cosine: the two must see the same corners.
                let (s, c) = crate::numerics::trig::sin_cos(phi);
                let o = p.clip_below_plate(y, phi).unwrap();
                let (first, len) = (o.corners.first as usize, o.corners.count as usize);
                let low = p.lowest_vertex(s, c);
                let q = p.chain.overlap(&p.vertices, (first, len, low), y, (s, c));
                let r: f64 = 0.01;
                for (a, b, scale, what) in [
                    (o.area, q.area, r * r, "area"),
                    (o.area * o.cx, q.area * q.cx, r * r * r, "moment x"),
                    (o.first_moment, q.first_moment, r * r * r, "moment y"),
                ] {
                    let what = format!("n {n} k {k} {what}: {a:e} {b:e}");
                    assert!((a - b).abs() <= 1e-13 * scale, "{what}");
                }
                assert_eq!(
                    (o.chord, o.x_mid, o.depth),
                    (q.chord, q.x_mid, q.depth),
                    "n {n} k {k}"
                );
            }
        }
    }
}
