//! The pair's law on the adaptive path (docs/model.md, 17.5): the derivative of the state in a
//! mode and the forces, the error scales, the tangential mode where a contact starts, and the
//! spring's elongation that carries a slip.

use super::piece::{Eval, Mode, State, Tan, GX, GY, NS, W1, W2, WD, WN, WT, X, XI, Y};
use crate::geometry::pair::{HeldSprings, PairGeometry};
use crate::impact::adaptive::{spring_scale, velocity_scales, LinearSlip};
use crate::law::contact::NormalForce;
use crate::law::pair::dot;
use crate::model::{Initial, NormalLaw, Pair};
use std::f64::consts::PI;

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

impl<'a, G: PairGeometry> PairOde<'a, G> {
    /// The ODE of `pair` meeting through `geometry`, slip -> stick's forward difference taken
    /// over `fd_step` (s).
    pub(super) fn new(pair: &'a Pair, geometry: G, fd_step: f64) -> Self {
        PairOde {
            pair,
            geometry,
            mu: pair.law.scene.mu,
            normal: NormalForce::new(&pair.law),
            inv: [
                1.0 / pair.m_star,
                1.0 / pair.particle.inertia,
                1.0 / pair.i2,
            ],
            fd_step,
            held: Default::default(),
        }
    }

    /// The derivative `ds` of state `s` in mode `m`, and the forces.
    pub(super) fn eval(&self, m: &Mode, s: &State, ds: &mut State) -> Eval {
        self.eval_reading(m, s, ds, true)
    }

    /// [`Self::eval`] at an inner stage of a step, whose depth is read for its sign alone
    /// (whether the stage found the bodies in contact: the stage filters'), and only through
    /// it: bodies with corners that the held overlap does not find in contact are not
    /// measured apart (-inf), only told apart from an overlap the clip finds. The derivative
    /// is [`Self::eval`]'s bit for bit: apart, the law reads no depth. Measuring the gap
    /// there cost two 120-gons a twentieth of their impact.
    pub(super) fn eval_stage(&self, m: &Mode, s: &State, ds: &mut State) -> Eval {
        self.eval_reading(m, s, ds, !G::CORNERS)
    }

    /// [`Self::eval`]; `gap`: bodies the held overlap does not find in contact are measured
    /// apart (their depth minus their gap, else -inf where no overlap is found).
    fn eval_reading(&self, m: &Mode, s: &State, ds: &mut State, gap: bool) -> Eval {
        self.eval_inlined(m, s, ds, gap)
    }

    /// The law's evaluation at `s` in mode `m` without the derivative, the same bits as
    /// [`Self::eval`]'s: an event function reads the forces and the contact alone, and the
    /// derivative's assembly (the forces on the lanes, the works' powers) was a fifth of the
    /// evaluations the switches' searches take.
    pub(super) fn eval_value(&self, m: &Mode, s: &State) -> Eval {
        let mut unread = [0.0; NS];
        self.eval_inlined(m, s, &mut unread, true)
    }

    /// [`Self::eval_reading`]'s body, compiled into each of its callers (so that where the
    /// derivative is not read it is not formed).
    #[inline(always)]
    fn eval_inlined(&self, m: &Mode, s: &State, ds: &mut State, gap: bool) -> Eval {
        #[cfg(feature = "bench-counters")]
        crate::counters::count_pair_law_evaluation();
        let q = [s[X], s[Y], s[4], s[6]];
        let v = [s[GX], s[GY], s[W1], s[W2]];
        let mut e = Eval::default();
        // Round bodies hold nothing: their frame is the held one, and inlined (held
        // through the trait's default it stayed a call, and wrote the whole frame, the linear
        // law's springs included, to be read back: a sixth of two discs' impact).
        let frame = if G::CORNERS {
            self.geometry.frame_held(&q, &self.held)
        } else {
            self.geometry.frame(&q)
        };
        match frame {
            Some(fr) => {
                let normal = self.normal.on_pair(&fr, &v, G::CORNERS);
                e.f_raw = normal.f_el + normal.f_d;
                // Apart, the touch is an event: a force at once (the linear law's dashpot
                // jumps there) in the stages past it would spoil the state located there.
                if !m.clipped && !m.apart {
                    (e.f_el, e.f_d) = (normal.f_el, normal.f_d);
                    (e.el, e.damp) = (normal.el, normal.damp);
                }
                (e.n, e.depth, e.area, e.chord) = (fr.n, fr.depth, fr.area, fr.chord);
                e.lever_t = fr.lever_t;
                e.lever_rate = Some(fr.lever_rate_area);
            }
            None => {
                // Apart: the depth is minus the gap (round bodies: at no cost), the normal the
                // line of centres.
                let d = q[0].hypot(q[1]);
                e.n = [q[0] / d, q[1] / d];
                e.depth = if gap {
                    self.geometry.signed_depth(&q)
                } else {
                    // An overlap's depth as `signed_depth` reads it.
                    let overlap = self.geometry.frame(&q);
                    overlap.map_or(f64::NEG_INFINITY, |fr| fr.depth)
                };
            }
        }
        self.rates(m, s, e, ds)
    }

