//! Error against time of each antialiasing mode on one preset.
//!
//! `cargo run --release --example aa_measure -- PRESET [--width 640 --height 480 --ref-spp 1024]`
//!
//! The reference is the preset rendered with the bilinear filter, box pixel filter and jittered
//! sampling at `--ref-spp` samples per pixel (cached in the system's temporary directory). Each
//! mode's RMSE is taken on display values in [0, 1] (exposure applied, sRGB-encoded, clipped:
//! what a viewer sees), over all pixels and channels; its time is the median of up to 3 renders
//! on the default rayon pool.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use texplore::math::linear_to_srgb;
use texplore::render::{Film, render_blocking};
use texplore::sampler::PixelSampler;
use texplore::scene::{
    AdaptiveDesc, AssetCache, Overrides, apply_overrides, build_scene, load_preset,
};
use texplore::texture::Filter;

struct Mode {
    filter: Filter,
    spp: u32,
    sampler: PixelSampler,
    adaptive: Option<u32>,
}

fn arg(args: &[String], name: &str, default: u32) -> u32 {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn render(preset: &Path, w: u32, h: u32, m: &Mode) -> (Film, f32, Duration) {
    let mut desc = load_preset(preset).expect("preset");
    apply_overrides(
        &mut desc,
        Overrides {
            width: Some(w),
            height: Some(h),
            spp: Some(m.spp),
            filter: Some(m.filter),
            sampler: Some(m.sampler),
            adaptive: m.adaptive.map(|max_spp| AdaptiveDesc {
                max_spp,
                threshold: 0.01,
            }),
            no_adaptive: m.adaptive.is_none(),
            ..Overrides::default()
        },
    );
    let scene = build_scene(&desc, preset, &mut AssetCache::new()).expect("scene");
    let mut times = Vec::new();
    let mut film = None;
    for _ in 0..3 {
        let t0 = Instant::now();
        let f = render_blocking(&scene, |_| {});
        times.push(t0.elapsed());
        film = Some(f);
        if times[0] > Duration::from_secs(2) {
            break;
        }
    }
    times.sort();
    let film = film.expect("rendered");
    let spp = (film.total_samples() / f64::from(w * h)) as f32;
    (film, spp, times[times.len() / 2])
}

fn display(film: &Film, exposure: f32) -> Vec<f32> {
    film.to_linear()
        .iter()
        .flat_map(|c| c.to_array())
        .map(|v| linear_to_srgb((v * exposure).clamp(0.0, 1.0)))
        .collect()
}

fn rmse(a: &[f32], b: &[f32]) -> f64 {
    let s: f64 = a.iter().zip(b).map(|(x, y)| f64::from(x - y).powi(2)).sum();
    (s / a.len() as f64).sqrt()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let preset = PathBuf::from(args.first().expect("usage: aa_measure PRESET [options]"));
    let (w, h) = (arg(&args, "--width", 640), arg(&args, "--height", 480));
    let ref_spp = arg(&args, "--ref-spp", 1024);
    let exposure = load_preset(&preset).expect("preset").render.exposure.exp2();
    let stem = preset
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into());
    let cache = std::env::temp_dir().join(format!("aa_ref_{stem}_{w}x{h}_{ref_spp}.f32"));
    let reference: Vec<f32> = if let Ok(bytes) = std::fs::read(&cache) {
        bytes
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect()
    } else {
        let m = Mode {
            filter: Filter::Bilinear,
            spp: ref_spp,
            sampler: PixelSampler::Jittered,
            adaptive: None,
        };
        let t0 = Instant::now();
        let mut desc = load_preset(&preset).expect("preset");
        apply_overrides(
            &mut desc,
            Overrides {
                width: Some(w),
                height: Some(h),
                spp: Some(m.spp),
                filter: Some(m.filter),
                sampler: Some(m.sampler),
                no_adaptive: true,
                ..Overrides::default()
            },
        );
        let scene = build_scene(&desc, &preset, &mut AssetCache::new()).expect("scene");
        let film = render_blocking(&scene, |_| {});
        eprintln!(
            "reference: {ref_spp} spp in {:.1} s",
            t0.elapsed().as_secs_f64()
        );
        let d = display(&film, exposure);
        let bytes: Vec<u8> = d.iter().flat_map(|v| v.to_le_bytes()).collect();
        let _ = std::fs::write(&cache, bytes);
        d
    };
    let modes = [
        (Filter::Nearest, 1, PixelSampler::Jittered, None),
        (Filter::Nearest, 4, PixelSampler::Jittered, None),
        (Filter::Nearest, 16, PixelSampler::Jittered, None),
        (Filter::Nearest, 64, PixelSampler::Jittered, None),
        (Filter::Bilinear, 1, PixelSampler::Jittered, None),
        (Filter::Bilinear, 16, PixelSampler::Jittered, None),
        (Filter::Bicubic, 1, PixelSampler::Jittered, None),
        (Filter::Trilinear, 1, PixelSampler::Jittered, None),
        (Filter::Trilinear, 1, PixelSampler::Regular, None),
        (Filter::Ewa, 1, PixelSampler::Jittered, None),
        (Filter::Ewa, 1, PixelSampler::Regular, None),
        (Filter::Ewa, 2, PixelSampler::MultiJittered, None),
        (Filter::Ewa, 1, PixelSampler::Regular, Some(16)),
        (Filter::Ewa, 2, PixelSampler::MultiJittered, Some(16)),
    ];
    println!(
        "{} at {w}x{h}; reference: bilinear, box, jittered, {ref_spp} spp",
        preset.display()
    );
    println!("| filter | sampler | spp (mean) | adaptive | RMSE | time (s) |");
    println!("|---|---|---|---|---|---|");
    for (filter, spp, sampler, adaptive) in modes {
        let m = Mode {
            filter,
            spp,
            sampler,
            adaptive,
        };
        let (film, mean_spp, t) = render(&preset, w, h, &m);
        let e = rmse(&display(&film, exposure), &reference);
        println!(
            "| {filter} | {sampler} | {mean_spp:.2} | {} | {e:.4} | {:.3} |",
            adaptive.map_or_else(|| "-".to_string(), |a| format!("max {a}")),
            t.as_secs_f64()
        );
    }
}
