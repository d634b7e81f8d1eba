//! A small seeded generator of uniform numbers on [0, 1), with no dependency: a 64-bit linear
//! congruential step (Knuth's MMIX constants) and its top 53 bits. The one that the consistency
//! matrix's representative shapes, the tests' random scenes and the examples draw from, so that
//! a seed means the same draws everywhere.

/// The next uniform number on [0, 1) from `state`, which it advances.
pub fn uniform(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}

/// A stream of [`uniform`] numbers from its seed.
#[derive(Debug, Clone)]
pub struct Seeded(pub u64);

impl Seeded {
    /// The next uniform number on [0, 1).
    pub fn uniform(&mut self) -> f64 {
        uniform(&mut self.0)
    }
}