    /// [`Self::eval`] in flight (mode apart, no tangential law: no force acts) where the
    /// evaluation's contact is not read: the same derivative, bit for bit, without the
    /// geometry (in flight the frame only sets the normal and depth, and the forces it would
    /// give are off). The depth is left unmeasured (-inf: apart): each stage of a flight's
    /// step measured the gap, which places and scans every corner of both bodies.
    pub(super) fn eval_in_flight(&self, m: &Mode, s: &State, ds: &mut State) -> Eval {
        debug_assert!(m.apart && matches!(m.tan, Tan::None | Tan::Free));
        let d = s[X].hypot(s[Y]);
        let e = Eval {
            n: [s[X] / d, s[Y] / d],
            depth: f64::NEG_INFINITY,
            ..Eval::default()
        };
        self.rates(m, s, e, ds)
    }

    /// [`Self::eval`]'s tangential force and the derivative, from its `contact` at `s` (the
    /// frame and the normal force, which read the positions and velocities alone) in a mode of
    /// the same clip and contact as `m` (its tangential law and spring may differ).
    #[inline(always)]
    pub(super) fn rates(&self, m: &Mode, s: &State, contact: Eval, ds: &mut State) -> Eval {
        let law = &self.pair.law;
        let g = [s[GX], s[GY]];
        let v = [s[GX], s[GY], s[W1], s[W2]];
        let at = |l: [f64; 2]| l[0] * s[W1] + l[1] * s[W2];
        let mut e = contact;
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

    /// [`Self::opening`] at state `s` from the law's evaluation `e` at its positions (its
    /// velocities may differ), where that found the contact's frame: the frame the force acts
    /// in (the held overlap), read rather than found again.
    pub(super) fn opening_of(&self, e: &Eval, s: &State) -> Option<(f64, f64)> {
        let lever = e.lever_rate?;
        let g_n = e.n[0] * s[GX] + e.n[1] * s[GY];
        Some((e.depth, g_n + lever[0] * s[W1] + lever[1] * s[W2]))
    }

    /// Whether a step that ends at state `end` has crossed the parting (no overlap is left at
    /// its end). The force is not smooth there under any law: the area and Hertz laws have a
    /// root singularity, the linear law's spring a kink (its slope k up to the parting, nothing
    /// beyond; damped, its force reaches zero at the clip first, undamped at the parting). The
    /// dense output's error estimate, like the embedded one, understates across that point
    /// (`singular_factor`), so the state at a switch inside such a step is the step redone to
    /// it: a slip that ended as the cone closed just before the parting, read off the dense
    /// output, put a disc on a 12-gon and a disc on a 120-gon (elastic, mu 0.25 and 1.35) 4.7
    /// and 4.1 tol off at tol 1e-4 and 1e-5 with err_est 0.5 and 1.4 tol; two discs under the
    /// linear law, the parting itself read off it, erred up to 4.45 tol, err_est covering 79.9 %
    /// of them at tol 1e-5 (`benchmarks/pair_accuracy.py --two-discs --seeds 4`).
    pub(super) fn ends_apart(&self, end: &State) -> bool {
        self.opening(end).0 <= 0.0
    }

    pub(super) fn eval_new(&self, m: &Mode, s: &State) -> (State, Eval) {
        let mut ds = [0.0; NS];
        let e = self.eval(m, s, &mut ds);
        (ds, e)
    }

    /// The linear tangential spring a slip's stage bound reads
    /// ([`crate::impact::adaptive::TangentialStages::stays_slipping`]); `None` for Mindlin's,
    /// whose stiffness and damping change with the depth, and for a history that shrinks as
    /// the contact unloads.
    pub(super) fn linear_slip(&self) -> Option<LinearSlip> {
        let law = &self.pair.law;
        if law.mindlin || law.history.rescales() {
            return None;
        }
        let (k_t, _, c_t) = law.spring(0.0);
        Some(LinearSlip {
            mu: self.mu,
            k_t,
            c_t,
        })
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
            // The derivative alone, as a stage reads it (the same bits): at the touch the
            // held overlap has no area yet, and measuring the gap there cost two 120-gons
            // 48 000 instructions, a fiftieth of their impact.
            let mut k = [0.0; NS];
            self.eval_stage(m, s, &mut k);
            return k;
        }
        let mut k = self.eval_new(m, probe).0;
        for (i, rate) in [(X, GX), (Y, GY), (4, W1), (6, W2)] {
            k[i] = s[rate];
        }
        k
    }

