//! The contact law: normal force (area or linear law, with damping, never attractive) and the
//! tangential force, evaluated once per time step at the integrator's predicted state.

use crate::geometry::pair::PairFrame;
use crate::geometry::{disc_segment, parry, sphere_contact, Overlap, OverlapMethod, Shape};
use crate::law::tangential::{StickState, TangentialSpring};
use crate::model::{Hertz, Model, NormalLaw};
use crate::numerics::trig::sin_cos;

/// Position (x, y, phi) or velocity (vx, vy, omega) of the particle.
pub type Dof = [f64; 3];

/// The forces of one evaluation and where they act.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Forces {
    /// Total force and torque on the body (N/m, N).
    pub fx: f64,
    /// See `fx`.
    pub fy: f64,
    /// See `fx`.
    pub torque: f64,
    /// Elastic part of the (clipped) normal force.
    pub f_el: f64,
    /// Damping part of the (clipped) normal force.
    pub f_d: f64,
    /// Tangential force (along +x).
    pub f_t: f64,
    /// Overlap, if any.
    pub overlap: Option<Overlap>,
    /// Stick/slip state of this step.
    pub stick: StickState,
    /// x of the elastic force's point of application, relative to the centre of mass: the
    /// overlap centroid (area law) or the deepest point (linear law).
    pub x_el: f64,
    /// x of the damping force's point of application, relative to the centre of mass.
    pub x_damp: f64,
}

impl Forces {
    /// The forces on a body at centre height `y` from an overlap `o`: the normal force `f_n`
    /// = F_el + F_d with its parts `normal` = (F_el, F_d, x_el, x_damp) (after the clip; the
    /// sum passed in, not re-added: the fixed-step path selects it from the unclipped sum)
    /// and the tangential force `f_t`, acting at the overlap's centroid height; the torque
    /// about the centre of mass follows from where each acts.
    #[inline(always)]
    pub fn on_overlap(
        o: Overlap,
        y: f64,
        f_n: f64,
        normal: (f64, f64, f64, f64),
        f_t: f64,
        stick: StickState,
    ) -> Forces {
        let (f_el, f_d, x_el, x_damp) = normal;
        let arm_y = o.cy - y;
        Forces {
            fx: f_t,
            fy: f_n,
            torque: x_el * f_el + x_damp * f_d - arm_y * f_t,
            f_el,
            f_d,
            f_t,
            overlap: Some(o),
            stick,
            x_el,
            x_damp,
        }
    }

    /// Power of the normal force (elastic, damping) and of the tangential force for the body
    /// velocity `v` at centre height `y`: F . (v + omega x arm).
    #[inline]
    pub fn powers(&self, y: f64, v: &Dof) -> (f64, f64, f64) {
        match self.overlap {
            None => (0.0, 0.0, 0.0),
            Some(o) => (
                self.f_el * (v[1] + v[2] * self.x_el),
                self.f_d * (v[1] + v[2] * self.x_damp),
                self.f_t * (v[0] - v[2] * (o.cy - y)),
            ),
        }
    }
}

/// Where the particle meets the plate: its overlap and the depth of its lowest point.
///
/// One implementation per kind of shape, so that the integration loop is compiled for each:
/// the exact disc's loop then has no shape dispatch, and its zero lever arms (the centroid and
/// the chord midpoint lie on the vertical through the centre) fold away.
pub trait PlateGeometry: Clone {
    /// Whether the contact law has events inside a contact that the fixed-step integrators
    /// should locate (a polygon's corners crossing the plate). The exact disc has none: its
    /// loop is compiled without any of the event handling.
    const EVENTS: bool;
    /// Overlap for a centre of mass at height `y` and orientation `phi`; `None` when clear.
    fn overlap(&self, y: f64, phi: f64) -> Option<Overlap>;
    /// Signed depth of the lowest point below the plate (negative when clear).
    fn depth(&self, y: f64, phi: f64) -> f64;
    /// Number of corners (0 for a disc).
    fn corner_count(&self) -> usize {
        0
    }
    /// World height of corner `k` for the centre of mass at height `y`, orientation `phi`.
    fn corner_height(&self, _k: usize, _y: f64, _phi: f64) -> f64 {
        f64::NAN
    }
    /// x of corner `k` relative to the centre of mass, at orientation `phi`.
    fn corner_x(&self, _k: usize, _phi: f64) -> f64 {
        f64::NAN
    }
}

