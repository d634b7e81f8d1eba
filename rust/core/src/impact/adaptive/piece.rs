//! What holds in one piece of an impact: its mode (overlap formula, clip, tangential law), the
//! switches that end a piece, and the bookkeeping the switches update. Plain types, used by
//! every other part of the adaptive path and using none of them.

/// Which overlap formula holds in a piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Touch {
    /// No overlap: free flight.
    Off,
    /// The disc's circular segment.
    Disc,
    /// A polygon with the corners `first .. first + len` (cyclic) below the plate; `low` is one
    /// of them, where a long run's search for its lowest corner starts (`law.rs`, `LONG_RUN`).
    Poly {
        first: usize,
        len: usize,
        low: usize,
    },
}

/// The tangential law in a piece, on the plate and on a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Tan {
    /// mu = 0 or no overlap.
    None,
    /// Spring and damper within the Coulomb cone; xi integrated.
    Stick,
    /// F_t = mu F_n s, s = +-1.
    Slip(f64),
    /// The normal force is clipped: no tangential force, xi = -c_t v_t / k_t.
    Free,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Mode {
    pub(super) touch: Touch,
    pub(super) clip_on: bool,
    /// The clip held off for one step, its events ignored, where it chatters (see
    /// `OnPlate::resolve_chatter`).
    pub(super) clip_hold: bool,
    pub(super) tan: Tan,
    /// Past the deepest point of a contact, for a history that shrinks as the contact unloads
    /// (the `mindlin_rescale` variants; always false for the others).
    pub(super) unloading: bool,
}

impl Mode {
    /// Whether the clip is watched: on, with an overlap, not held for chattering.
    pub(super) fn clipped(&self) -> bool {
        self.clip_on && !self.clip_hold && self.touch != Touch::Off
    }
}

/// The switches that end a piece. Each has a continuous event function that is <= 0 while
/// the piece's mode holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Event {
    Touch,
    Separate,
    EnterLeft,
    EnterRight,
    LeaveLeft,
    LeaveRight,
    ClipOff,
    ClipOn,
    ToSlip,
    ToStick,
    /// The deepest point (v_y = 0), where a rescaled history starts to shrink: a kink in its
    /// rate that the step control cannot see.
    Unload,
}

/// Bookkeeping of one impact that is not part of the ODE state.
#[derive(Default)]
pub(super) struct Tally {
    pub(super) contact_start: f64,
    pub(super) contact_time: f64,
    pub(super) contacts: u32,
    pub(super) slip_events: u64,
    pub(super) stuck: bool,
    pub(super) max_depth: f64,
    pub(super) max_area: f64,
}
