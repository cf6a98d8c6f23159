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

/// [`hash3`] of (`a`, `b[i]`, `c`) per lane: the same numbers, in plain u32 lane loops that
/// compile to vector multiplies and per-lane shifts (AVX2's `vpsrlvd`) where inlined into a
/// dispatched kernel.
#[must_use]
#[inline(always)]
pub fn hash3_lanes<const N: usize>(a: u32, b: &[u32; N], c: u32) -> [u32; N] {
    let h0 = pcg(a ^ 0x9e37_79b9);
    let mut h = [0; N];
    for (x, bi) in h.iter_mut().zip(b) {
        *x = h0 ^ bi;
    }
    pcg_lanes(&mut h);
    for x in &mut h {
        *x ^= c;
    }
    pcg_lanes(&mut h);
    h
}

/// The PCG permutation ([`SampleRng::next_u32`]'s step) per lane, in place.
#[inline(always)]
pub fn pcg_lanes<const N: usize>(v: &mut [u32; N]) {
    for x in v.iter_mut() {
        let state = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
        // The shift is 4..=19: `wrapping_shr` only spares the debug build its overflow check.
        let word = (state.wrapping_shr((state >> 28) + 4) ^ state).wrapping_mul(277_803_737);
        *x = (word >> 22) ^ word;
    }
}

/// [`SampleRng::next_f32`]'s conversion of 32 random bits to a float in [0, 1).
#[must_use]
#[inline(always)]
pub fn unit_f32(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
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
        unit_f32(self.next_u32())
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
    fn lane_hashes_and_steps_match_the_scalar_ones() {
        let pixels = [0, 1, 2, 799, 800, 640_000, 0x7fff_ffff, u32::MAX];
        for seed in [0, 1, 0xdead_beef] {
            for k in [0, 3, u32::MAX] {
                let mut h = hash3_lanes(seed, &pixels, k);
                let mut rngs = pixels.map(|p| SampleRng::new(seed, p, k));
                for (i, p) in pixels.iter().enumerate() {
                    assert_eq!(h[i], hash3(seed, *p, k), "seed {seed} pixel {p} sample {k}");
                }
                for _ in 0..3 {
                    pcg_lanes(&mut h);
                    for (i, r) in rngs.iter_mut().enumerate() {
                        assert_eq!(h[i], r.next_u32());
                    }
                }
            }
        }
    }

    #[test]
    fn streams_differ_by_pixel_and_sample() {
        assert_ne!(hash3(0, 1, 0), hash3(0, 2, 0));
        assert_ne!(hash3(0, 1, 0), hash3(0, 1, 1));
        assert_eq!(hash3(7, 8, 9), hash3(7, 8, 9));
    }
}
