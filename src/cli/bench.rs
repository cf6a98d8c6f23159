//! `texplore bench`: full-pass and preview timings per thread count.

use crate::geometry::Mesh;
use crate::render::{
    Film, PREVIEW_BLOCKS, SimdMode, render_pass_with, render_preview_into, simd_level, thread_pool,
};
use crate::scene::{
    AssetCache, Overrides, apply_overrides, build_scene, parse_preset, read_preset_or_png,
};
use anyhow::Result;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// `texplore bench`.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// The preset.
    #[arg(required_unless_present = "mesh")]
    pub preset: Option<PathBuf>,
    /// Instead of a preset: a generated bumpy sphere of about this many triangles (with UVs)
    /// filling the view; also reports the BVH build time and bytes per triangle.
    #[arg(long, value_name = "TRIANGLES", conflicts_with = "preset", value_parser = super::parse_bench_triangles)]
    pub mesh: Option<u32>,
    /// With `--mesh`: the light casts shadows (one shadow ray per pixel through the BVH).
    #[arg(long, requires = "mesh")]
    pub shadows: bool,
    /// Image width.
    #[arg(long, default_value_t = 800, value_parser = super::parse_resolution)]
    pub width: u32,
    /// Image height.
    #[arg(long, default_value_t = 800, value_parser = super::parse_resolution)]
    pub height: u32,
    /// Thread counts to measure.
    #[arg(long, value_delimiter = ',', default_values_t = [1, 2], value_parser = super::parse_threads)]
    pub threads: Vec<usize>,
    /// Timed passes per thread count (after one warm-up); the median is reported.
    #[arg(long, default_value_t = 9, value_parser = super::parse_repeat)]
    pub repeat: usize,
    /// Run the kernel one ray a packet instead of at the CPU's SIMD width, for comparison
    /// (`TEXPLORE_SIMD=scalar` does the same for every command).
    #[arg(long)]
    pub scalar: bool,
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

/// The generated mesh scene: its BVH built (and timed) once per thread count.
fn mesh_scene(a: &BenchArgs, triangles: u32) -> Result<(crate::scene::SceneDesc, AssetCache)> {
    let rings = ((f64::from(triangles) / 4.0).sqrt().round() as u32).max(2) + 1;
    let data = crate::meshio::bumpy_sphere(2 * (rings - 1), rings, 0.03);
    let path = Path::new("generated-sphere");
    println!(
        "generated sphere: {} vertices, {} triangles",
        data.positions.len(),
        data.triangles.len()
    );
    let mut mesh = None;
    for &threads in &a.threads {
        let pool = thread_pool(threads)?;
        let mut times = Vec::new();
        let mut cpu = Vec::new();
        for _ in 0..3 {
            let d = data.clone();
            let (t0, c0) = (Instant::now(), process_cpu_seconds());
            let m = pool.install(|| Mesh::new(d, path))?;
            times.push(t0.elapsed());
            if let (Some(c0), Some(c1)) = (c0, process_cpu_seconds()) {
                cpu.push(Duration::from_secs_f64(c1 - c0));
            }
            mesh = Some(m);
        }
        let cpu = if cpu.len() == 3 {
            format!(", {:.0} ms of CPU time", median(cpu).as_secs_f64() * 1e3)
        } else {
            String::new()
        };
        println!(
            "threads {threads}: BVH build (with vertex normals) {:.0} ms{cpu} (median of 3)",
            median(times).as_secs_f64() * 1e3
        );
    }
    let mesh = mesh.map_or_else(|| Mesh::new(data, path), Ok)?;
    println!(
        "memory: {:.1} bytes per triangle (mesh + BVH of {} nodes)",
        mesh.bytes_per_triangle(),
        mesh.bvh_nodes()
    );
    let mut cache = AssetCache::new();
    cache.insert_mesh(path, Arc::new(mesh));
    let text = format!(
        "(version: 1, camera: (eye: (0, 0, 2.2), projection: Pinhole(fov: 36)),
          ambient: (ls: 0.3), lights: [Directional(direction: (1, 1, 2), shadows: {})],
          objects: [(shape: Mesh(path: \"generated-sphere\", shading: Smooth),
                     material: Matte(cd: UvGrid(mapping: Uv, filter: Bilinear)))])",
        a.shadows
    );
    Ok((parse_preset(&text, Path::new("generated"))?, cache))
}