/// The normal force on a pair before the clip: its elastic and damping parts as numbers (their
/// sum decides the clip) and as generalised forces on the lanes (x, y, phi1, phi2).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairNormal {
    /// Elastic part (N/m).
    pub f_el: f64,
    /// Damping part (N/m).
    pub f_d: f64,
    /// The elastic part on the lanes.
    pub el: [f64; 4],
    /// The damping part on the lanes.
    pub damp: [f64; 4],
}

/// The normal law's force on an overlap, with its constants derived once per impact: the one
/// formula of each law that every integrator evaluates (a polygon under the linear law takes
/// [`vertex_springs`] instead).
#[derive(Debug, Clone, Copy)]
pub struct NormalForce {
    law: NormalLaw,
    /// E / L of the area law, so that the elastic force is one product per step.
    e_over_l: f64,
    /// gamma sqrt(m E) / L of the area law.
    area_damping: f64,
    /// The Hertz law's constants (zero for the other laws).
    hertz: Hertz,
}

impl NormalForce {
    /// The normal law of `model`.
    pub fn new(model: &Model) -> Self {
        NormalForce {
            law: model.scene.normal_law,
            e_over_l: model.scene.e_modulus / model.length,
            area_damping: model.area_damping,
            hertz: model.hertz.unwrap_or(Hertz {
                e_star: 0.0,
                g_star: 0.0,
                beta: 0.0,
                k: 0.0,
                c: 0.0,
                kt: 0.0,
                ct: 0.0,
            }),
        }
    }

    /// (F_el, F_d, x_el, x_damp) before the clip for the overlap `o` and the body velocity
    /// `v`: the area law on the overlap's area and chord, the linear law at the lowest point
    /// (a disc or sphere), the Hertz law at the depth (none above the plate, where the
    /// adaptive path continues a sphere's contact as nothing).
    #[inline(always)]
    pub fn on_overlap(&self, o: &Overlap, v: &Dof) -> (f64, f64, f64, f64) {
        match self.law {
            NormalLaw::Area => {
                // Exact rate of the overlap area: minus the chord times the normal velocity
                // of the body at the chord's midpoint (the body velocity is linear along it).
                let da_dt = o.area_rate(v);
                (
                    o.area * self.e_over_l,
                    self.area_damping * da_dt,
                    o.cx,
                    o.x_mid,
                )
            }
            NormalLaw::Linear { kn, cn } => {
                // One spring-dashpot at the lowest point.
                let ddepth_dt = o.depth_rate(v);
                (kn * o.depth, cn * ddepth_dt, o.x_low, o.x_low)
            }
            NormalLaw::Hertz { .. } => {
                // 4/3 E* sqrt(R) delta^(3/2) and the Tsuji dashpot ~ delta^(1/4) (section 14),
                // acting along the centre line.
                let h = &self.hertz;
                let delta = o.depth.max(0.0);
                let s = delta.sqrt();
                (h.k * delta * s, h.c * s.sqrt() * -v[1], 0.0, 0.0)
            }
        }
    }

