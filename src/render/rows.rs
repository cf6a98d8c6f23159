//! One row of a pass through the render kernel ([`Scene::trace_lanes`]): the row's pixels in
//! chunks of 16 (their sample positions lane-wise where the sampler allows), each chunk traced
//! as packets of `S::F32_LANES` rays, `S` the instruction set [`pulp::Arch::dispatch`] picks at
//! run time (AVX-512, AVX2 + FMA, else SSE2; NEON on aarch64; simd128 in the page), or pulp's
//! `Scalar` (one ray a packet) under [`SimdMode::Scalar`]. Both are the same code, so a film is
//! the same whichever runs it.

use super::{
    MIN_FOOTPRINT_SCALE, Row, sample_cell, sample_position, sample_positions_lanes, uniform_cell,
};
use crate::math::lanes::{MAX_LANES, from_array, mask_from_array, mask_to_array, to_array};
use crate::math::{RayDifferential, Vec2, Vec3A};
use crate::scene::{Diffs, Rays, Scene, SimdMode};
use pulp::{Simd, WithSimd};

/// Pixels whose sample positions are made together (the sampler's lane-wise width).
pub const CHUNK: usize = 16;

/// The kernel's width under `mode` on this CPU: the rays in one packet.
#[must_use]
pub fn kernel_width(mode: SimdMode) -> usize {
    struct Width;
    impl WithSimd for Width {
        type Output = usize;
        #[inline(always)]
        fn with_simd<S: Simd>(self, _s: S) -> usize {
            S::F32_LANES
        }
    }
    match mode {
        SimdMode::Scalar => 1,
        SimdMode::Auto => pulp::Arch::new().dispatch(Width),
    }
}

/// The instruction set the kernel runs on here and its width, for `texplore bench`.
#[must_use]
pub fn simd_level(mode: SimdMode) -> String {
    let width = kernel_width(mode);
    if mode == SimdMode::Scalar {
        return "pulp's Scalar, 1 ray a packet (asked for)".to_owned();
    }
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    let name = match pulp::Arch::new() {
        pulp::Arch::V4(_) => "AVX-512 (x86-64-v4)",
        pulp::Arch::V3(_) => "AVX2 + FMA (x86-64-v3)",
        _ => "SSE2 (x86-64 baseline)",
    };
    #[cfg(target_arch = "aarch64")]
    let name = "NEON (aarch64)";
    #[cfg(target_arch = "wasm32")]
    let name = "WebAssembly simd128";
    #[cfg(not(any(
        target_arch = "x86",
        target_arch = "x86_64",
        target_arch = "aarch64",
        target_arch = "wasm32"
    )))]
    let name = "no SIMD dispatch on this architecture";
    format!("{name}, {width} rays a packet")
}

/// Traces row `y`'s pixels (where `mask` allows) for sample `sample` into `row`.
pub(super) fn render_row(
    scene: &Scene,
    row: &mut Row,
    y: u32,
    sample: u32,
    mask: Option<&[bool]>,
    mode: SimdMode,
) {
    let op = KernelRow {
        scene,
        row,
        y,
        sample,
        mask,
    };
    match mode {
        SimdMode::Scalar => Simd::vectorize(pulp::Scalar, op),
        SimdMode::Auto => pulp::Arch::new().dispatch(op),
    }
}

/// [`kernel_row`] as pulp's operation: `with_simd` is inlined into the `#[target_feature]`
/// function the dispatch picks, and everything below it is `#[inline(always)]`, so the kernel
/// is compiled for that instruction set.
struct KernelRow<'s, 'r, 'f> {
    scene: &'s Scene,
    row: &'r mut Row<'f>,
    y: u32,
    sample: u32,
    mask: Option<&'s [bool]>,
}

impl WithSimd for KernelRow<'_, '_, '_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, s: S) {
        kernel_row(s, self.scene, self.row, self.y, self.sample, self.mask);
    }
}

/// A register from `a`'s lanes from `at`.
#[inline(always)]
fn load_at<S: Simd>(a: &[f32; CHUNK], at: usize) -> crate::math::lanes::F<S> {
    S::as_simd_f32s(&a[at..at + S::F32_LANES]).0[0]
}