    /// [`Self::initial_tan`] from the law's evaluation `stuck` at the state in its mode, stuck
    /// (where `mu` > 0): the evaluation read where it is already known.
    pub(super) fn tan_of_stuck(&self, stuck: &Eval) -> Tan {
        if stuck.trial.abs() <= self.mu * stuck.f_raw.max(0.0) {
            Tan::Stick
        } else {
            Tan::Slip(stuck.trial.signum())
        }
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
        self.tan_of_stuck(&e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::pair_shapes::ShapePair;
    use crate::geometry::Shape;
    use crate::model::{Model, Partner, Scene};

    /// Calls `check` with the ODE of a square on a heptagon under `law` (mu 0.5) and 200
    /// random states each: centres 0.8 to 1.2 times the reach apart (overlapping to well
    /// clear), any orientations, velocities, spins and spring.
    fn random_states(law: NormalLaw, mut check: impl FnMut(&PairOde<ShapePair>, &State)) {
        let mut seeded = crate::numerics::seeded::Seeded(11);
        let mut rng = move || seeded.uniform();
        let scene = Scene {
            shape: Shape::regular_polygon(0.01, 4).unwrap(),
            partner: Some(Partner::of(Shape::regular_polygon(0.013, 7).unwrap())),
            normal_law: law,
            mu: 0.5,
            ..Scene::default()
        };
        let pair = Pair::new(Model::new(&scene).unwrap()).unwrap();
        let mut geometry = ShapePair::new(&scene.shape, &pair.partner_shape).unwrap();
        geometry.springs = matches!(law, NormalLaw::Linear { .. });
        let ode = PairOde::new(&pair, geometry, 1e-9);
        for _ in 0..200 {
            let (d, ang) = (0.023 * (0.8 + 0.4 * rng()), 6.3 * rng());
            let mut s: State = std::array::from_fn(|_| 2.0 * rng() - 1.0);
            (s[X], s[Y], s[4], s[6]) = (d * ang.cos(), d * ang.sin(), 7.0 * rng(), 7.0 * rng());
            check(&ode, &s);
        }
    }

    const LAWS: [NormalLaw; 2] = [NormalLaw::Area, NormalLaw::Linear { kn: 1e5, cn: 2.0 }];

    /// In flight the derivative does not read the contact: [`PairOde::eval_in_flight`] gives
    /// the full evaluation's derivative, bit for bit, for two polygons apart, touching and
    /// overlapping (a step's stages past a touch), spinning, with a spring left stretched,
    /// on both laws of polygons.
    #[test]
    fn a_flight_derivative_is_the_full_evaluations() {
        let (mut compared, mut overlapping) = (0, 0);
        for law in LAWS {
            for tan in [Tan::None, Tan::Free] {
                let m = Mode {
                    clipped: false,
                    apart: true,
                    tan,
                };
                random_states(law, |ode, s| {
                    let (mut full, mut flight) = ([0.0; NS], [0.0; NS]);
                    ode.eval(&m, s, &mut full);
                    ode.eval_in_flight(&m, s, &mut flight);
                    assert_eq!(full, flight, "state {s:?}");
                    compared += 1;
                    let q = [s[X], s[Y], s[4], s[6]];
                    overlapping += usize::from(ode.geometry.frame(&q).is_some());
                });
            }
        }
        assert_eq!(compared, 800);
        assert!(
            overlapping > 100 && overlapping < 700,
            "{overlapping} of 800 overlapping"
        );
    }

    /// At a step's inner stage the gap is not measured: [`PairOde::eval_stage`] gives the full
    /// evaluation's derivative bit for bit, and its depth (where the bodies overlap) or a
    /// depth of the same sign, in every mode in contact.
    #[test]
    fn a_stage_reads_the_full_evaluations_derivative_and_the_sign_of_its_depth() {
        let (mut compared, mut apart) = (0, 0);
        let tans = [
            Tan::None,
            Tan::Free,
            Tan::Stick,
            Tan::Slip(1.0),
            Tan::Slip(-1.0),
        ];
        for law in LAWS {
            for (tan, clipped) in tans.into_iter().flat_map(|t| [(t, false), (t, true)]) {
                let m = Mode {
                    clipped,
                    apart: false,
                    tan,
                };
                random_states(law, |ode, s| {
                    let (mut full, mut stage) = ([0.0; NS], [0.0; NS]);
                    let e_full = ode.eval(&m, s, &mut full);
                    let e_stage = ode.eval_stage(&m, s, &mut stage);
                    assert_eq!(full, stage, "state {s:?}");
                    if e_full.depth > 0.0 {
                        assert_eq!(e_stage.depth, e_full.depth, "state {s:?}");
                    } else {
                        assert!(e_stage.depth <= 0.0, "state {s:?}");
                        apart += 1;
                    }
                    compared += 1;
                });
            }
        }
        assert_eq!(compared, 4000);
        assert!(apart > 500 && apart < 3500, "{apart} of 4000 apart");
    }
}
