//! A seeded generator for the random parts of test lines and committed
//! vectors.

/// xorshift64 for the random parts of committed vectors: seeded, and the
/// same on every machine and version, so a recording is reproducible.
pub struct VectorRng(pub u64);

impl VectorRng {
    /// The next 64 random bits (the seed must be non-zero).
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}
