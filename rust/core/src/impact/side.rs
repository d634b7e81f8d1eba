//! What the one fixed-step loop (`fixed.rs`) asks of the body the particle meets: the plate (a
//! partner of infinite mass and a half-plane shape, [`PlateSide`]) or a free partner
//! ([`PairSide`], the pair in its centre-of-mass frame). Each answers a few small questions on
//! the four lanes (its forces, its depth and gap, when the bodies can no longer touch, how
//! the record closes) and the loop asks nothing else; monomorphised per side and geometry,
//! the disc on the plate compiles to the loop it had on its own.

use super::flight::Approach;
use super::record::{separation_normal, Bodies, Ending, Record, Trace};
use crate::cancel::POLL_STEPS;
use crate::geometry::pair::PairGeometry;
use crate::integrate::events::{self, BranchStart, EventControl};
use crate::integrate::{LaneForces, Lanes, Stepper};
use crate::law::pair::{PairContact, PairForces};
use crate::law::{Contact, Dof, Forces, PlateGeometry, TangentialSpring};
use crate::model::{Initial, Model, NormalLaw, Pair};

/// The body the particle meets, as the fixed-step loop sees it.
pub(crate) trait Side {
    /// What one evaluation reports besides the forces on the lanes.
    type Out: Copy + Default;
    /// Lane forces and the report at position `q` and velocity `v`; advances the tangential
    /// spring by `dt`.
    fn evaluate(&mut self, q: &Lanes, v: &Lanes, dt: f64) -> (Lanes, Self::Out);
    /// 1 / mass of each lane (0 for a lane that does not move).
    fn inv_mass(&self) -> Lanes;
    /// Kinetic energy at lane velocities `v`.
    fn kinetic_energy(&self, v: &Lanes) -> f64;
    /// Powers (elastic, damping, tangential) of an evaluation's forces at (`q`, `v`).
    fn powers(f: &Self::Out, q: &Lanes, v: &Lanes) -> (f64, f64, f64);
    /// Whether the (clipped) normal force pushes.
    fn pushing(f: &Self::Out) -> bool;
    /// The overlap's area (`None` when apart).
    fn area(f: &Self::Out) -> Option<f64>;
    /// Signed depth at `q` (negative when apart), `f` the evaluation at the end of the step
    /// that reached `q`.
    fn depth(&self, q: &Lanes, f: &Self::Out) -> f64;
    /// The gap (minus the signed depth) after a free flight of `t` from (`q`, `v`).
    fn gap_after(&self, q: &Lanes, v: &Lanes, t: f64) -> f64;
    /// How the free flight from (`q`, `v`) approaches (see [`Approach`]).
    fn approach(&self, q: &Lanes, v: &Lanes) -> Approach;
    /// Apart at (`q`, `v`): no part of the bodies can meet again, seen without a flight.
    fn cleared(&self, q: &Lanes, v: &Lanes) -> bool;
    /// The contact's normal at `q` (the line of centres; the plate's +y).
    fn normal(&self, q: &Lanes) -> [f64; 2];
    /// The tangential spring.
    fn spring(&self) -> &TangentialSpring;
    /// The circumradius that scales the step control's tolerance.
    fn radius(&self) -> f64;
    /// Steps between two polls of the cancel token (a power of two, see
    /// [`Cancel::poll_every`]).
    ///
    /// [`Cancel::poll_every`]: crate::cancel::Cancel::poll_every
    fn poll_stride(&self) -> u64;
    /// Appends a step to the trace.
    fn push(tr: &mut Trace, t: f64, qv: (&Lanes, &Lanes), f: &Self::Out, depth: f64, xi: f64);
    /// Completes `rec` from the final lanes (`q`, `v`) and the normal where the last contact
    /// ended, `n_sep`.
    fn close(&self, rec: &mut Record, init: &Initial, qv: (Lanes, Lanes), n_sep: [f64; 2]);
    /// Whether fixed steps land on the contact's events ([`crate::integrate::events`]): a
    /// polygon on the plate without friction, or under the linear law.
    fn wants_events(&self) -> bool {
        false
    }
    /// Every corner crossing is an event (the linear law's dashpots on a polygon).
    fn every_crossing(&self) -> bool {
        false
    }
    /// The branch the contact enters at (`q`, `v`) with acceleration `a` (only where
    /// [`Side::wants_events`]).
    fn branch_start(&self, _q: &Lanes, _v: &Lanes, _a: &Dof, _dt: f64) -> BranchStart {
        unreachable!("only a side with events starts branches")
    }
    /// One step under the event control (only where [`Side::wants_events`]): the report,
    /// the step's length and the branch restarted at its end, if it ended on an event.
    fn event_step<S: Stepper>(
        &mut self,
        _control: &mut EventControl,
        _stepper: &mut S,
    ) -> (Self::Out, f64, Option<BranchStart>) {
        unreachable!("only a side with events steps on them")
    }
}