pub fn run(a: &BenchArgs, simd: SimdMode) -> Result<()> {
    let (mut desc, preset, mut cache) = match (&a.preset, a.mesh) {
        (_, Some(n)) => {
            let (desc, cache) = mesh_scene(a, n)?;
            (desc, PathBuf::from("generated"), cache)
        }
        (Some(p), None) => (read_preset_or_png(p)?, p.clone(), AssetCache::new()),
        (None, None) => anyhow::bail!("name a preset or --mesh TRIANGLES"),
    };
    apply_overrides(
        &mut desc,
        Overrides {
            width: Some(a.width),
            height: Some(a.height),
            spp: Some(1),
            ..Overrides::default()
        },
    );
    let scene = build_scene(&desc, &preset, &mut cache)?;
    let rays = f64::from(a.width) * f64::from(a.height);
    println!(
        "{} at {}x{}, 1 spp, median of {} passes after a warm-up",
        preset.display(),
        a.width,
        a.height,
        a.repeat.max(1)
    );
    let mode = if a.scalar { SimdMode::Scalar } else { simd };
    println!("kernel: {}", simd_level(mode));
    let mut base = None;
    for &threads in &a.threads {
        let pool = thread_pool(threads)?;
        let never = || false;
        let passes = pool.install(|| {
            // One film and one preview buffer for every pass: the timings measure tracing,
            // not the allocator and the kernel clearing fresh pages.
            let mut film = Film::new(a.width, a.height);
            let mut preview = Vec::new();
            let _ = render_pass_with(&scene, &mut film, 0, None, mode, &never);
            let mut passes = Vec::new();
            let mut previews = Vec::new();
            let mut cpu = Some(0.0);
            for i in 0..a.repeat.max(1) {
                let (t0, c0) = (Instant::now(), process_cpu_seconds());
                let _ = render_pass_with(&scene, &mut film, i as u32, None, mode, &never);
                passes.push(t0.elapsed());
                cpu = match (cpu, c0, process_cpu_seconds()) {
                    (Some(sum), Some(c0), Some(c1)) => Some(sum + c1 - c0),
                    _ => None,
                };
                let t0 = Instant::now();
                let _ = render_preview_into(&scene, PREVIEW_BLOCKS[0], &mut preview, &never);
                previews.push(t0.elapsed());
            }
            (passes, previews, cpu)
        });
        let (passes, previews, cpu) = (passes.0, passes.1, passes.2);
        let n_passes = passes.len() as f64;
        let (pass, preview) = (median(passes), median(previews));
        let rate = rays / pass.as_secs_f64();
        let speedup = base.map_or(1.0, |b: f64| rate / b);
        base.get_or_insert(rate);
        println!(
            "threads {threads}: pass {:.2} ms, {:.1} M primary rays/s (x{speedup:.2}), first preview ({block}x{block} blocks) {:.2} ms",
            pass.as_secs_f64() * 1e3,
            rate / 1e6,
            preview.as_secs_f64() * 1e3,
            block = PREVIEW_BLOCKS[0],
        );
        if let Some(cpu) = cpu.filter(|c| *c > 0.0) {
            // On a shared machine wall time includes waiting for a core; CPU time does not.
            println!(
                "           {:.1} M primary rays per CPU-second (process CPU time over all passes)",
                rays * n_passes / cpu / 1e6
            );
        }
    }
    Ok(())
}

/// CPU seconds (user + system) this process has used, from `/proc/self/stat` (Linux; `None`
/// elsewhere). Ticks are USER_HZ = 100 on every Linux.
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let rest = &stat[stat.rfind(')')? + 1..];
    let fields: Vec<&str> = rest.split_ascii_whitespace().collect();
    let ticks = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}
