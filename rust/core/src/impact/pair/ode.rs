//! The pair's ODE on the adaptive path: the state, the modes of a piece (clip, stick, slip), the
//! derivative in a mode, and the event functions that end a piece (docs/model.md, 17.5).

use crate::geometry::pair::{HeldSprings, PairGeometry};
use crate::impact::adaptive::{spring_scale, velocity_scales};
use crate::law::contact::NormalForce;
use crate::law::pair::{dot, PairForces};
use crate::law::StickState;
use crate::model::{Initial, NormalLaw, Pair};
use std::f64::consts::PI;

/// x, y, g_x, g_y, phi1, omega1, phi2, omega2, xi, then the works of the normal and the
/// tangential force, and of the normal force's dashpot alone.
pub(super) const NS: usize = 12;
pub(super) type State = [f64; NS];
pub(super) const X: usize = 0;
pub(super) const Y: usize = 1;
pub(super) const GX: usize = 2;
pub(super) const GY: usize = 3;
pub(super) const W1: usize = 5;
pub(super) const W2: usize = 7;
pub(super) const XI: usize = 8;
pub(super) const WN: usize = 9;
pub(super) const WT: usize = 10;
pub(super) const WD: usize = 11;

/// The error scale of each state component, from the impact's own scales, by the plate's rules
/// (`velocity_scales`, `spring_scale`): the velocities' the incident ones, floored at 1e-3 of the
/// impact's `speed`; positions what they cover in t_c / pi; the spring the elongation holding the
/// contact point's energy; works the energy.
pub(super) fn error_scales(
    pair: &Pair,
    init: &Initial,
    (speed, energy): (f64, f64),
    t_est: f64,
    depth: f64,
) -> State {
    let (r1, r2) = (pair.particle.r, pair.r2);
    let t_c = t_est / PI;
    let [vx, vy, spin] = velocity_scales(init, speed);
    [
        vx * t_c,
        vy * t_c,
        vx,
        vy,
        spin / r1 * t_c,
        spin / r1,
        spin / r2 * t_c,
        spin / r2,
        spring_scale(&pair.law, vx, depth),
        energy,
        energy,
        energy,
    ]
}

/// The tangential law of a piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Tan {
    /// mu = 0.
    None,
    Stick,
    /// F_t = mu F_n s, s = +-1.
    Slip(f64),
    /// The normal force is clipped: no tangential force.
    Free,
}

/// The law that holds in a piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Mode {
    pub(super) clipped: bool,
    /// Bodies with corners between contacts (no force; the piece ends at the next touch).
    pub(super) apart: bool,
    pub(super) tan: Tan,
}

/// The switches that end a piece; each event function is <= 0 while the piece's mode holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Event {
    Separate,
    Touch,
    ClipOn,
    ClipOff,
    ToSlip,
    ToStick,
    /// The linear law's held vertex springs switch (docs/model.md, 17.8).
    Springs,
}

/// What one evaluation yields besides the derivative.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Eval {
    /// F_el + F_d before the clip, and its parts as they act (clipped by the mode).
    pub(super) f_raw: f64,
    pub(super) f_el: f64,
    pub(super) f_d: f64,
    pub(super) f_t: f64,
    pub(super) trial: f64,
    pub(super) v_t: f64,
    pub(super) depth: f64,
    pub(super) area: f64,
    pub(super) n: [f64; 2],
    /// The elastic and damping parts on the lanes (clipped by the mode) and the tangential
    /// force's lever (`PairFrame`).
    pub(super) el: [f64; 4],
    pub(super) damp: [f64; 4],
    pub(super) lever_t: [f64; 2],
}

impl Eval {
    /// The evaluation as the fixed steps report theirs (for the trace), in mode `m`.
    pub(super) fn forces(&self, m: &Mode) -> PairForces {
        PairForces {
            f_el: self.f_el,
            f_d: self.f_d,
            f_t: self.f_t,
            n: self.n,
            el: self.el,
            damp: self.damp,
            lever_t: self.lever_t,
            area: self.area,
            depth: self.depth,
            stick: match m.tan {
                Tan::Stick => StickState::Stick,
                Tan::Slip(_) => StickState::Slip,
                _ => StickState::None,
            },
        }
    }
}

