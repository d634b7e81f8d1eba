//! The switches that end a piece of a pair's impact (docs/model.md, 17.5 and 17.8): which can end
//! a mode, and their event functions (continuous, <= 0 while the piece's mode holds).

use super::law::PairOde;
use super::piece::{Eval, Event, Mode, State, Tan, GX, GY, NS, W1, W2, X, XI, Y};
use crate::geometry::pair::PairGeometry;
use crate::geometry::Overlap;
use crate::impact::adaptive::switch_precision;
use crate::model::NormalLaw;

impl<G: PairGeometry> PairOde<'_, G> {
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

    /// To what fraction of its step switch `ev` is located: the plate's rule
    /// ([`switch_precision`]) at the run's local tolerance. The force jumps where the linear
    /// law's dashpot starts to push (the touch) and where the held springs switch (a corner's
    /// spring enters or leaves; under the area law a crossing passes a corner, where the
    /// potential's force jumps, docs/model.md 17.8).
    pub(super) fn switch_precision(&self, ev: Event) -> f64 {
        let linear = matches!(self.pair.law.scene.normal_law, NormalLaw::Linear { .. });
        let jumps = ev == Event::Springs || (linear && ev == Event::Touch);
        switch_precision(self.pair.particle.scene.local_tol(), jumps)
    }

    /// The value of event `ev`'s function at state `s` in mode `m` (> 0: it fired).
    pub(super) fn event_value(&self, m: &Mode, ev: Event, s: &State) -> f64 {
        self.event_value_with(m, ev, s, || self.eval_value(m, s))
    }

    /// [`Self::event_value`], the law's evaluation at `s` in mode `m` given by `eval` (called
    /// only where the event needs it: a step's candidates share one evaluation per sample).
    pub(super) fn event_value_with(
        &self,
        m: &Mode,
        ev: Event,
        s: &State,
        eval: impl FnOnce() -> Eval,
    ) -> f64 {
        self.state_event_value(ev, s)
            .unwrap_or_else(|| self.event_value_of(m, ev, s, &eval()))
    }

    /// The value of event `ev`'s function at `s` where it reads the positions alone: the
    /// held springs', and round bodies' separation and touch (their depth is their gap's,
    /// r1 + r2 - d, in contact and apart alike, the law's own), so that their searches need
    /// no evaluation of the law; `None` for the others.
    pub(super) fn state_event_value(&self, ev: Event, s: &State) -> Option<f64> {
        let q = [s[X], s[Y], s[4], s[6]];
        if ev == Event::Springs {
            return Some(self.geometry.held_springs_value(&q, &self.held));
        }
        if !G::CORNERS && matches!(ev, Event::Separate | Event::Touch) {
            let depth = self.geometry.signed_depth(&q);
            return Some(if ev == Event::Separate { -depth } else { depth });
        }
        None
    }

    /// [`Self::event_value`] given the law's evaluation `e` at `s` in mode `m`.
    pub(super) fn event_value_of(&self, m: &Mode, ev: Event, s: &State, e: &Eval) -> f64 {
        match ev {
            Event::Separate => -e.depth,
            Event::Touch => e.depth,
            Event::ClipOn => -e.f_raw,
            Event::ClipOff => e.f_raw,
            Event::ToSlip => self.to_slip_value(e),
            Event::ToStick => self.to_stick_value(m, s, e),
            Event::Springs => {
                let q = [s[X], s[Y], s[4], s[6]];
                self.geometry.held_springs_value(&q, &self.held)
            }
        }
    }

    /// Stick -> slip: |F_trial| - mu F_n, at evaluation `e`.
    pub(super) fn to_slip_value(&self, e: &Eval) -> f64 {
        // Where no overlap is resolved (the touch itself) the cone is closed but no spring
        // acts either: the touch's probe has chosen the mode (`mode_after_touch`).
        if e.depth <= 0.0 {
            return f64::NEG_INFINITY;
        }
        // Past the cone by a margin of 1e-9 of it: a spring just set on the cone (at a
        // slip -> stick switch) is not taken back by round-off.
        let cap = self.mu * e.f_raw.max(0.0);
        e.trial.abs() - cap - 1e-9 * (e.trial.abs() + cap)
    }

    /// Slip -> stick: mu dF_n/dt - s dF_trial/dt, positive where sticking would move the
    /// trial force inside the cone: both rates along the motion the contact would have if it
    /// stuck now (the spring at its slipping elongation, moving as in stick), so that a slip
    /// the damper reverses ends, and the switch is consistent ([`Self::stick_rates`]).
    fn to_stick_value(&self, m: &Mode, s: &State, e: &Eval) -> f64 {
        let Tan::Slip(sg) = m.tan else {
            return f64::NEG_INFINITY;
        };
        if e.depth <= 0.0 {
            return f64::NEG_INFINITY;
        }
        let (dfn, dtrial) = self.stick_rates(m, s, e);
        let value = self.mu * dfn - sg * dtrial;
        // Past its root by a margin of 1e-9 of its terms, so that the spring starts inside.
        value - 1e-9 * (self.mu * dfn.abs() + dtrial.abs())
    }

    /// (dF_n/dt, dF_trial/dt) at state `s` slipping in mode `m` with evaluation `e` there,
    /// along the motion the contact would have if it stuck now: in closed form on a lens
    /// ([`Self::lens_stick_rates`]), by a forward difference elsewhere.
    pub(super) fn stick_rates(&self, m: &Mode, s: &State, e: &Eval) -> (f64, f64) {
        let mut held = *s;
        held[XI] = self.slipping_xi(e);
        let stick = Mode {
            tan: Tan::Stick,
            ..*m
        };
        // Held differs from `s` in the spring alone: the contact `e` found there is its own.
        let mut d_stick = [0.0; NS];
        let now = self.rates(&stick, &held, *e, &mut d_stick);
        if let Some(rates) = self.lens_stick_rates(&held, &d_stick, &now) {
            return rates;
        }
        let h = self.fd_step;
        let ahead: State = std::array::from_fn(|i| held[i] + h * d_stick[i]);
        let later = self.eval_value(&stick, &ahead);
        ((later.f_raw - now.f_raw) / h, (later.trial - now.trial) / h)
    }

    /// [`Self::stick_rates`] in closed form on two discs' lens under the area or linear law
    /// with a spring of constant stiffness and damping, from the state `s`, its derivative `d`
    /// and the evaluation `e` there: one evaluation of the law fewer than the difference
    /// (a tenth of two discs' impact). With d the centres' distance, n = q / d and
    /// t = (n_y, -n_x), dn/dt = g_t t / d and dt/dt = -g_t n / d, so that g_n = n . g moves at
    /// a . n + g_t^2 / d and g_t at a . t - g_t g_n / d; the lens's chord and lever follow d,
    /// which moves at g_n (`PairGeometry::lens_rates`); the normal force's rate is the law's
    /// own ([`NormalForce::rate_on_area`], [`NormalForce::rate_on_disc`]: the lens as a
    /// half-plane overlap whose chord sinks at -g_n), and F_trial = -k_t xi - c_t v_t with
    /// v_t = g_t + L_1 omega_1 + L_2 omega_2. `None` elsewhere.
    fn lens_stick_rates(&self, s: &State, d: &State, e: &Eval) -> Option<(f64, f64)> {
        let law = &self.pair.law;
        if law.mindlin {
            return None;
        }
        let dist = (s[X] * s[X] + s[Y] * s[Y]).sqrt();
        let [l1, l2] = e.lever_t;
        let (chord_rate, arm_rate) = self.geometry.lens_rates(dist, e.chord, e.area, l1)?;
        let (n, g, a) = (e.n, [s[GX], s[GY]], [d[GX], d[GY]]);
        let t = [n[1], -n[0]];
        let (g_n, g_t) = (n[0] * g[0] + n[1] * g[1], t[0] * g[0] + t[1] * g[1]);
        let dg_n = n[0] * a[0] + n[1] * a[1] + g_t * g_t / dist;
        let dg_t = t[0] * a[0] + t[1] * a[1] - g_t * g_n / dist;
        let lens = Overlap {
            area: e.area,
            chord: e.chord,
            depth: e.depth,
            ..Overlap::default()
        };
        let (v, acc) = ([g_t, g_n, 0.0], [dg_t, dg_n, 0.0]);
        let dfn = match law.scene.normal_law {
            NormalLaw::Area => self
                .normal
                .rate_on_area(&lens, (chord_rate * g_n, 0.0), &v, &acc),
            NormalLaw::Linear { .. } => self.normal.rate_on_disc(&lens, dist, &v, &acc),
            NormalLaw::Hertz { .. } => None,
        }?;
        let dv_t =
            dg_t + g_n * (arm_rate * s[W1] + (1.0 - arm_rate) * s[W2]) + l1 * d[W1] + l2 * d[W2];
        let (k_xi, _, c_t) = law.spring(e.depth.max(0.0));
        Some((dfn, -k_xi * d[XI] - c_t * dv_t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::pair::DiscPair;
    use crate::geometry::Shape;
    use crate::model::{Model, Pair, Partner, Scene};

    /// (dF_n/dt, dF_trial/dt) at `s` slipping in mode `m` by central differences of step `h`
    /// along the motion the contact would have if it stuck now (the closed form's meaning).
    fn central_rates(ode: &PairOde<DiscPair>, m: &Mode, s: &State, h: f64) -> (f64, f64) {
        let e = ode.eval_new(m, s).1;
        let mut held = *s;
        held[XI] = ode.slipping_xi(&e);
        let stick = Mode {
            tan: Tan::Stick,
            ..*m
        };
        let d = ode.eval_new(&stick, &held).0;
        let at = |k: f64| {
            let moved: State = std::array::from_fn(|i| held[i] + k * h * d[i]);
            ode.eval_new(&stick, &moved).1
        };
        let (ahead, behind) = (at(1.0), at(-1.0));
        (
            (ahead.f_raw - behind.f_raw) / (2.0 * h),
            (ahead.trial - behind.trial) / (2.0 * h),
        )
    }

    /// The slip -> stick rates in closed form on two discs' lens equal their central
    /// differences along the stick motion: equal and unequal discs (the partner half to 2.3
    /// times the particle), the area and the linear law, damped, 300 random states each,
    /// from grazing (1e-5 of the smaller radius) to deep (0.3 of it) overlaps, any direction
    /// of the line of centres, velocities and spins, both slip directions, clipped or not.
    /// Central differences err like h^2 and, at finer steps, by round-off: the closed form
    /// must lie within twice the truncation error that halving the step reveals, or 1e-8 of
    /// the value. A wrong term (the chord's rate, the lever's, the normal's turn) fails it.
    #[test]
    fn closed_form_lens_rates_match_central_differences() {
        let mut seeded = crate::numerics::seeded::Seeded(7);
        let mut rng = move || seeded.uniform();
        let laws = [NormalLaw::Area, NormalLaw::Linear { kn: 5e6, cn: 8.0 }];
        let mut compared = 0;
        for law in laws {
            for r2 in [0.01, 0.023, 0.005] {
                let scene = Scene {
                    shape: Shape::Disc { r: 0.01 },
                    partner: Some(Partner::of(Shape::Disc { r: r2 })),
                    normal_law: law,
                    gamma: 0.33,
                    gamma_t: 0.5,
                    mu: 0.5,
                    ..Scene::default()
                };
                let pair = Pair::new(Model::new(&scene).unwrap()).unwrap();
                let geometry = DiscPair {
                    r1: 0.01,
                    r2,
                    linear: matches!(law, NormalLaw::Linear { .. }),
                };
                let ode = PairOde::new(&pair, geometry, 1e-9);
                for _ in 0..300 {
                    let depth = 0.01f64.min(r2) * 10f64.powf(-5.0 + 4.5 * rng());
                    let (dist, ang) = (0.01 + r2 - depth, 6.3 * rng());
                    let mut s: State = [0.0; NS];
                    (s[X], s[Y], s[4], s[6]) = (dist * ang.cos(), dist * ang.sin(), 0.0, 0.0);
                    // The velocity at least a fifth along the line of centres, so that the
                    // differences' steps move the depth measurably (their rounding, below).
                    let (g, turn) = (0.01 + 0.1 * rng(), 2.7 * rng() - 1.35);
                    let (c, s_) = ((ang + turn).cos(), (ang + turn).sin());
                    (s[GX], s[GY]) = if rng() < 0.5 {
                        (g * c, g * s_)
                    } else {
                        (-g * c, -g * s_)
                    };
                    (s[W1], s[W2]) = (40.0 * rng() - 20.0, 40.0 * rng() - 20.0);
                    let m = Mode {
                        clipped: rng() < 0.2,
                        apart: false,
                        tan: Tan::Slip(if rng() < 0.5 { 1.0 } else { -1.0 }),
                    };
                    let e = ode.eval_new(&m, &s).1;
                    let closed = ode.stick_rates(&m, &s, &e);
                    let speed = s[GX].hypot(s[GY]) + 0.03 * (s[W1].abs() + s[W2].abs());
                    let h = 1e-2 * depth / speed;
                    let (coarse, fine) = (
                        central_rates(&ode, &m, &s, h),
                        central_rates(&ode, &m, &s, 0.5 * h),
                    );
                    // The distance carries a rounding of eps |q|, which the difference
                    // divides by the distance h |g_n| it moves it.
                    let g_n = (s[X] * s[GX] + s[Y] * s[GY]) / dist;
                    let noise = 8.0 * f64::EPSILON * dist / (h * g_n.abs());
                    for (a, c, f) in [(closed.0, coarse.0, fine.0), (closed.1, coarse.1, fine.1)] {
                        let bound = 2.0 * 4.0 / 3.0 * (c - f).abs() + (1e-8 + noise) * a.abs();
                        assert!(
                            (a - f).abs() <= bound,
                            "{law:?} r2 {r2} depth {depth:e} {m:?} {closed:?}: {a:e} vs {f:e} ({c:e} at 2h)"
                        );
                    }
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 1800);
    }
}
