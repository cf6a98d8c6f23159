//! `texplore probe`: turns an equirectangular panorama into the light-probe image the
//! light-probe mapping reads.
//!
//! The panorama is read the way the spherical mapping reads an image (u = atan2(x, z) / 2 pi,
//! v = 1 - acos(y) / pi; left edge = longitude -180 degrees when +z is longitude 0, top row =
//! zenith), so a panorama on the environment sphere under the spherical map and its probe under
//! the light-probe map show the same room.

use crate::error::{Error, Result};
use crate::mapping::Mapping;
use crate::math::{PI, Rgb, Vec3A};
use crate::output::{check_extension, check_output, extension, write_atomically};
use crate::texture::{ImageData, Wrap, load_image};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The layout of a probe image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
#[derive(Serialize, Deserialize)]
pub enum ProbeFormat {
    /// Debevec's angular map, the lecture's: distance from the centre is proportional to the
    /// angle from +z (read by the `light-probe` mapping).
    #[default]
    Angular,
    /// A mirror ball photographed from +z: distance from the centre is sin(angle / 2)
    /// (read by the `mirror-ball` mapping).
    MirrorBall,
}

impl ProbeFormat {
    /// The mapping that reads this format.
    #[must_use]
    pub const fn mapping(self) -> Mapping {
        match self {
            Self::Angular => Mapping::LightProbe,
            Self::MirrorBall => Mapping::MirrorBall,
        }
    }

    /// The direction seen at probe-image position `(a, b)` in [-1, 1]^2 (a right, b up), or
    /// `None` outside the disc.
    #[must_use]
    pub fn direction(self, a: f32, b: f32) -> Option<Vec3A> {
        let r = (a * a + b * b).sqrt();
        if r > 1.0 {
            return None;
        }
        let alpha = match self {
            Self::Angular => r * PI,
            Self::MirrorBall => 2.0 * r.asin(),
        };
        let (cb, sb) = if r > 0.0 { (a / r, b / r) } else { (1.0, 0.0) };
        let (sa, ca) = alpha.sin_cos();
        Some(Vec3A::new(sa * cb, sa * sb, ca))
    }
}

/// Subsamples per probe pixel along each axis (antialiases the disc's rim and the panorama).
const SUPERSAMPLE: u32 = 3;

/// Builds a `size` x `size` probe image from a panorama.
#[must_use]
pub fn panorama_to_probe(panorama: &ImageData, size: u32, format: ProbeFormat) -> ImageData {
    let n = size.max(1);
    let k = SUPERSAMPLE;
    ImageData::from_fn(n, n, "probe", |col, row_top| {
        let mut sum = Rgb::BLACK;
        for sy in 0..k {
            for sx in 0..k {
                let u = (col as f32 + (sx as f32 + 0.5) / k as f32) / n as f32;
                let v = 1.0 - (row_top as f32 + (sy as f32 + 0.5) / k as f32) / n as f32;
                if let Some(d) = format.direction(2.0 * u - 1.0, 2.0 * v - 1.0) {
                    let uv = Mapping::Spherical.map_point(d).uv;
                    sum += panorama.bilinear(uv, Wrap::Repeat, Wrap::Clamp);
                }
            }
        }
        sum / (k * k) as f32
    })
}

/// The extensions a probe can be written as.
pub const PROBE_EXTS: &[&str] = &["hdr", "exr", "png", "jpg", "jpeg", "tif", "tiff", "ppm"];

/// Reads a panorama, converts it and writes the probe. The output format follows the
/// extension: `.hdr` or `.exr` keep linear values; `.png`, `.jpg`, `.tif` and `.ppm` are
/// sRGB-encoded and clip above 1. The output is checked (extension, not the panorama itself,
/// not a directory or device) before the panorama is read.
///
/// # Errors
/// The output is refused, the panorama cannot be read, or the probe cannot be written.
pub fn make_probe(
    panorama: &Path,
    output: &Path,
    size: u32,
    format: ProbeFormat,
) -> Result<ImageData> {
    if !(1..=16_384).contains(&size) {
        return Err(Error::invalid(
            output,
            format!("--size {size} is out of range (1 to 16384)"),
        ));
    }
    check_output(output, PROBE_EXTS, &[panorama])?;
    let pano = load_image(panorama, true)?;
    let probe = panorama_to_probe(&pano, size, format);
    save_image_checked(&probe, output, &[panorama])?;
    Ok(probe)
}

