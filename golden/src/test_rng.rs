//! A seeded random number generator for the unit tests (xorshift64*), so
//! that every random case replays; the workspace tests use `rand_chacha`.

/// xorshift64* with a fixed seed.
pub(crate) struct TestRng(u64);

impl TestRng {
    /// A generator seeded with `seed` (non-zero).
    pub(crate) fn new(seed: u64) -> Self {
        assert_ne!(seed, 0, "xorshift needs a non-zero seed");
        TestRng(seed)
    }

    /// The next 64 random bits.
    pub(crate) fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
}
