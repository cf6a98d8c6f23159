//! Linear RGB colour, the sRGB transfer function, the 8-bit quantiser and the display image.

use serde::{Deserialize, Serialize};
use std::ops::{Add, AddAssign, Div, Mul, MulAssign};
use std::sync::LazyLock;

/// A linear-light RGB colour (radiance or reflectance). Presets write it as a tuple `(r, g, b)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Rgb(pub f32, pub f32, pub f32);

impl Rgb {
    pub const BLACK: Self = Self(0.0, 0.0, 0.0);
    /// `(1, 1, 1)`: full reflectance, and the default colour of lights and the ambient light.
    pub const WHITE: Self = Self(1.0, 1.0, 1.0);

    /// A grey of value `v`.
    #[must_use]
    pub const fn grey(v: f32) -> Self {
        Self(v, v, v)
    }

    /// `[r, g, b]`.
    #[must_use]
    pub const fn to_array(self) -> [f32; 3] {
        [self.0, self.1, self.2]
    }

    /// From `[r, g, b]`.
    #[must_use]
    pub const fn from_array(a: [f32; 3]) -> Self {
        Self(a[0], a[1], a[2])
    }

    /// True when every channel is finite.
    #[must_use]
    pub fn is_finite(self) -> bool {
        self.0.is_finite() && self.1.is_finite() && self.2.is_finite()
    }

    /// Rec. 709 luminance.
    #[must_use]
    pub fn luminance(self) -> f32 {
        0.2126 * self.0 + 0.7152 * self.1 + 0.0722 * self.2
    }

    #[must_use]
    pub fn max_channel(self) -> f32 {
        self.0.max(self.1).max(self.2)
    }
}

impl Add for Rgb {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self(self.0 + o.0, self.1 + o.1, self.2 + o.2)
    }
}
impl AddAssign for Rgb {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl Mul for Rgb {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self(self.0 * o.0, self.1 * o.1, self.2 * o.2)
    }
}
impl Mul<f32> for Rgb {
    type Output = Self;
    #[inline]
    fn mul(self, s: f32) -> Self {
        Self(self.0 * s, self.1 * s, self.2 * s)
    }
}
impl Mul<Rgb> for f32 {
    type Output = Rgb;
    #[inline]
    fn mul(self, c: Rgb) -> Rgb {
        c * self
    }
}
impl MulAssign<f32> for Rgb {
    #[inline]
    fn mul_assign(&mut self, s: f32) {
        *self = *self * s;
    }
}
impl Div<f32> for Rgb {
    type Output = Self;
    #[inline]
    fn div(self, s: f32) -> Self {
        self * (1.0 / s)
    }
}

/// The sRGB decoding curve (IEC 61966-2-1), display value in [0, 1] to linear light.
#[must_use]
pub fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The sRGB encoding curve, linear light to display value; clamps to [0, 1] first.
#[must_use]
pub fn linear_to_srgb(v: f32) -> f32 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    if v <= 0.003_130_8 {
        v * 12.92
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

static SRGB8_TABLE: LazyLock<[f32; 256]> = LazyLock::new(|| {
    let mut t = [0.0; 256];
    for (i, e) in t.iter_mut().enumerate() {
        *e = srgb_to_linear(i as f32 / 255.0);
    }
    t
});

/// Decodes an 8-bit sRGB value through a 256-entry table.
#[must_use]
#[inline]
pub fn srgb8_to_linear(v: u8) -> f32 {
    SRGB8_TABLE[v as usize]
}

/// The table itself, for hot loops that index it directly.
#[must_use]
pub fn srgb8_table() -> &'static [f32; 256] {
    &SRGB8_TABLE
}

static UNORM8_TABLE: LazyLock<[f32; 256]> = LazyLock::new(|| {
    let mut t = [0.0; 256];
    for (i, e) in t.iter_mut().enumerate() {
        *e = f32::from(i as u8) / 255.0;
    }
    t
});

/// The values of raw (not sRGB-encoded) 8-bit samples, `v / 255`, as a 256-entry table: the
/// same bits as the division, read like [`srgb8_table`].
#[must_use]
pub fn unorm8_table() -> &'static [f32; 256] {
    &UNORM8_TABLE
}

