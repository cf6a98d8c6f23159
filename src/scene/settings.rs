//! Render settings: the description ([`RenderDesc`], [`AdaptiveDesc`], [`SnapshotDesc`]), its
//! ranges, the checked runtime [`RenderSettings`], and the command line's [`Overrides`].

use super::preset::SceneDesc;
use super::texture::TextureDesc;
use super::values::finite_non_negative;
use crate::field::{FieldPath, Refusal};
use crate::math::Rgb;
use crate::sampler::{PixelFilter, PixelSampler};
use crate::texture::{Compare, Filter, MAX_COMPARE_TOLERANCE, View};
use serde::{Deserialize, Serialize};

/// Largest accepted width or height of a render.
pub const MAX_RESOLUTION: u32 = 16_384;

/// Bytes a render keeps for each pixel, whatever the command: the film's running sums (16),
/// its adaptive statistics and edge keys (12), the display image (4) and a linear copy (12,
/// what EXR output and the report's metrics read).
pub const RENDER_BYTES_PER_PIXEL: u64 = 44;

/// The memory a render's per-pixel buffers may take together: 2 GiB, about 6986 x 6986
/// pixels. A larger render is refused before anything is allocated, where it used to abort
/// when the allocation failed (16384 x 16384 needs 11 GiB).
pub const MAX_RENDER_BYTES: u64 = 2 << 30;

/// Largest accepted samples per pixel.
pub const MAX_SPP: u32 = 1 << 20;

/// Image size, sampling, exposure and view. Every field has a default (written below), so a
/// preset lists only what it changes: `render: (width: 320, spp: 4)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderDesc {
    /// Image width in pixels, 1 to [`MAX_RESOLUTION`]; default 640.
    pub width: u32,
    /// Image height in pixels, 1 to [`MAX_RESOLUTION`]; default 480.
    pub height: u32,
    /// Samples per pixel, 1 to [`MAX_SPP`]; default 16.
    pub spp: u32,
    /// Seed of every random number: the same seed gives the same image; default 0.
    pub seed: u32,
    /// Where samples go in a pixel; default `Jittered`.
    pub sampler: PixelSampler,
    /// Exposure in stops, -64 to 64 (multiplies radiance by 2^exposure before display); default 0.
    pub exposure: f32,
    /// Linear radiance of rays that hit nothing (not negative); default black.
    pub background: Rgb,
    /// How a pixel weighs its samples (the reconstruction filter); default `Box`.
    pub pixel_filter: PixelFilter,
    /// Adaptive sampling: after `spp` samples everywhere, more (up to `max_spp`) only where
    /// the image needs them; default `None` (off), on with `adaptive: Some((max_spp: 256))`.
    pub adaptive: Option<AdaptiveDesc>,
    /// What the render shows: the shaded image or a debug view; default `Shaded`.
    pub view: View,
    /// What the `Difference` view compares the texture's mapping with: the built-in mapping
    /// and the tolerance in texels; default `(with: Spherical, tolerance: 1)`.
    #[serde(skip_serializing_if = "is_default_compare")]
    pub compare: Compare,
    /// How many mirror bounces a ray may take (`Reflective` materials), 0 to
    /// [`MAX_REFLECTION_DEPTH`]; 0 shades a mirror as plain Phong; default 4.
    #[serde(skip_serializing_if = "is_default_depth")]
    pub reflection_depth: u32,
}

/// The default [`RenderDesc::reflection_depth`].
pub const DEFAULT_REFLECTION_DEPTH: u32 = 4;

/// The largest [`RenderDesc::reflection_depth`].
pub const MAX_REFLECTION_DEPTH: u32 = 64;

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_default_compare(c: &Compare) -> bool {
    *c == Compare::default()
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_default_depth(d: &u32) -> bool {
    *d == DEFAULT_REFLECTION_DEPTH
}

impl Default for RenderDesc {
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            spp: 16,
            seed: 0,
            sampler: PixelSampler::Jittered,
            exposure: 0.0,
            background: Rgb::BLACK,
            pixel_filter: PixelFilter::Box,
            adaptive: None,
            view: View::Shaded,
            compare: Compare::default(),
            reflection_depth: DEFAULT_REFLECTION_DEPTH,
        }
    }
}

/// Adaptive sampling: after the first `render.spp` samples of every pixel, further passes
/// sample only pixels whose estimated error is above `threshold`, up to `max_spp` in all.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdaptiveDesc {
    /// Most samples a pixel may take, from `render.spp` to [`MAX_SPP`];
    /// required.
    pub max_spp: u32,
    /// Error tolerance in display units ((0, 1], sRGB-encoded luminance): a pixel keeps sampling
    /// while the standard error of its mean, or (after a single sample) its difference from a
    /// neighbour, exceeds this.
    #[serde(default = "default_threshold")]
    pub threshold: f32,
}