    /// The normal force on a pair's frame `f` at lane velocity `v` = (g_x, g_y, omega1,
    /// omega2), before the clip (docs/model.md, section 17): the area law on the area, damped
    /// by dA/dt = -l (g_n + lever_rate_area . omega), acting along n at its levers; the linear
    /// law on the springs, each with its own dashpot; the Hertz law at the depth.
    /// `levers` false for round pairs, whose normal forces act on the line of centres: their
    /// levers are zero, and leaving the zeros' products out keeps them off the step's chain
    /// of dependent operations (1.36x the plate's step with them, against 1.08x).
    #[inline(always)]
    pub fn on_pair(&self, f: &PairFrame, v: &[f64; 4], levers: bool) -> PairNormal {
        let n = f.n;
        let g_n = n[0] * v[0] + n[1] * v[1];
        let at = |l: [f64; 2]| {
            if levers {
                l[0] * v[2] + l[1] * v[3]
            } else {
                0.0
            }
        };
        let (f_el, f_d) = match self.law {
            NormalLaw::Area if levers => {
                // Bodies with corners: the gradient of the potential (docs/model.md 17.8), whose
                // part along n is the normal force that friction and the clip read.
                let el = f.area_push.map(|x| x * self.e_over_l);
                let f_d = self.area_damping * (-f.chord * (g_n + at(f.lever_rate_area)));
                let ld = f.lever_rate_area;
                return PairNormal {
                    f_el: el[0] * n[0] + el[1] * n[1],
                    f_d,
                    el,
                    damp: [f_d * n[0], f_d * n[1], f_d * ld[0], f_d * ld[1]],
                };
            }
            NormalLaw::Area => (
                f.area * self.e_over_l,
                self.area_damping * (-f.chord * (g_n + at(f.lever_rate_area))),
            ),
            NormalLaw::Linear { kn, cn } => {
                let s = &f.springs;
                let rates = s.rates(v);
                let rate: f64 = (0..4).map(|i| s.sum[i] * v[i]).sum();
                return PairNormal {
                    f_el: kn * s.depth,
                    f_d: -cn * rate,
                    el: s.push.map(|x| kn * x),
                    damp: rates.map(|x| -cn * x),
                };
            }
            NormalLaw::Hertz { .. } => {
                let h = &self.hertz;
                let s = f.depth.max(0.0).sqrt();
                (h.k * f.depth * s, h.c * s.sqrt() * -g_n)
            }
        };
        // Round bodies: the law acts on the line of centres, without torque.
        PairNormal {
            f_el,
            f_d,
            el: [f_el * n[0], f_el * n[1], 0.0, 0.0],
            damp: [f_d * n[0], f_d * n[1], 0.0, 0.0],
        }
    }

    /// The rate of change of F_el + F_d on an exact disc of radius `r` (before the clip),
    /// for the overlap `o`, body velocity `v` and acceleration `a` (x, y, spin): the time
    /// derivative of [`NormalForce::on_overlap`] where the disc's lever arms are zero. The
    /// area law: dA/dt = -c v_y with c the chord, and dc/dt = -4 (r - depth) v_y / c; the
    /// linear law at the lowest point: d(depth)/dt = -v_y. `None` for the Hertz law (a sphere).
    pub fn rate_on_disc(&self, o: &Overlap, r: f64, v: &Dof, a: &Dof) -> Option<f64> {
        match self.law {
            NormalLaw::Area => {
                let dc_dt = -4.0 * (r - o.depth) * v[1] / o.chord;
                self.rate_on_area(o, (dc_dt, 0.0), v, a)
            }
            NormalLaw::Linear { kn, cn } => Some(-kn * v[1] - cn * a[1]),
            NormalLaw::Hertz { .. } => None,
        }
    }

    /// The rate of change of the area law's F_el + F_d (before the clip) on a half-plane
    /// overlap `o` whose chord and chord midpoint move at `(chord_rate, mid_rate)`, for the body
    /// velocity `v` and acceleration `a`: with dA/dt = -c (v_y + omega x_mid),
    /// d2A/dt2 = -(dc/dt (v_y + omega x_mid) + c (a_y + alpha x_mid + omega dx_mid/dt)).
    /// `None` under the other laws.
    pub fn rate_on_area(
        &self,
        o: &Overlap,
        (chord_rate, mid_rate): (f64, f64),
        v: &Dof,
        a: &Dof,
    ) -> Option<f64> {
        if self.law != NormalLaw::Area {
            return None;
        }
        let sink = v[1] + v[2] * o.x_mid;
        let d2a_dt2 = -(chord_rate * sink + o.chord * (a[1] + a[2] * o.x_mid + v[2] * mid_rate));
        Some(self.e_over_l * o.area_rate(v) + self.area_damping * d2a_dt2)
    }
}

