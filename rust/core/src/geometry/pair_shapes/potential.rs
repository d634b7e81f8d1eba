//! The area law's potential on a pair with corners and its exact derivatives (docs/model.md,
//! section 17.8): with the chord line l through the two points c_1, c_2 where the boundaries
//! cross, W = integral over the overlap of dist(p, l) dA (m^3), and the law's elastic force on
//! the lanes (x, y, phi1, phi2) is -kappa grad W. On the plate (a half-plane partner) W is the
//! plate's potential integral of the depth, whose gradient is the force k A at the overlap's
//! centroid: the law the plate uses.
//!
//! The derivative, by Reynolds' transport theorem: the chord cuts the overlap into the
//! particle's cap (bounded by the particle's boundary and the chord, on the side
//! sigma_1 = sign of s there, s(p) = n . (p - c_1)) and the partner's cap. The caps' boundaries
//! move with their bodies' rigid motions u_i, and the chord moves with the crossings, each
//! sliding along both boundaries: n_P . (c' - u_1(c)) = 0 and n_Q . (c' - u_2(c)) = 0. So
//!
//!   dW/dt = sum_i sigma_i integral_{cap_i} n . u_i dA - [w_1 (D - E) + w_2 E],
//!
//! the first term the boundary integral turned into an area integral (|s| vanishes on the
//! chord, u_i is divergence-free), the second the chord's own motion: w_k = n . c_k', with
//! D = integral of sign(s) dA and E = integral of sign(s) lambda dA, lambda = t . (p - c_1) / l
//! the position along the chord. Each w_k is linear in the lanes' rates (alpha_P n_P +
//! alpha_Q n_Q = n gives w_k = alpha_P n_P . u_1(c_k) + alpha_Q n_Q . u_2(c_k)), so the gradient
//! is read off in closed form from the caps' areas and first moments and the crossings'
//! boundary normals.

use super::{cross, dot, sub};

/// One cap of the overlap: its area and its first moment about the chord's first end c_1.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Cap {
    /// Area (m^2).
    pub area: f64,
    /// Integral of (p - c_1) dA (m^3).
    pub moment: [f64; 2],
}

/// One crossing of the two boundaries: where, and the particle's and the partner's boundary
/// normals there (any length, any sign).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Crossing {
    /// Where the boundaries cross (partner's frame, m).
    pub at: [f64; 2],
    /// The particle's boundary normal there.
    pub particle: [f64; 2],
    /// The partner's boundary normal there.
    pub partner: [f64; 2],
}

/// The potential integral W (m^3) and the generalised force -grad W on the lanes (m^2 on the
/// position, m^3 on the angles), the particle's centre at `q`, the partner's at the origin,
/// `n` the unit normal of the chord c_1 c_2, `caps` the particle's and the partner's. The
/// partner's torque is taken from the particle's and the force so that a rigid turn of the
/// whole pair does no work (angular momentum to the last bit).
pub(crate) fn potential_push(
    q: [f64; 2],
    n: [f64; 2],
    [c1, c2]: [Crossing; 2],
    caps: [Cap; 2],
) -> (f64, [f64; 4]) {
    let g = gradient(q, n, [c1, c2], caps);
    let force = [-g.grad[0], -g.grad[1]];
    let torque1 = -g.grad[2];
    (
        g.w,
        [force[0], force[1], torque1, -torque1 - cross(q, force)],
    )
}

/// W and its gradient on all four lanes, each term written out (the partner's torque too).
pub(crate) struct Gradient {
    /// The potential integral (m^3).
    pub w: f64,
    /// dW/d(x, y, phi1, phi2).
    pub grad: [f64; 4],
}

