//! What holds in one piece of a pair's impact on the adaptive path (docs/model.md, 17.5): the
//! ODE's state, the modes of a piece (clip, stick, slip, apart), the switches that end one, and
//! what an evaluation of the law yields. Plain types, using no other part of the pair's path.

use crate::law::pair::PairForces;
use crate::law::StickState;

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
/// The components a step's dense output forms for its switches and extremes: the law reads
/// the positions, velocities and spring alone; the works are read at a step's end and at a
/// switch (where the state is formed whole), so they are not interpolated at every sample
/// (their coefficients were a fifth of the ones a disc pair's step formed).
pub(super) const INTERPOLATED: usize = XI + 1;

/// The tangential law of a piece: the plate's.
pub(super) use crate::impact::adaptive::Tan;

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
    /// The overlap's chord (`PairFrame::chord`; 0 apart).
    pub(super) chord: f64,
    pub(super) n: [f64; 2],
    /// The elastic and damping parts on the lanes (clipped by the mode) and the tangential
    /// force's lever (`PairFrame`).
    pub(super) el: [f64; 4],
    pub(super) damp: [f64; 4],
    pub(super) lever_t: [f64; 2],
    /// Where the contact's frame was found: the levers of the area's rate on the spins
    /// (`PairFrame::lever_rate_area`), from which the opening is read.
    pub(super) lever_rate: Option<[f64; 2]>,
}

/// The law's evaluation at a state, kept where a switch took it: another test at that state, or
/// the next piece's first stage, reads its contact (the frame and the normal force, which read
/// the positions and velocities alone, and the clip) in any tangential mode and spring.
#[derive(Debug, Clone, Copy)]
pub(super) struct Kept {
    /// The positions and velocities it was taken at (all the state but the spring and works).
    at: [f64; XI],
    clipped: bool,
    apart: bool,
    e: Eval,
}

impl Kept {
    /// Evaluation `e` at state `s` in mode `m`.
    pub(super) fn new(s: &State, m: &Mode, e: Eval) -> Self {
        Kept {
            at: std::array::from_fn(|i| s[i]),
            clipped: m.clipped,
            apart: m.apart,
            e,
        }
    }

    /// The kept evaluation, where it holds the contact at `s` in mode `m`: the same
    /// positions and velocities, bit for bit, and a mode of the same clip.
    pub(super) fn contact_at(&self, s: &State, m: &Mode) -> Option<Eval> {
        let same_state = self
            .at
            .iter()
            .zip(s)
            .all(|(a, b)| a.to_bits() == b.to_bits());
        (same_state && (self.clipped, self.apart) == (m.clipped, m.apart)).then_some(self.e)
    }
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