/// A side's contact law as the steppers see it (one evaluation per step).
pub(crate) struct OnSide<'s, C> {
    /// The side.
    pub side: &'s mut C,
    /// The step (s).
    pub dt: f64,
}

impl<C: Side> LaneForces for OnSide<'_, C> {
    type Out = C::Out;

    #[inline(always)]
    fn forces(self, q: &Lanes, v: &Lanes) -> (Lanes, C::Out) {
        self.side.evaluate(q, v, self.dt)
    }
}

/// The plate: the particle's contact with the half-plane.
pub(crate) struct PlateSide<'a, G> {
    model: &'a Model,
    contact: Contact<'a, G>,
    inv_mass: Dof,
}

impl<'a, G: PlateGeometry> PlateSide<'a, G> {
    pub(crate) fn new(model: &'a Model, geometry: G) -> Self {
        PlateSide {
            model,
            contact: Contact::new(model, geometry),
            inv_mass: [1.0 / model.mass, 1.0 / model.mass, 1.0 / model.inertia],
        }
    }

    /// The linear law on a polygon (Gear-5 only): one dashpot per submerged corner, whose force
    /// jumps as the corner crosses the plate, so every crossing is an event, with friction too
    /// (a step straddling a jump errs to first order: energy residuals up to 2.7e-5 with plain
    /// steps, 1.5e-6 located, quick matrix and `examples/linear_events.rs`). Verlet is
    /// refused for this law on a polygon (`check_laws`): its audit, the trapezoid of the
    /// powers, closes only where the force is continuous and the step fixed (the boundary term
    /// h^2 |F|^2 / 8m telescopes away), so every located jump would leave an O(h^2) residual
    /// (up to 7e-5 at the default step on a triangle), and plain steps miss the jumps.
    fn linear(&self) -> bool {
        G::EVENTS && matches!(self.model.scene.normal_law, NormalLaw::Linear { .. })
    }
}

