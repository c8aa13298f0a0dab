//! Helpers of the library's unit tests.

/// Draws uniform in [0, 1) from `seed` (a 64-bit linear congruential generator, Knuth's
/// constants): the same numbers on every machine, so a test's random cases are fixed.
pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}