/// The linear law on a polygon: one spring-dashpot per submerged corner (Cundall's vertex
/// contacts), each acting vertically at its corner. `corners` yields, for every corner at or
/// below the plate, its depth d_i and its x relative to the centre of mass; `v` is the body
/// velocity. Returns (F_el, F_d, x_el, x_damp): the elastic force kn sum d_i, the gradient of
/// the potential kn sum d_i^2 / 2 (torque included), at its centre x_el; the damping force
/// cn sum d(d_i)/dt, whose power -cn sum (d(d_i)/dt)^2 is never positive, at x_damp.
#[inline]
pub fn vertex_springs(
    kn: f64,
    cn: f64,
    corners: impl Iterator<Item = (f64, f64)>,
    v: &Dof,
) -> (f64, f64, f64, f64) {
    let (mut d, mut dx, mut rate, mut rate_x) = (0.0, 0.0, 0.0, 0.0);
    for (depth, x) in corners {
        let r = -(v[1] + v[2] * x);
        d += depth;
        dx += depth * x;
        rate += r;
        rate_x += r * x;
    }
    let x_el = if d != 0.0 { dx / d } else { 0.0 };
    let x_damp = if rate != 0.0 { rate_x / rate } else { 0.0 };
    (kn * d, cn * rate, x_el, x_damp)
}

/// The exact disc of radius `r`: closed-form circular segment.
#[derive(Debug, Clone, Copy)]
pub struct DiscPlate {
    /// Radius (m).
    pub r: f64,
}

impl PlateGeometry for DiscPlate {
    const EVENTS: bool = false;

    #[inline(always)]
    fn overlap(&self, y: f64, _phi: f64) -> Option<Overlap> {
        disc_segment(self.r, y)
    }

    #[inline(always)]
    fn depth(&self, y: f64, _phi: f64) -> f64 {
        self.r - y
    }
}

/// A sphere of radius `r`: its Hertz contact ([`sphere_contact`]), no events.
#[derive(Debug, Clone, Copy)]
pub struct SpherePlate {
    /// Radius (m).
    pub r: f64,
}

impl PlateGeometry for SpherePlate {
    const EVENTS: bool = false;

    #[inline(always)]
    fn overlap(&self, y: f64, _phi: f64) -> Option<Overlap> {
        sphere_contact(self.r, y)
    }

    #[inline(always)]
    fn depth(&self, y: f64, _phi: f64) -> f64 {
        self.r - y
    }
}

/// The overlap of `shape` with the plate at height `y` and orientation `phi`, computed by
/// `method`: the disc's closed form, or for polygons the half-plane clip or parry's general
/// intersection. A disc always uses its closed form (`OverlapMethod::check_shape` refuses
/// parry for it before an impact starts).
#[inline(always)]
pub fn plate_overlap(shape: &Shape, method: OverlapMethod, y: f64, phi: f64) -> Option<Overlap> {
    match (shape, method) {
        (Shape::Polygon(p), OverlapMethod::Parry) => parry::plate_overlap(p, y, phi),
        _ => shape.overlap(y, phi),
    }
}

/// Any shape: the disc's closed form, or for polygons the half-plane clip or parry's
/// general intersection, as `method` says.
#[derive(Debug, Clone, Copy)]
pub struct ShapePlate<'a> {
    /// The particle's shape.
    pub shape: &'a Shape,
    /// How the overlap is computed.
    pub method: OverlapMethod,
}