/// See [`potential_push`]; the partner's angle's derivative from its own terms.
pub(crate) fn gradient(q: [f64; 2], n: [f64; 2], c: [Crossing; 2], caps: [Cap; 2]) -> Gradient {
    let d = sub(c[1].at, c[0].at);
    let t = if dot(d, [n[1], -n[0]]) >= 0.0 {
        [n[1], -n[0]]
    } else {
        [-n[1], n[0]]
    };
    let l = dot(t, d);
    let s = caps.map(|cap| dot(n, cap.moment));
    // Each cap lies on one side of the chord; an empty one takes the other side.
    let mut sigma = s.map(f64::signum);
    if s[0] == 0.0 {
        sigma[0] = -sigma[1];
    }
    if s[1] == 0.0 {
        sigma[1] = -sigma[0];
    }
    let w = s[0].abs() + s[1].abs();
    let area_signed = sigma[0] * caps[0].area + sigma[1] * caps[1].area;
    let along = if l > 0.0 {
        (sigma[0] * dot(t, caps[0].moment) + sigma[1] * dot(t, caps[1].moment)) / l
    } else {
        0.0
    };
    // The caps' boundary terms: sigma_i integral n . u_i dA, u_1 = V + w1 z x (p - q),
    // u_2 = w2 z x p; the first moments about c_1 moved to each body's centre.
    let arm1 = [
        caps[0].moment[0] + caps[0].area * (c[0].at[0] - q[0]),
        caps[0].moment[1] + caps[0].area * (c[0].at[1] - q[1]),
    ];
    let arm2 = [
        caps[1].moment[0] + caps[1].area * c[0].at[0],
        caps[1].moment[1] + caps[1].area * c[0].at[1],
    ];
    let mut grad = [
        sigma[0] * caps[0].area * n[0],
        sigma[0] * caps[0].area * n[1],
        sigma[0] * cross(arm1, n),
        sigma[1] * cross(arm2, n),
    ];
    // The chord's motion: -(w_1 (D - E) + w_2 E).
    for (k, weight) in [(0, area_signed - along), (1, along)] {
        let x = &c[k];
        let det = cross(x.particle, x.partner);
        if det == 0.0 || weight == 0.0 {
            continue;
        }
        let a_p = cross(n, x.partner) / det;
        let a_q = cross(x.particle, n) / det;
        grad[0] -= weight * a_p * x.particle[0];
        grad[1] -= weight * a_p * x.particle[1];
        grad[2] -= weight * a_p * cross(sub(x.at, q), x.particle);
        grad[3] -= weight * a_q * cross(x.at, x.partner);
    }
    Gradient { w, grad }
}

/// A polygon's area and first moment about `o` (shoelace, relative to `o` so that slivers
/// keep their digits).
pub(crate) fn polygon_cap(mut points: impl Iterator<Item = [f64; 2]>, o: [f64; 2]) -> Cap {
    let Some(p0) = points.next() else {
        return CapSum::start([0.0; 2], [0.0; 2]).finish();
    };
    let mut sum = CapSum::start(p0, o);
    points.for_each(|p| sum.push(p));
    sum.finish()
}

/// The shoelace sums of [`polygon_cap`], fed one vertex at a time (a polygon whose vertices
/// lie in two runs of a slice is summed without chaining iterators).
pub(crate) struct CapSum {
    o: [f64; 2],
    first: [f64; 2],
    prev: [f64; 2],
    a2: f64,
    mx: f64,
    my: f64,
}

impl CapSum {
    /// The sums of the polygon's first vertex `p0`, about `o`.
    #[inline(always)]
    pub(crate) fn start(p0: [f64; 2], o: [f64; 2]) -> Self {
        let r = sub(p0, o);
        CapSum {
            o,
            first: r,
            prev: r,
            a2: 0.0,
            mx: 0.0,
            my: 0.0,
        }
    }

    /// The next vertex `p`.
    #[inline(always)]
    pub(crate) fn push(&mut self, p: [f64; 2]) {
        let r = sub(p, self.o);
        let w = cross(self.prev, r);
        self.a2 += w;
        self.mx += (self.prev[0] + r[0]) * w;
        self.my += (self.prev[1] + r[1]) * w;
        self.prev = r;
    }

    /// The polygon closed back to its first vertex.
    #[inline(always)]
    pub(crate) fn finish(mut self) -> Cap {
        let r0 = self.first;
        let w = cross(self.prev, r0);
        self.a2 += w;
        self.mx += (self.prev[0] + r0[0]) * w;
        self.my += (self.prev[1] + r0[1]) * w;
        Cap {
            area: 0.5 * self.a2,
            moment: [self.mx / 6.0, self.my / 6.0],
        }
    }
}
