//! Stateless, seeded random numbers: every value derives from (seed, pixel, sample index), so a
//! render is identical on every run and every thread count.

/// A 32-bit integer hash of three words (a PCG-style permutation per word, chained).
#[must_use]
#[inline]
pub fn hash3(a: u32, b: u32, c: u32) -> u32 {
    let mut h = pcg(a ^ 0x9e37_79b9);
    h = pcg(h ^ b);
    pcg(h ^ c)
}

#[inline]
fn pcg(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// A tiny generator seeded from (seed, pixel, sample): draws uniform floats in [0, 1).
#[derive(Clone, Copy, Debug)]
pub struct SampleRng {
    state: u32,
}

impl SampleRng {
    /// The generator for one sample of one pixel.
    #[must_use]
    #[inline]
    pub fn new(seed: u32, pixel: u32, sample: u32) -> Self {
        Self {
            state: hash3(seed, pixel, sample),
        }
    }

    /// The next 32 random bits.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        self.state = pcg(self.state);
        self.state
    }

    /// A uniform float in [0, 1) (24 random bits, never 1.0).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_stay_in_unit_interval_and_spread() {
        let mut r = SampleRng::new(1, 2, 3);
        let mut sum = 0.0;
        for _ in 0..10_000 {
            let x = r.next_f32();
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        assert!((sum / 10_000.0 - 0.5).abs() < 0.02);
    }

    #[test]
    fn streams_differ_by_pixel_and_sample() {
        assert_ne!(hash3(0, 1, 0), hash3(0, 2, 0));
        assert_ne!(hash3(0, 1, 0), hash3(0, 1, 1));
        assert_eq!(hash3(7, 8, 9), hash3(7, 8, 9));
    }
}