impl<G: PlateGeometry> Side for PlateSide<'_, G> {
    type Out = Forces;

    #[inline(always)]
    fn evaluate(&mut self, q: &Lanes, v: &Lanes, dt: f64) -> (Lanes, Forces) {
        let f = self
            .contact
            .evaluate(&[q[0], q[1], q[2]], &[v[0], v[1], v[2]], dt);
        ([f.fx, f.fy, f.torque, 0.0], f)
    }

    /// Built at each step, its fourth lane a constant 0 (stored in the loop instead, the
    /// disc's Verlet step took 13 % longer: 25.5 against 22.5 ns).
    #[inline(always)]
    fn inv_mass(&self) -> Lanes {
        let m = &self.inv_mass;
        [m[0], m[1], m[2], 0.0]
    }

    fn kinetic_energy(&self, v: &Lanes) -> f64 {
        self.model.kinetic_energy(&[v[0], v[1], v[2]])
    }

    #[inline(always)]
    fn powers(f: &Forces, q: &Lanes, v: &Lanes) -> (f64, f64, f64) {
        f.powers(q[1], &[v[0], v[1], v[2]])
    }

    #[inline(always)]
    fn pushing(f: &Forces) -> bool {
        f.f_el + f.f_d > 0.0
    }

    #[inline(always)]
    fn area(f: &Forces) -> Option<f64> {
        f.overlap.map(|o| o.area)
    }

    #[inline(always)]
    fn depth(&self, q: &Lanes, _f: &Forces) -> f64 {
        self.contact.geometry.depth(q[1], q[2])
    }

    fn gap_after(&self, q: &Lanes, v: &Lanes, t: f64) -> f64 {
        -self
            .contact
            .geometry
            .depth(q[1] + v[1] * t, q[2] + v[2] * t)
    }

    fn approach(&self, q: &Lanes, v: &Lanes) -> Approach {
        let r = self.model.r;
        Approach::to_plate(q[1], &[v[0], v[1], v[2]], (r, r))
    }

    /// Its circumscribed circle is clear and moving away, or every point of it moves away
    /// (v_y > r |omega|: in free flight the gap then only grows; without this a face-first
    /// polygon at a glancing angle would time out while drifting up to clear r).
    #[inline(always)]
    fn cleared(&self, q: &Lanes, v: &Lanes) -> bool {
        let r = self.model.r;
        v[1] > 0.0 && (q[1] >= r || v[1] > r * v[2].abs())
    }

    #[inline(always)]
    fn normal(&self, _q: &Lanes) -> [f64; 2] {
        [0.0, 1.0]
    }

    fn spring(&self) -> &TangentialSpring {
        &self.contact.spring
    }

    fn radius(&self) -> f64 {
        self.model.r
    }

    #[inline(always)]
    fn poll_stride(&self) -> u64 {
        POLL_STEPS
    }

    fn push(tr: &mut Trace, t: f64, (q, v): (&Lanes, &Lanes), f: &Forces, depth: f64, xi: f64) {
        tr.push(t, &[q[0], q[1], q[2]], &[v[0], v[1], v[2]], f, depth, xi);
    }

    fn close(&self, rec: &mut Record, init: &Initial, (q, v): (Lanes, Lanes), _n_sep: [f64; 2]) {
        let end = Ending::on_plate(&[q[0], q[1], q[2]], &[v[0], v[1], v[2]]);
        rec.close(&Bodies::Plate(self.model), init, &end);
    }

    /// Polygons without friction: steps located on events and refined where the force
    /// changes within a step (see `events`), only without friction: with it the stick/slip
    /// switches bound the fixed-step integrators to first order anyway (docs/model.md), and
    /// the restarts and refined steps measured no better e_n while they disturbed the energy
    /// balance of frictional spinning polygons (its residual rose from ~1e-7 to ~2e-6 at the
    /// default step), so those keep the plain steps. The linear law's polygons: always.
    fn wants_events(&self) -> bool {
        G::EVENTS && (self.model.scene.mu == 0.0 || self.linear())
    }

    fn every_crossing(&self) -> bool {
        self.linear()
    }

    fn branch_start(&self, q: &Lanes, v: &Lanes, a: &Dof, dt: f64) -> BranchStart {
        let (q, v) = ([q[0], q[1], q[2]], [v[0], v[1], v[2]]);
        events::branch_start(&self.contact, &q, &v, a, &self.inv_mass, dt)
    }

    fn event_step<S: Stepper>(
        &mut self,
        control: &mut EventControl,
        stepper: &mut S,
    ) -> (Forces, f64, Option<BranchStart>) {
        let taken = control.step(stepper, &mut self.contact, &self.inv_mass);
        (taken.forces, taken.h, taken.restart)
    }
}

/// Steps between two polls of the cancel token for a pair whose steps evaluate its law about
/// `per_step` times: the plate's [`POLL_STEPS`] over the cost of an evaluation relative to the
/// plate's, about linear in the two bodies' corners (their intersection), so that a pair
/// polls about as often in time as the plate does (about every millisecond).
pub(crate) fn poll_stride(pair: &Pair, per_step: u64) -> u64 {
    let corners = pair.particle.scene.shape.vertices().len() + pair.partner_shape.vertices().len();
    let work = (1 + corners as u64 / 4) * per_step;
    (POLL_STEPS / work.next_power_of_two()).max(1)
}

/// A free partner: the pair's contact on the relative motion and both rotations.
pub(crate) struct PairSide<'a, G> {
    pair: &'a Pair,
    contact: PairContact<'a, G>,
    /// The pair's angular momentum, restored on the final state (`Pair::restoring_turn`).
    l0: f64,
    /// The centres' distance at first touch.
    y0: f64,
    /// Steps between two polls of the cancel token (`poll_stride`).
    poll_stride: u64,
    /// 1 / mass of each lane: m*, m*, I1, I2.
    inv_mass: Lanes,
}