/// Writes an image, linear for `.hdr`/`.exr`, sRGB 8-bit otherwise, atomically, in the
/// format its extension names (see [`PROBE_EXTS`]).
///
/// # Errors
/// Unknown extension, a refused output or a failed write: "cannot write FILE: reason".
pub fn save_image(img: &ImageData, path: &Path) -> Result<()> {
    save_image_checked(img, path, &[])
}

/// [`save_image`] that also refuses to write over any of `inputs`.
///
/// # Errors
/// As [`save_image`].
pub fn save_image_checked(img: &ImageData, path: &Path, inputs: &[&Path]) -> Result<()> {
    check_extension(path, PROBE_EXTS)?;
    let ext = extension(path);
    let (w, h) = (img.width(), img.height());
    let image = if matches!(ext.as_str(), "hdr" | "exr") {
        let mut data = Vec::with_capacity(w as usize * h as usize * 3);
        for y in 0..h {
            for x in 0..w {
                data.extend_from_slice(&img.texel_top(x, y).to_array());
            }
        }
        image::Rgb32FImage::from_raw(w, h, data).map(image::DynamicImage::ImageRgb32F)
    } else {
        image::RgbImage::from_raw(w, h, img.to_srgb8()).map(image::DynamicImage::ImageRgb8)
    };
    let image = image.ok_or_else(|| Error::Write {
        path: path.to_path_buf(),
        reason: "the pixel buffer does not match the image size".into(),
    })?;
    let format = match ext.as_str() {
        "hdr" => image::ImageFormat::Hdr,
        "exr" => image::ImageFormat::OpenExr,
        "png" => image::ImageFormat::Png,
        "jpg" | "jpeg" => image::ImageFormat::Jpeg,
        "tif" | "tiff" => image::ImageFormat::Tiff,
        _ => image::ImageFormat::Pnm,
    };
    write_atomically(path, inputs, |out| {
        image.write_to(out, format).map_err(std::io::Error::other)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec2;

    /// A panorama whose colour encodes the direction it shows: red = x, green = y, blue = z
    /// (each mapped to [0, 1]).
    fn direction_panorama() -> ImageData {
        let (w, h) = (256, 128);
        ImageData::from_fn(w, h, "dirs", |c, r| {
            let u = (c as f32 + 0.5) / w as f32;
            let v = 1.0 - (r as f32 + 0.5) / h as f32;
            let phi = u * crate::math::TAU;
            let theta = (1.0 - v) * PI;
            let d = Vec3A::new(
                theta.sin() * phi.sin(),
                theta.cos(),
                theta.sin() * phi.cos(),
            );
            Rgb((d.x + 1.0) / 2.0, (d.y + 1.0) / 2.0, (d.z + 1.0) / 2.0)
        })
    }

    #[test]
    fn probe_read_through_its_mapping_shows_the_same_direction() {
        let pano = direction_panorama();
        for format in [ProbeFormat::Angular, ProbeFormat::MirrorBall] {
            let probe = panorama_to_probe(&pano, 256, format);
            for d in [
                Vec3A::new(0.3, 0.5, 0.8),
                Vec3A::new(-0.7, 0.1, 0.2),
                Vec3A::new(0.1, -0.9, -0.3),
                Vec3A::new(0.0, 0.0, 1.0),
            ] {
                let d = d.normalize();
                let uv = format.mapping().map_point(d).uv;
                let c = probe.bilinear(uv, Wrap::Clamp, Wrap::Clamp);
                let seen = Vec3A::new(c.0 * 2.0 - 1.0, c.1 * 2.0 - 1.0, c.2 * 2.0 - 1.0);
                assert!((seen - d).length() < 0.06, "{format:?} {d:?} -> {seen:?}");
            }
        }
    }

    #[test]
    fn inverse_of_the_mapping() {
        for format in [ProbeFormat::Angular, ProbeFormat::MirrorBall] {
            for (a, b) in [(0.1, 0.2), (-0.5, 0.3), (0.0, -0.9), (0.6, 0.6)] {
                let d = format.direction(a, b).unwrap();
                let uv = format.mapping().map_point(d).uv;
                assert!((uv - Vec2::new((a + 1.0) / 2.0, (b + 1.0) / 2.0)).length() < 1e-4);
            }
        }
        assert!(ProbeFormat::Angular.direction(0.9, 0.9).is_none());
    }
}