/// The default adaptive threshold: about 2.5 steps of 8-bit display colour.
pub const DEFAULT_ADAPTIVE_THRESHOLD: f32 = 0.01;

fn default_threshold() -> f32 {
    DEFAULT_ADAPTIVE_THRESHOLD
}

/// Settings `texplore snapshot` renders at (small and quick, but enough to see every feature).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SnapshotDesc {
    /// Width in pixels; default 320.
    pub width: u32,
    /// Height in pixels; default 240.
    pub height: u32,
    /// Samples per pixel; default 4.
    pub spp: u32,
}

impl Default for SnapshotDesc {
    fn default() -> Self {
        Self {
            width: 320,
            height: 240,
            spp: 4,
        }
    }
}

/// How wide the render kernel runs: not part of a preset, but chosen by whoever renders (the
/// command line's `--simd`, or `TEXPLORE_SIMD`, and the window's start options), and carried in
/// [`RenderSettings::simd`].
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    strum::EnumString,
    strum::Display
)]
#[strum(serialize_all = "kebab-case")]
pub enum SimdMode {
    /// The render kernel at the widest instruction set the CPU has (16 rays a packet on
    /// AVX-512, 8 on AVX2, 4 on NEON, SSE2 and simd128).
    #[default]
    #[strum(
        serialize = "auto",
        serialize = "on",
        serialize = "1",
        serialize = "true"
    )]
    Auto,
    /// The same kernel one ray a packet (pulp's `Scalar`), for comparison: the same pixels.
    #[strum(
        serialize = "scalar",
        serialize = "off",
        serialize = "0",
        serialize = "false"
    )]
    Scalar,
}

/// Settings the renderer needs besides geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Target samples per pixel.
    pub spp: u32,
    /// Seed of every random number.
    pub seed: u32,
    /// Pixel sample pattern.
    pub sampler: PixelSampler,
    /// Linear multiplier applied before display (2^exposure).
    pub exposure_scale: f32,
    /// Radiance of rays that hit nothing.
    pub background: Rgb,
    /// Reconstruction filter (how samples spread around the pixel centre).
    pub pixel_filter: PixelFilter,
    /// Adaptive sampling, if on.
    pub adaptive: Option<AdaptiveDesc>,
    /// The shaded image or a debug view.
    pub view: View,
    /// What the `Difference` view compares with.
    pub compare: Compare,
    /// How many mirror bounces a ray may take.
    pub reflection_depth: u32,
    /// How wide the render kernel runs: [`SimdMode::Auto`] when a scene is built; whoever renders
    /// sets it.
    pub simd: SimdMode,
}

impl RenderSettings {
    /// The most samples any pixel takes: `spp`, or the adaptive `max_spp`.
    #[must_use]
    pub fn max_spp(&self) -> u32 {
        self.adaptive.map_or(self.spp, |a| a.max_spp.max(self.spp))
    }
}

