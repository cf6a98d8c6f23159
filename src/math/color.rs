//! Linear RGB colour and the sRGB transfer function.

use serde::{Deserialize, Serialize};
use std::ops::{Add, AddAssign, Div, Mul, MulAssign};
use std::sync::LazyLock;

/// A linear-light RGB colour (radiance or reflectance). Presets write it as a tuple `(r, g, b)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Rgb(pub f32, pub f32, pub f32);

impl Rgb {
    /// Black.
    pub const BLACK: Self = Self(0.0, 0.0, 0.0);
    /// White.
    pub const WHITE: Self = Self(1.0, 1.0, 1.0);

    /// A grey of value `v`.
    #[must_use]
    pub const fn grey(v: f32) -> Self {
        Self(v, v, v)
    }

    /// The colour as an array.
    #[must_use]
    pub const fn to_array(self) -> [f32; 3] {
        [self.0, self.1, self.2]
    }

    /// From an array.
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

    /// Largest channel.
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

    #[test]
    fn encoding_clamps_and_kills_nan() {
        assert_eq!(linear_to_srgb(f32::NAN), 0.0);
        assert_eq!(linear_to_srgb(-1.0), 0.0);
        assert!(linear_to_srgb(7.0) > 0.9999 && linear_to_srgb(7.0) <= 1.0);
    }
}
