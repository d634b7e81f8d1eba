//! What the contact law needs to know of an overlap with the plate, whatever computed it (the
//! disc's segment, the polygon's clip, parry, the sphere's contact): one summary type.

/// What the contact law needs to know about the overlap of a particle with the plate.
///
/// Positions are relative to the particle's centre of mass in x (`cx`, `x_mid`, `x_low`) and
/// absolute in y (the plate is y = 0, so the overlap lies at y <= 0).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Overlap {
    /// Overlap area A (m^2).
    pub area: f64,
    /// Overlap centroid, x relative to the centre of mass (m).
    pub cx: f64,
    /// Overlap centroid, absolute y (m, <= 0).
    pub cy: f64,
    /// Chord length l: the part of y = 0 inside the particle (m).
    pub chord: f64,
    /// Chord midpoint, x relative to the centre of mass (m).
    pub x_mid: f64,
    /// Depth of the particle's lowest point below the plate (m, > 0 in contact).
    pub depth: f64,
    /// Lowest point, x relative to the centre of mass (m).
    pub x_low: f64,
    /// First moment of the overlap about y = 0: integral of (-y) dA (m^3). The elastic
    /// potential of the area law is (E / L) times this.
    pub first_moment: f64,
    /// Which of a polygon's vertices lie at or below the plate (all zero for a disc). The
    /// contact law is smooth while this stays the same; a change marks an event (a touch, a
    /// separation, a corner crossing the plate) that the fixed-step integrators locate.
    pub corners: Corners,
}

impl Overlap {
    /// The rate at which the body at velocity `v` = (v_x, v_y, omega) sinks at the point `x`
    /// (from the centre) on the plate: -(v_y + omega x).
    #[inline(always)]
    fn sink(v: &[f64; 3], x: f64) -> f64 {
        -(v[1] + v[2] * x)
    }

    /// dA/dt for the body velocity `v`: the chord times the rate at which the body sinks at
    /// its midpoint (the rate is linear along the chord), -l (v_y + omega x_mid).
    #[inline(always)]
    pub fn area_rate(&self, v: &[f64; 3]) -> f64 {
        self.chord * Self::sink(v, self.x_mid)
    }

    /// The rate at which the lowest point deepens for the body velocity `v`:
    /// -(v_y + omega x_low).
    #[inline(always)]
    pub fn depth_rate(&self, v: &[f64; 3]) -> f64 {
        Self::sink(v, self.x_low)
    }
}

/// The chain of a polygon's vertices at or below the plate: the first of them in
/// counter-clockwise order and how many there are (below the plate they are contiguous).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Corners {
    /// Index of the first vertex of the chain.
    pub first: u32,
    /// Number of vertices in the chain.
    pub count: u32,
}