/// The 8-bit quantiser: an encoded (display) value in [0, 1] rounded to the nearest byte;
/// clipped to [0, 1] first, NaN to 0. Every 8-bit sRGB byte texplore writes comes from here.
#[must_use]
#[inline]
pub fn quantize8(encoded: f32) -> u8 {
    // `as` saturates and maps NaN to 0.
    (encoded.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Linear value to 8-bit sRGB through the exact curve: [`quantize8`] of [`linear_to_srgb`]
/// (for texel storage, where the value must not depend on a table's step).
#[must_use]
#[inline]
pub fn linear_to_srgb8(v: f32) -> u8 {
    quantize8(linear_to_srgb(v))
}

const ENCODE_STEPS: usize = 1 << 16;

static ENCODE_TABLE: LazyLock<Vec<u8>> = LazyLock::new(|| {
    (0..ENCODE_STEPS)
        .map(|i| linear_to_srgb8(i as f32 / (ENCODE_STEPS - 1) as f32))
        .collect()
});

/// Linear value to 8-bit sRGB for display: [`linear_to_srgb8`] sampled at 65536 steps of
/// [0, 1] (the input is rounded to the nearest step, so a value near a rounding boundary can
/// land one byte from the exact curve's); clips to [0, 1], NaN to 0. Renders and PNGs use it.
#[must_use]
#[inline]
pub fn encode_srgb8(v: f32) -> u8 {
    let v = if v > 0.0 { v.min(1.0) } else { 0.0 }; // also maps NaN to 0
    ENCODE_TABLE[(v * (ENCODE_STEPS - 1) as f32 + 0.5) as usize]
}

/// One linear pixel, times `exposure_scale`, as display bytes ([`encode_srgb8`] per channel).
#[must_use]
#[inline]
pub fn encode_display(c: Rgb, exposure_scale: f32) -> [u8; 3] {
    (c * exposure_scale).to_array().map(encode_srgb8)
}

/// An 8-bit sRGB RGBA image ready for the screen or a PNG.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DisplayImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGBA bytes, row-major from the top-left pixel.
    pub rgba: Vec<u8>,
}

impl DisplayImage {
    /// Linear radiance, scaled and encoded ([`encode_display`]; alpha 255).
    #[must_use]
    pub fn from_linear(width: u32, height: u32, pixels: &[Rgb], exposure_scale: f32) -> Self {
        Self::encode(width, height, pixels.iter().copied(), exposure_scale)
    }

    /// [`DisplayImage::from_linear`] of pixels computed on the fly.
    #[must_use]
    pub fn encode(
        width: u32,
        height: u32,
        pixels: impl ExactSizeIterator<Item = Rgb>,
        exposure_scale: f32,
    ) -> Self {
        let mut rgba = Vec::with_capacity(pixels.len() * 4);
        for c in pixels {
            let [r, g, b] = encode_display(c, exposure_scale);
            rgba.extend_from_slice(&[r, g, b, 255]);
        }
        Self {
            width,
            height,
            rgba,
        }
    }

    /// The RGB bytes without alpha.
    #[must_use]
    pub fn rgb(&self) -> Vec<u8> {
        self.rgba
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips_every_byte() {
        for i in 0..=255u8 {
            let lin = srgb8_to_linear(i);
            let back = (linear_to_srgb(lin) * 255.0).round() as u8;
            assert_eq!(back, i);
        }
    }

    /// Every linear value worth trying: the table's 65536 steps and the midpoints between them
    /// (where its index rounds), every 2048th f32 bit pattern (negatives, subnormals, huge
    /// values, infinities, NaNs) and the curve's edges.
    fn dense_inputs() -> Vec<f32> {
        let steps = (ENCODE_STEPS - 1) as f32;
        let mut v: Vec<f32> = (0..ENCODE_STEPS)
            .flat_map(|i| [i as f32 / steps, (i as f32 + 0.5) / steps])
            .collect();
        v.extend((0..=u32::MAX >> 11).map(|k| f32::from_bits(k << 11)));
        v.extend([
            0.0,
            -0.0,
            1.0,
            1.0 + f32::EPSILON,
            1.0 - f32::EPSILON / 2.0,
            f32::MIN_POSITIVE,
            0.003_130_8,
            0.040_45,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
        ]);
        v
    }

    /// The five 8-bit quantisers [`quantize8`] replaced, as they were written.
    mod former {
        use super::super::linear_to_srgb;
        use std::sync::LazyLock;

        /// `render::film::encode_srgb8` (renders, PNGs, the report's bytes).
        pub fn film_table(v: f32) -> u8 {
            static TABLE: LazyLock<Vec<u8>> = LazyLock::new(|| {
                (0..1usize << 16)
                    .map(|i| (linear_to_srgb(i as f32 / 65535.0) * 255.0).round() as u8)
                    .collect()
            });
            let v = if v > 0.0 { v.min(1.0) } else { 0.0 };
            TABLE[(v * 65535.0 + 0.5) as usize]
        }
        /// `EncodedImage::from_srgb`.
        pub fn report_from_srgb(v: f32) -> u8 {
            (v.clamp(0.0, 1.0) * 255.0).round() as u8
        }
        /// `ImageData::to_srgb8`.
        pub fn image_to_srgb8(ch: f32) -> u8 {
            (linear_to_srgb(ch) * 255.0).round() as u8
        }
        /// The mip pyramid's sRGB levels and the inspector's swatches.
        pub fn mip_and_inspector(v: f32) -> u8 {
            (linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0).round() as u8
        }
    }

    #[test]
    fn the_one_quantiser_gives_the_former_bytes() {
        for v in dense_inputs() {
            assert_eq!(encode_srgb8(v), former::film_table(v), "{v:e}");
            assert_eq!(quantize8(v), former::report_from_srgb(v), "{v:e}");
            assert_eq!(linear_to_srgb8(v), former::image_to_srgb8(v), "{v:e}");
            assert_eq!(linear_to_srgb8(v), former::mip_and_inspector(v), "{v:e}");
        }
    }

    #[test]
    fn the_table_is_the_exact_curve_at_its_steps_and_within_one_byte_between() {
        let steps = (ENCODE_STEPS - 1) as f32;
        for i in 0..ENCODE_STEPS {
            let v = i as f32 / steps;
            assert_eq!(encode_srgb8(v), linear_to_srgb8(v), "{v}");
        }
        for v in dense_inputs() {
            let d = i32::from(encode_srgb8(v)) - i32::from(linear_to_srgb8(v));
            assert!(d.abs() <= 1, "{v:e}: {d}");
        }
        assert_eq!(encode_srgb8(f32::NAN), 0);
        assert_eq!(encode_srgb8(f32::INFINITY), 255);
        assert_eq!(encode_srgb8(-3.0), 0);
        assert_eq!(quantize8(0.5), 128);
        assert_eq!(quantize8(0.5 / 255.0 - 1e-6), 0);
    }

    #[test]
    fn display_image_encodes_like_the_film_did() {
        let inputs = dense_inputs();
        let pixels: Vec<Rgb> = inputs
            .chunks_exact(3)
            .map(|c| Rgb(c[0], c[1], c[2]))
            .collect();
        for exposure in [1.0, 0.37, 4.0] {
            let img = DisplayImage::from_linear(pixels.len() as u32, 1, &pixels, exposure);
            let mut expected = Vec::with_capacity(pixels.len() * 4);
            for c in &pixels {
                let c = *c * exposure;
                expected.extend_from_slice(&[
                    former::film_table(c.0),
                    former::film_table(c.1),
                    former::film_table(c.2),
                    255,
                ]);
            }
            assert!(img.rgba == expected, "exposure {exposure}");
            assert_eq!(img.rgb().len(), pixels.len() * 3);
            assert!(
                img.rgb()
                    .iter()
                    .eq(expected.chunks_exact(4).flat_map(|p| &p[..3]))
            );
        }
    }

    #[test]
    fn encoding_clamps_and_kills_nan() {
        assert_eq!(linear_to_srgb(f32::NAN), 0.0);
        assert_eq!(linear_to_srgb(-1.0), 0.0);
        assert!(linear_to_srgb(7.0) > 0.9999 && linear_to_srgb(7.0) <= 1.0);
    }
}
