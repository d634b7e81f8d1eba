//! Cundall-Strack tangential spring with a damper and a Coulomb cap; Mindlin's spring shares
//! it (its history as the force or the displacement, rescaled or not: docs/model.md, 14.8).

/// Whether the contact point sticks or slips in a step (for the trace and slip counting).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StickState {
    /// No tangential interaction this step (no overlap, or mu = 0).
    #[default]
    None,
    /// The spring force stayed within the Coulomb cone.
    Stick,
    /// The force was capped at mu F_n.
    Slip,
}

impl StickState {
    /// 0 none, 1 stick, 2 slip (for columns).
    pub fn code(self) -> u8 {
        match self {
            StickState::None => 0,
            StickState::Stick => 1,
            StickState::Slip => 2,
        }
    }
}

/// The force of a sticking spring of stiffness `kt` at elongation `xi` with its damper:
/// -k_t xi - c_t v_t (the trial force that Coulomb's cap tests).
#[inline(always)]
pub fn trial_force(kt: f64, xi: f64, ct: f64, v_t: f64) -> f64 {
    -kt * xi - ct * v_t
}

/// The elongation at which the spring, with its damper, carries the force `f_t`:
/// xi = -(F_t + c_t v_t) / k_t (a capped spring, and the slip -> stick handover).
#[inline(always)]
pub fn carrying(f_t: f64, kt: f64, ct: f64, v_t: f64) -> f64 {
    -(f_t + ct * v_t) / kt
}

/// The history-dependent tangential spring.
#[derive(Debug, Clone, Default)]
pub struct TangentialSpring {
    /// Spring elongation xi (m).
    pub xi: f64,
    /// State in the previous step.
    pub last: StickState,
    /// Stick to slip transitions so far.
    pub slip_events: u64,
    /// The depth at the previous step (m; 0 before the first): what [`Self::rescale`]
    /// compares with.
    pub last_depth: f64,
}

impl TangentialSpring {
    /// One step: elongate by `v_t dt`, cap at `mu fn_`, and return the force F_t.
    ///
    /// When capped, the spring is reset to carry what the damper does not,
    /// xi = -(F_t + c_t v_t) / k_t (the rule LAMMPS uses).
    #[inline]
    pub fn step(
        &mut self,
        v_t: f64,
        dt: f64,
        mu: f64,
        fn_: f64,
        kt: f64,
        ct: f64,
    ) -> (f64, StickState) {
        self.step_scaled(v_t, dt, mu, fn_, kt, 1.0, ct)
    }

    /// As [`Self::step`] with the elongation growing at `rate` v_t: with `kt` = 1 and `rate`
    /// the current stiffness this is the spring incremental in the force (Mindlin's, whose
    /// stiffness changes with the depth): xi is then minus the elastic force.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub fn step_scaled(
        &mut self,
        v_t: f64,
        dt: f64,
        mu: f64,
        fn_: f64,
        kt: f64,
        rate: f64,
        ct: f64,
    ) -> (f64, StickState) {
        if mu == 0.0 {
            self.reset();
            return (0.0, StickState::None);
        }
        self.xi += rate * v_t * dt;
        let trial = trial_force(kt, self.xi, ct, v_t);
        let cap = mu * fn_;
        let (f, state) = if trial.abs() > cap {
            let f = cap.copysign(trial);
            self.xi = carrying(f, kt, ct, v_t);
            (f, StickState::Slip)
        } else {
            (trial, StickState::Stick)
        };
        if state == StickState::Slip && self.last == StickState::Stick {
            self.slip_events += 1;
        }
        self.last = state;
        (f, state)
    }

    /// Walton's rescaling of the history as the contact unloads (LAMMPS's `mindlin_rescale`
    /// variants): where the depth fell since the previous step, xi shrinks with the contact
    /// radius a = sqrt(R delta), xi <- xi a / a_prev; then the depth is remembered. Called
    /// before [`Self::step_scaled`] adds the step's increment.
    #[inline]
    pub fn rescale(&mut self, depth: f64) {
        if depth < self.last_depth {
            self.xi *= (depth / self.last_depth).sqrt();
        }
        self.last_depth = depth;
    }

    /// No overlap: the spring relaxes (a new contact starts unstretched).
    #[inline]
    pub fn reset(&mut self) {
        self.xi = 0.0;
        self.last = StickState::None;
        self.last_depth = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn caps_at_coulomb_and_counts_stick_to_slip() {
        let mut s = TangentialSpring::default();
        let (kt, ct, mu, fn_, dt) = (10.0, 0.0, 0.5, 1.0, 0.01);
        // Small velocity: sticks.
        let (f, st) = s.step(1.0, dt, mu, fn_, kt, ct);
        assert_eq!(st, StickState::Stick);
        assert!((f + 0.1).abs() < 1e-15);
        // Big velocity: slips at exactly mu F_n, opposing the motion; one event.
        let (f, st) = s.step(100.0, dt, mu, fn_, kt, ct);
        assert_eq!(st, StickState::Slip);
        assert_eq!(f, -0.5);
        assert_eq!(s.slip_events, 1);
        assert!(
            (s.xi - 0.05).abs() < 1e-15,
            "spring reset to carry the capped force"
        );
        // Staying in slip does not count again.
        s.step(100.0, dt, mu, fn_, kt, ct);
        assert_eq!(s.slip_events, 1);
    }

    #[test]
    fn rescale_shrinks_with_the_contact_radius_on_unloading_only() {
        let mut s = TangentialSpring::default();
        s.rescale(4e-6);
        s.xi = 2.0;
        // Loading: untouched.
        s.rescale(9e-6);
        assert_eq!(s.xi, 2.0);
        // Unloading to a quarter of the depth: half the contact radius, half the history.
        s.rescale(2.25e-6);
        assert!((s.xi - 1.0).abs() < 1e-15, "{}", s.xi);
        s.reset();
        assert_eq!((s.xi, s.last_depth), (0.0, 0.0));
    }

    #[test]
    fn frictionless_gives_no_force() {
        let mut s = TangentialSpring::default();
        assert_eq!(
            s.step(3.0, 0.1, 0.0, 5.0, 1.0, 1.0),
            (0.0, StickState::None)
        );
        assert_eq!(s.xi, 0.0);
    }
}