impl PlateGeometry for ShapePlate<'_> {
    const EVENTS: bool = true;

    fn corner_count(&self) -> usize {
        self.shape.vertices().len()
    }

    fn corner_height(&self, k: usize, y: f64, phi: f64) -> f64 {
        match self.shape {
            Shape::Polygon(p) => p.vertex_height(k, y, phi),
            Shape::Disc { .. } | Shape::Sphere { .. } => f64::NAN,
        }
    }

    fn corner_x(&self, k: usize, phi: f64) -> f64 {
        let (s, c) = sin_cos(phi);
        let v = &self.shape.vertices()[k];
        c * v.x - s * v.y
    }

    #[inline(always)]
    fn overlap(&self, y: f64, phi: f64) -> Option<Overlap> {
        plate_overlap(self.shape, self.method, y, phi)
    }

    #[inline(always)]
    fn depth(&self, y: f64, phi: f64) -> f64 {
        self.shape.touch_height(phi) - y
    }
}

/// The contact law with its history (the tangential spring).
#[derive(Debug, Clone)]
pub struct Contact<'a, G> {
    model: &'a Model,
    /// How the overlap is found.
    pub geometry: G,
    /// The Cundall-Strack spring.
    pub spring: TangentialSpring,
    /// The normal law.
    normal: NormalForce,
}

impl<'a, G: PlateGeometry> Contact<'a, G> {
    /// A fresh contact (unstretched spring).
    pub fn new(model: &'a Model, geometry: G) -> Self {
        Contact {
            model,
            geometry,
            spring: TangentialSpring::default(),
            normal: NormalForce::new(model),
        }
    }

    /// Forces at position `q` and velocity `v`; advances the tangential spring by `dt`.
    #[inline(always)]
    pub fn evaluate(&mut self, q: &Dof, v: &Dof, dt: f64) -> Forces {
        let m = self.model;
        let Some(o) = self.geometry.overlap(q[1], q[2]) else {
            self.spring.reset();
            return Forces::default();
        };
        let (f_el, f_d, x_el, x_damp) = match m.scene.normal_law {
            NormalLaw::Linear { kn, cn } if G::EVENTS => {
                // A polygon: one spring-dashpot per submerged corner (see `vertex_springs`).
                let g = &self.geometry;
                let below = (0..g.corner_count()).filter_map(|k| {
                    let h = g.corner_height(k, q[1], q[2]);
                    (h <= 0.0).then(|| (-h, g.corner_x(k, q[2])))
                });
                vertex_springs(kn, cn, below, v)
            }
            // The disc or sphere (its lowest point below the centre), and the area law.
            _ => self.normal.on_overlap(&o, v),
        };
        // The plate never pulls. (f_n is selected from the sum rather than re-added after the
        // clip: the same value, one addition less on the step's critical path.)
        let f_n = f_el + f_d;
        let (f_n, f_el, f_d) = if f_n < 0.0 {
            (0.0, 0.0, 0.0)
        } else {
            (f_n, f_el, f_d)
        };
        let arm_y = o.cy - q[1];
        let v_t = v[0] - v[2] * arm_y;
        let (f_t, stick) = tangential_step(&mut self.spring, m, o.depth, v_t, dt, f_n);
        Forces::on_overlap(o, q[1], f_n, (f_el, f_d, x_el, x_damp), f_t, stick)
    }
}

/// One step of `model`'s tangential spring at depth `depth`, contact-point slip velocity
/// `v_t` and normal force `f_n`: Mindlin's (its stiffness and damping at the depth, its history
/// rescaled where the variant says) or the Cundall-Strack spring. The plate's and the pair's
/// contact both step their spring here.
#[inline(always)]
pub(crate) fn tangential_step(
    spring: &mut TangentialSpring,
    model: &Model,
    depth: f64,
    v_t: f64,
    dt: f64,
    f_n: f64,
) -> (f64, StickState) {
    if model.mindlin {
        let (k_xi, rate, ct) = model.spring(depth);
        if model.history.rescales() {
            spring.rescale(depth);
        }
        spring.step_scaled(v_t, dt, model.scene.mu, f_n, k_xi, rate, ct)
    } else {
        spring.step(v_t, dt, model.scene.mu, f_n, model.kt, model.ct)
    }
}