pub(super) fn render_settings(r: &RenderDesc) -> std::result::Result<RenderSettings, Refusal> {
    let at = |field: FieldPath, m: String| Refusal::new(FieldPath::field("render").join(&field), m);
    if !(1..=MAX_RESOLUTION).contains(&r.width) || !(1..=MAX_RESOLUTION).contains(&r.height) {
        return Err(at(
            FieldPath::root(),
            format!(
                "resolution {}x{} is out of range (1 to {MAX_RESOLUTION} per side)",
                r.width, r.height
            ),
        ));
    }
    let bytes = u64::from(r.width) * u64::from(r.height) * RENDER_BYTES_PER_PIXEL;
    if bytes > MAX_RENDER_BYTES {
        let side = ((MAX_RENDER_BYTES / RENDER_BYTES_PER_PIXEL) as f64)
            .sqrt()
            .floor();
        let gib = |b: u64| b as f64 / f64::from(1u32 << 30);
        return Err(at(
            FieldPath::root(),
            format!(
                "{}x{} pixels need {:.1} GiB for the film and the image \
             ({RENDER_BYTES_PER_PIXEL} bytes a pixel), above the {:.0} GiB render budget \
             (about {side}x{side} at most)",
                r.width,
                r.height,
                gib(bytes),
                gib(MAX_RENDER_BYTES)
            ),
        ));
    }
    if !(1..=MAX_SPP).contains(&r.spp) {
        return Err(at(
            "spp".into(),
            format!("{} is out of range (1 to {MAX_SPP})", r.spp),
        ));
    }
    if !r.exposure.is_finite() || r.exposure.abs() > 64.0 {
        return Err(at(
            "exposure".into(),
            format!("{} stops is out of range (-64 to 64)", r.exposure),
        ));
    }
    finite_non_negative("background", &r.background.to_array())
        .map_err(|r| r.under(&FieldPath::field("render")))?;
    if let Some(a) = r.adaptive {
        if !(r.spp..=MAX_SPP).contains(&a.max_spp) {
            return Err(at(
                FieldPath::field("adaptive").then("max_spp"),
                format!(
                    "{} is out of range ({} = render.spp to {MAX_SPP})",
                    a.max_spp, r.spp
                ),
            ));
        }
        if !(a.threshold.is_finite() && a.threshold > 0.0 && a.threshold <= 1.0) {
            return Err(at(
                FieldPath::field("adaptive").then("threshold"),
                format!("{} is out of range (0, 1]", a.threshold),
            ));
        }
    }
    let tol = r.compare.tolerance;
    if !(tol.is_finite() && tol > 0.0 && tol <= MAX_COMPARE_TOLERANCE) {
        return Err(at(
            FieldPath::field("compare").then("tolerance"),
            format!("{tol} texels is out of range (above 0, at most {MAX_COMPARE_TOLERANCE})"),
        ));
    }
    if r.reflection_depth > MAX_REFLECTION_DEPTH {
        return Err(at(
            "reflection_depth".into(),
            format!(
                "{} is out of range (0 to {})",
                r.reflection_depth, MAX_REFLECTION_DEPTH
            ),
        ));
    }
    Ok(RenderSettings {
        width: r.width,
        height: r.height,
        spp: r.spp,
        seed: r.seed,
        sampler: r.sampler,
        exposure_scale: r.exposure.exp2(),
        background: r.background,
        pixel_filter: r.pixel_filter,
        adaptive: r.adaptive,
        view: r.view,
        compare: r.compare,
        reflection_depth: r.reflection_depth,
        simd: SimdMode::Auto,
    })
}

/// Resolution and samples for one render, possibly overriding the preset's.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Width in pixels.
    pub width: Option<u32>,
    /// Height in pixels.
    pub height: Option<u32>,
    /// Samples per pixel.
    pub spp: Option<u32>,
    /// Seed.
    pub seed: Option<u32>,
    /// Texture filter for every image texture.
    pub filter: Option<Filter>,
    /// Pixel sampler.
    pub sampler: Option<PixelSampler>,
    /// EWA's largest anisotropy for every image texture.
    pub max_anisotropy: Option<f32>,
    /// Pixel reconstruction filter.
    pub pixel_filter: Option<PixelFilter>,
    /// Adaptive sampling on (`Some`); the preset's setting otherwise.
    pub adaptive: Option<AdaptiveDesc>,
    /// Turns adaptive sampling off whatever the preset says.
    pub no_adaptive: bool,
    /// Debug view.
    pub view: Option<View>,
}

/// Applies command-line overrides to a preset's render settings.
pub fn apply_overrides(desc: &mut SceneDesc, o: Overrides) {
    let r = &mut desc.render;
    r.width = o.width.unwrap_or(r.width);
    r.height = o.height.unwrap_or(r.height);
    r.spp = o.spp.unwrap_or(r.spp);
    r.seed = o.seed.unwrap_or(r.seed);
    r.sampler = o.sampler.unwrap_or(r.sampler);
    r.pixel_filter = o.pixel_filter.unwrap_or(r.pixel_filter);
    r.view = o.view.unwrap_or(r.view);
    if o.no_adaptive {
        r.adaptive = None;
    }
    if let Some(a) = o.adaptive {
        r.adaptive = Some(a);
    }
    for obj in &mut desc.objects {
        for (_, t) in obj.textures_mut() {
            match t {
                TextureDesc::Image {
                    filter,
                    max_anisotropy,
                    ..
                }
                | TextureDesc::UvGrid {
                    filter,
                    max_anisotropy,
                    ..
                }
                | TextureDesc::MeshMaterial {
                    filter,
                    max_anisotropy,
                    ..
                } => {
                    *filter = o.filter.unwrap_or(*filter);
                    *max_anisotropy = o.max_anisotropy.unwrap_or(*max_anisotropy);
                }
                TextureDesc::Checker { filter, .. } => *filter = o.filter.unwrap_or(*filter),
                // Point-sampled formulas have no filter.
                TextureDesc::Constant(_) | TextureDesc::Formula { .. } => {}
            }
        }
    }
}