impl<'a, G: PairGeometry> PairSide<'a, G> {
    /// The pair at first touch, lanes (`q0`, `v0`).
    pub(crate) fn new(pair: &'a Pair, geometry: G, (q0, v0): (&Lanes, &Lanes)) -> Self {
        PairSide {
            pair,
            contact: PairContact::new(&pair.law, geometry),
            l0: pair.angular_momentum(q0, v0),
            y0: q0[1],
            poll_stride: poll_stride(pair, 1),
            inv_mass: [
                1.0 / pair.m_star,
                1.0 / pair.m_star,
                1.0 / pair.particle.inertia,
                1.0 / pair.i2,
            ],
        }
    }

    fn radii(&self) -> [f64; 2] {
        [self.pair.particle.r, self.pair.r2]
    }
}

impl<G: PairGeometry> Side for PairSide<'_, G> {
    type Out = PairForces;

    #[inline(always)]
    fn evaluate(&mut self, q: &Lanes, v: &Lanes, dt: f64) -> (Lanes, PairForces) {
        self.contact.evaluate(q, v, dt)
    }

    #[inline(always)]
    fn inv_mass(&self) -> Lanes {
        self.inv_mass
    }

    fn kinetic_energy(&self, v: &Lanes) -> f64 {
        self.pair.kinetic_energy(v)
    }

    #[inline(always)]
    fn powers(f: &PairForces, _q: &Lanes, v: &Lanes) -> (f64, f64, f64) {
        f.powers(v)
    }

    #[inline(always)]
    fn pushing(f: &PairForces) -> bool {
        f.f_el + f.f_d > 0.0
    }

    #[inline(always)]
    fn area(f: &PairForces) -> Option<f64> {
        Some(f.area)
    }

    /// Bodies with corners in contact: the evaluation's, to spare a second intersection.
    #[inline(always)]
    fn depth(&self, q: &Lanes, f: &PairForces) -> f64 {
        if G::CORNERS && f.area > 0.0 {
            f.depth
        } else {
            self.contact.geometry.signed_depth(q)
        }
    }

    fn gap_after(&self, q: &Lanes, v: &Lanes, t: f64) -> f64 {
        let at: Lanes = std::array::from_fn(|i| q[i] + v[i] * t);
        -self.contact.geometry.signed_depth(&at)
    }

    fn approach(&self, q: &Lanes, v: &Lanes) -> Approach {
        Approach::of_pair(q, v, self.radii())
    }

    /// Receding, round bodies cannot touch again once apart, bodies with corners once their
    /// circumscribed circles are apart too.
    #[inline(always)]
    fn cleared(&self, q: &Lanes, v: &Lanes) -> bool {
        let receding = q[0] * v[0] + q[1] * v[1] > 0.0;
        let reach = self.pair.particle.r + self.pair.r2;
        receding && (!G::CORNERS || q[0].hypot(q[1]) >= reach)
    }

    fn normal(&self, q: &Lanes) -> [f64; 2] {
        let d = q[0].hypot(q[1]);
        [q[0] / d, q[1] / d]
    }

    fn spring(&self) -> &TangentialSpring {
        &self.contact.spring
    }

    fn radius(&self) -> f64 {
        self.pair.law.r
    }

    fn poll_stride(&self) -> u64 {
        self.poll_stride
    }

    fn push(tr: &mut Trace, t: f64, (q, v): (&Lanes, &Lanes), f: &PairForces, _d: f64, xi: f64) {
        tr.push_pair(t, q, v, f, xi);
    }

    /// The angular momentum restored once, on the final state: Gear-5's steps drift by up to
    /// 7e-10 of m* v (r1 + r2) per impact (Verlet's by round-off), far below their error;
    /// restored after every step, as the adaptive path does, it cost a quarter of a disc
    /// pair's step (40 against 32.5 ns). Round bodies part along the line of centres where
    /// they were last `reach` apart, found by going back along the flight since.
    fn close(&self, rec: &mut Record, init: &Initial, (q, v): (Lanes, Lanes), n_sep: [f64; 2]) {
        let turn = self.pair.restoring_turn(&q, &v, self.l0);
        let v: Lanes = std::array::from_fn(|i| v[i] + turn[i]);
        let n_sep = if G::CORNERS {
            n_sep
        } else {
            separation_normal(&q, &v, self.contact.geometry.reach())
        };
        let end = Ending {
            q,
            v,
            y0: self.y0,
            n_sep,
        };
        rec.close(&Bodies::Pair(self.pair), init, &end);
    }
}