/// The pair's ODE.
pub(super) struct PairOde<'a, G> {
    pub(super) pair: &'a Pair,
    pub(super) geometry: G,
    pub(super) mu: f64,
    pub(super) normal: NormalForce,
    /// 1 / m*, 1 / I1, 1 / I2.
    pub(super) inv: [f64; 3],
    /// The forward difference's time step for the slip -> stick rates.
    pub(super) fd_step: f64,
    /// The linear law's vertex springs held through the piece (`PairGeometry::held_springs`).
    pub(super) held: HeldSprings,
}

impl<G: PairGeometry> PairOde<'_, G> {
    /// The derivative `ds` of state `s` in mode `m`, and the forces.
    pub(super) fn eval(&self, m: &Mode, s: &State, ds: &mut State) -> Eval {
        let law = &self.pair.law;
        let q = [s[X], s[Y], s[4], s[6]];
        let g = [s[GX], s[GY]];
        let v = [s[GX], s[GY], s[W1], s[W2]];
        let at = |l: [f64; 2]| l[0] * s[W1] + l[1] * s[W2];
        let mut e = Eval::default();
        match self.geometry.frame_held(&q, &self.held) {
            Some(fr) => {
                let normal = self.normal.on_pair(&fr, &v, G::CORNERS);
                e.f_raw = normal.f_el + normal.f_d;
                // Apart, the touch is an event: a force at once (the linear law's dashpot
                // jumps there) in the stages past it would spoil the state located there.
                if !m.clipped && !m.apart {
                    (e.f_el, e.f_d) = (normal.f_el, normal.f_d);
                    (e.el, e.damp) = (normal.el, normal.damp);
                }
                (e.n, e.depth, e.area) = (fr.n, fr.depth, fr.area);
                e.lever_t = fr.lever_t;
            }
            None => {
                // Apart: the depth is minus the gap (round bodies: at no cost), the normal the
                // line of centres.
                let d = q[0].hypot(q[1]);
                e.n = [q[0] / d, q[1] / d];
                e.depth = self.geometry.signed_depth(&q);
            }
        }
        let n = e.n;
        let t = [n[1], -n[0]];
        let (g_n, g_t) = (n[0] * g[0] + n[1] * g[1], t[0] * g[0] + t[1] * g[1]);
        e.v_t = g_t + at(e.lever_t);
        let (k_xi, rate, ct) = law.spring(e.depth.max(0.0));
        e.trial = -k_xi * s[XI] - ct * e.v_t;
        let f_n = e.f_el + e.f_d;
        ds[XI] = 0.0;
        e.f_t = match m.tan {
            Tan::Stick if e.depth > 0.0 => {
                let shrink = if g_n > 0.0 {
                    law.history_shrink(e.depth, -g_n)
                } else {
                    0.0
                };
                ds[XI] = rate * e.v_t + shrink * s[XI];
                e.trial
            }
            Tan::Slip(sg) => sg * self.mu * f_n,
            _ => 0.0,
        };
        let tan = [
            e.f_t * t[0],
            e.f_t * t[1],
            e.f_t * e.lever_t[0],
            e.f_t * e.lever_t[1],
        ];
        let f: [f64; 4] = std::array::from_fn(|i| e.el[i] + e.damp[i] + tan[i]);
        ds[X] = g[0];
        ds[Y] = g[1];
        ds[GX] = f[0] * self.inv[0];
        ds[GY] = f[1] * self.inv[0];
        ds[4] = s[W1];
        ds[W1] = f[2] * self.inv[1];
        ds[6] = s[W2];
        ds[W2] = f[3] * self.inv[2];
        let p_d = dot(&e.damp, &v);
        ds[WN] = dot(&e.el, &v) + p_d;
        ds[WT] = e.f_t * e.v_t;
        ds[WD] = p_d;
        e
    }

    /// The depth at state `s` and the rate at which it closes (> 0 while separating): along
    /// the line of centres for round bodies, at the damping's point for bodies with corners.
    pub(super) fn opening(&self, s: &State) -> (f64, f64) {
        let q = [s[X], s[Y], s[4], s[6]];
        if !G::CORNERS {
            let d = q[0].hypot(q[1]);
            return (self.geometry.reach() - d, (q[0] * s[GX] + q[1] * s[GY]) / d);
        }
        let Some(fr) = self.geometry.frame(&q) else {
            return (0.0, 0.0);
        };
        let lever = fr.lever_rate_area;
        let g_n = fr.n[0] * s[GX] + fr.n[1] * s[GY];
        (fr.depth, g_n + lever[0] * s[W1] + lever[1] * s[W2])
    }

    pub(super) fn eval_new(&self, m: &Mode, s: &State) -> (State, Eval) {
        let mut ds = [0.0; NS];
        let e = self.eval(m, s, &mut ds);
        (ds, e)
    }

    /// The events that can end a piece of mode `m`.
    pub(super) fn candidates(&self, m: &Mode) -> impl Iterator<Item = Event> {
        let apart = m.apart.then_some(Event::Touch);
        let clip = if m.apart {
            None
        } else if m.clipped {
            Some(Event::ClipOff)
        } else {
            Some(Event::ClipOn)
        };
        let tan = match m.tan {
            Tan::Stick => Some(Event::ToSlip),
            Tan::Slip(_) => Some(Event::ToStick),
            _ => None,
        };
        let separate = (!m.apart).then_some(Event::Separate);
        let springs = (!m.apart && self.geometry.holds_springs()).then_some(Event::Springs);
        [apart, separate, clip, tan, springs].into_iter().flatten()
    }

    /// The value of event `ev`'s function at state `s` in mode `m` (> 0: it fired).
    pub(super) fn event_value(&self, m: &Mode, ev: Event, s: &State) -> f64 {
        if ev == Event::Springs {
            let q = [s[X], s[Y], s[4], s[6]];
            return self.geometry.held_springs_value(&q, &self.held);
        }
        let e = self.eval_new(m, s).1;
        match ev {
            Event::Separate => -e.depth,
            Event::Touch => e.depth,
            Event::ClipOn => -e.f_raw,
            Event::ClipOff => e.f_raw,
            // Where no overlap is resolved (the touch itself) the cone is closed but no spring
            // acts either: the touch's probe has chosen the mode (`mode_after_touch`).
            Event::ToSlip if e.depth <= 0.0 => f64::NEG_INFINITY,
            Event::ToSlip => {
                // Past the cone by a margin of 1e-9 of it: a spring just set on the cone (at a
                // slip -> stick switch) is not taken back by round-off.
                let cap = self.mu * e.f_raw.max(0.0);
                e.trial.abs() - cap - 1e-9 * (e.trial.abs() + cap)
            }
            Event::ToStick => self.to_stick_value(m, s, &e),
            Event::Springs => unreachable!("answered above"),
        }
    }

    /// Slip -> stick: mu dF_n/dt - s dF_trial/dt, positive where sticking would move the
    /// trial force inside the cone: both rates taken by a forward difference along the motion
    /// the contact would have if it stuck now (the spring at its slipping elongation, moving
    /// as in stick), so that a slip the damper reverses ends, and the switch is consistent.
    fn to_stick_value(&self, m: &Mode, s: &State, e: &Eval) -> f64 {
        let Tan::Slip(sg) = m.tan else {
            return f64::NEG_INFINITY;
        };
        if e.depth <= 0.0 {
            return f64::NEG_INFINITY;
        }
        let h = self.fd_step;
        let mut held = *s;
        held[XI] = self.slipping_xi(e);
        let stick = Mode {
            tan: Tan::Stick,
            ..*m
        };
        let (d_stick, now) = self.eval_new(&stick, &held);
        let ahead: State = std::array::from_fn(|i| held[i] + h * d_stick[i]);
        let later = self.eval_new(&stick, &ahead).1;
        let dfn = (later.f_raw - now.f_raw) / h;
        let dtrial = (later.trial - now.trial) / h;
        let value = self.mu * dfn - sg * dtrial;
        // Past its root by a margin of 1e-9 of its terms, so that the spring starts inside.
        value - 1e-9 * (self.mu * dfn.abs() + dtrial.abs())
    }

    /// The spring's elongation that carries the slipping force: -(F_t + c_t v_t) / k_xi.
    pub(super) fn slipping_xi(&self, e: &Eval) -> f64 {
        let (k_xi, _, ct) = self.pair.law.spring(e.depth.max(0.0));
        -(e.f_t + ct * e.v_t) / k_xi
    }

    /// The tangential mode just after a touch at state `s`, where the linear law's dashpot
    /// already pushes: at touch itself no overlap acts yet, so it is probed `dt` of the free
    /// motion in, and ten thousand times further while the bodies' overlap is still below what
    /// their frame resolves (a corner's overlap grows like the square of the time).
    /// The linear law's vertex springs are held from the probe on: at the touch itself the
    /// entering corner lies on the other body's edge, and its spring must be in the piece.
    /// Also the probe's state: the derivative just inside the contact (`touch_derivative`).
    pub(super) fn mode_after_touch(&mut self, m: &Mode, s: &State, dt: f64) -> (Tan, State) {
        let mut probe = *s;
        for k in 0..3 {
            let h = dt * 1e4f64.powi(k);
            for (i, rate) in [(X, GX), (Y, GY), (4, W1), (6, W2)] {
                probe[i] = s[i] + h * s[rate];
            }
            if self
                .geometry
                .frame(&[probe[X], probe[Y], probe[4], probe[6]])
                .is_some()
            {
                break;
            }
        }
        self.held = self
            .geometry
            .held_springs(&[probe[X], probe[Y], probe[4], probe[6]]);
        (self.initial_tan(m, &probe), probe)
    }

    /// The derivative a piece from a touch starts with (its first stage). Under the linear
    /// law the law's just inside the contact, at the touch's `probe` (`mode_after_touch`), with
    /// the positions' rates those of the touch: its dashpot pushes at once, c_n v_n, and a
    /// stuck spring charges at v_t, where at the touch itself (two discs: no overlap, no frame
    /// yet) neither acts; evaluated there, the first stage lacked them and the step lost its
    /// weight b_1 = 35/384 of them (two damped discs: 7 tol in e_N at tol 1e-6, 20 tol at
    /// 1e-10, whatever the largest step). The area and Hertz laws start from no force, and the
    /// step from touch is short (t_c tol^(2/3)); their derivative is the touch's (taken at the
    /// probe, which for a corner lies up to 1e-4 of the contact in, twin triangles under the
    /// area law at mu 1e3 and their exchange came 2.9e-5 apart).
    pub(super) fn touch_derivative(&self, m: &Mode, s: &State, probe: &State) -> State {
        if !matches!(self.pair.law.scene.normal_law, NormalLaw::Linear { .. }) {
            return self.eval_new(m, s).0;
        }
        let mut k = self.eval_new(m, probe).0;
        for (i, rate) in [(X, GX), (Y, GY), (4, W1), (6, W2)] {
            k[i] = s[rate];
        }
        k
    }

    /// The tangential mode when the normal force acts: stick if the spring's trial force is
    /// inside the cone, else slip in its direction.
    pub(super) fn initial_tan(&self, m: &Mode, s: &State) -> Tan {
        if self.mu == 0.0 {
            return Tan::None;
        }
        let e = self
            .eval_new(
                &Mode {
                    tan: Tan::Stick,
                    ..*m
                },
                s,
            )
            .1;
        if e.trial.abs() <= self.mu * e.f_raw.max(0.0) {
            Tan::Stick
        } else {
            Tan::Slip(e.trial.signum())
        }
    }
}