#[inline(always)]
fn kernel_row<S: Simd>(
    s: S,
    scene: &Scene,
    row: &mut Row,
    y: u32,
    sample: u32,
    mask: Option<&[bool]>,
) {
    let st = &scene.settings;
    let width = row.px.len();
    let w = S::F32_LANES;
    let footprints = scene.needs_differentials();
    for x0 in (0..width).step_by(CHUNK) {
        let active: [bool; CHUNK] = std::array::from_fn(|i| {
            let x = x0 + i;
            x < width && mask.is_none_or(|m| m[x])
        });
        if !active.contains(&true) {
            continue;
        }
        let (px, py) = sample_positions_lanes(st, x0 as u32, y, sample).unwrap_or_else(|| {
            let (mut px, mut py) = ([0.0_f32; CHUNK], [0.0_f32; CHUNK]);
            for i in 0..CHUNK {
                if active[i] {
                    let pos = sample_position(st, (x0 + i) as u32, y, sample);
                    (px[i], py[i]) = (pos.x, pos.y);
                }
            }
            (px, py)
        });
        // Each lane's cell, where a texture is filtered over the sample's footprint: usually
        // one for the whole chunk (see `uniform_cell`).
        let cells: [Vec2; CHUNK] = if footprints {
            uniform_cell(st, sample).map_or_else(
                || {
                    std::array::from_fn(|i| {
                        if active[i] {
                            sample_cell(st, (x0 + i) as u32, y, sample)
                        } else {
                            Vec2::ZERO
                        }
                    })
                },
                |c| [c; CHUNK],
            )
        } else {
            [Vec2::ZERO; CHUNK]
        };
        for sub in (0..CHUNK).step_by(w) {
            let mut on = [false; MAX_LANES];
            on[..w].copy_from_slice(&active[sub..sub + w]);
            if !on.contains(&true) {
                continue;
            }
            let mut diffs_buf: Option<Diffs> = None;
            let rays = if footprints {
                let blank = RayDifferential {
                    rx_origin: Vec3A::ZERO,
                    rx_dir: Vec3A::Z,
                    ry_origin: Vec3A::ZERO,
                    ry_dir: Vec3A::Z,
                };
                let (cx, cy): ([f32; MAX_LANES], [f32; MAX_LANES]) = (
                    std::array::from_fn(|i| cells.get(sub + i).map_or(1.0, |c| c.x)),
                    std::array::from_fn(|i| cells.get(sub + i).map_or(1.0, |c| c.y)),
                );
                let r = scene.camera.footprint_rays_lanes(
                    s,
                    load_at::<S>(&px, sub),
                    load_at::<S>(&py, sub),
                    from_array::<S>(&cx),
                    from_array::<S>(&cy),
                    MIN_FOOTPRINT_SCALE,
                );
                let (rxo, rxd, ryo, ryd) = (
                    r.rx_origin.to_arrays(),
                    r.rx_dir.to_arrays(),
                    r.ry_origin.to_arrays(),
                    r.ry_dir.to_arrays(),
                );
                let v = |a: &[[f32; MAX_LANES]; 3], i: usize| Vec3A::new(a[0][i], a[1][i], a[2][i]);
                let d: Diffs = std::array::from_fn(|i| {
                    if i < w && on[i] {
                        RayDifferential {
                            rx_origin: v(&rxo, i),
                            rx_dir: v(&rxd, i),
                            ry_origin: v(&ryo, i),
                            ry_dir: v(&ryd, i),
                        }
                    } else {
                        blank
                    }
                });
                let seen = s.and_m32s(r.seen, mask_from_array(s, &on));
                diffs_buf = Some(d);
                Rays {
                    o: r.o,
                    d: r.d,
                    active: seen,
                }
            } else {
                let (o, d, seen) =
                    scene
                        .camera
                        .rays_lanes(s, load_at::<S>(&px, sub), load_at::<S>(&py, sub));
                Rays {
                    o,
                    d,
                    active: s.and_m32s(seen, mask_from_array(s, &on)),
                }
            };
            let traced = scene.trace_lanes(s, &rays, diffs_buf.as_ref());
            let traced_on = mask_to_array(s, rays.active);
            let rgb = traced.rgb.map(to_array::<S>);
            for i in 0..w {
                if !on[i] {
                    continue;
                }
                if traced_on[i] {
                    // Straight from the lanes: no Rgb through memory.
                    row.add_parts(
                        sub + x0 + i,
                        rgb[0][i],
                        rgb[1][i],
                        rgb[2][i],
                        traced.keys[i],
                    );
                } else {
                    // The camera has no ray here (outside a fisheye's disc): black.
                    row.add_parts(sub + x0 + i, 0.0, 0.0, 0.0, 0);
                }
            }
        }
    }
}
