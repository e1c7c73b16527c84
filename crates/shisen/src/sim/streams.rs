//! The run's random streams.

use rand::SeedableRng;
use rand::rngs::StdRng;

/// Independent random streams, one per consumer, all derived from the
/// scene seed, so adding draws to one never shifts another.
pub(super) struct Streams {
    pub behaviour: StdRng,
    pub oculomotor: StdRng,
    pub face: StdRng,
    /// The physical body's motor noise (its sway).
    pub body: StdRng,
}

impl Streams {
    pub fn new(seed: u64) -> Self {
        let derive = |k: u64| StdRng::seed_from_u64(seed ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        Streams {
            behaviour: derive(1),
            oculomotor: derive(2),
            face: derive(3),
            body: derive(4),
        }
    }
}
