//! The command line: `texplore` with no subcommand opens the window; the subcommands run the
//! same scenes headless. One file per subcommand.

mod bench;
mod image_info;
pub mod lesson;
mod map;
mod mesh_info;
mod probe;
mod render;
mod report;
mod snapshot;

use crate::scene::SimdMode;
use anyhow::Result;
use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// texplore: an interactive texture-mapping explorer on a progressive CPU ray tracer.
///
/// Without a subcommand it opens the window on the Earth.
#[derive(Debug, Parser)]
#[command(version, about, long_about = None, args_conflicts_with_subcommands = true)]
pub struct Cli {
    /// What to do (none: open the window).
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Preset or screenshot to open in the window (default: the Earth), or a link to a scene
    /// (`'https://.../#texplore1-...'`, from *File > Copy link to this scene*).
    #[arg(value_name = "FILE")]
    pub open: Option<PathBuf>,
    /// How wide the render kernel runs: `auto` (packets of rays as wide as the CPU's SIMD
    /// registers: 16 on AVX-512, 8 on AVX2, 4 on NEON and SSE2) or `scalar` (the same kernel one
    /// ray at a time, for comparison: the same pixels). Every command that renders and the
    /// window take it.
    #[arg(long, global = true, env = "TEXPLORE_SIMD", default_value = "auto", value_parser = parse_simd)]
    pub simd: SimdMode,
}

/// `--simd`: `auto` (or `on`, `1`, `true`) or `scalar` (or `off`, `0`, `false`).
fn parse_simd(s: &str) -> std::result::Result<SimdMode, String> {
    s.trim()
        .to_ascii_lowercase()
        .parse()
        .map_err(|_| format!("`{s}` is not a path: use auto or scalar"))
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a preset to a PNG (the preset is embedded in the PNG's text chunk).
    Render(render::RenderArgs),
    /// Compare every preset's render with its golden image in screenshots/ (or rewrite them).
    Snapshot(snapshot::SnapshotArgs),
    /// Print (u, v), column and row of a local hit point under a mapping: the lecture's formulas.
    Map(map::MapArgs),
    /// Turn an equirectangular panorama into a light-probe image.
    Probe(probe::ProbeArgs),
    /// Time full 1-spp passes and the first preview of a preset with 1, 2, ... threads.
    Bench(bench::BenchArgs),
    /// Print a mesh file's vertex and triangle counts, (u, v) and normals, bounding box and
    /// degenerate triangles.
    MeshInfo(mesh_info::MeshInfoArgs),
    /// Print an image file's size and how texplore stores it (`-o` writes the texels it read).
    ImageInfo(image_info::ImageInfoArgs),
    /// Speed against error: time each antialiasing mode and measure its error against a reference.
    Report(report::ReportArgs),
    /// Open the window on a guided lesson (`lessons/*.toml`), or list them with `--list`.
    Lesson(lesson::LessonArgs),
}

/// Runs a subcommand.
///
/// # Errors
/// Anything the subcommand reports, with context naming the file.
pub fn run(command: Command, simd: SimdMode) -> Result<()> {
    match command {
        Command::Render(a) => render::run(&a, simd),
        Command::Snapshot(a) => snapshot::run(&a, simd),
        Command::Map(a) => map::run(&a),
        Command::Probe(a) => probe::run(&a),
        Command::Bench(a) => bench::run(&a, simd),
        Command::MeshInfo(a) => mesh_info::run(&a),
        Command::ImageInfo(a) => image_info::run(&a),
        Command::Report(a) => report::run(&a, simd),
        // The binary opens the window on the lesson; here only the list can be shown.
        Command::Lesson(a) => match lesson::run(&a)? {
            None => Ok(()),
            Some(l) => anyhow::bail!("{}: opening a lesson needs the window", l.file.display()),
        },
    }
}

/// Most timed runs `--repeat` asks for.
pub const MAX_REPEAT: usize = 1000;
/// Most triangles `bench --mesh` generates (about 1 GB of mesh and BVH).
pub const MAX_BENCH_TRIANGLES: u32 = 1 << 23;
/// Longest `report --time-budget`, in seconds (a day).
pub const MAX_TIME_BUDGET: f64 = 86_400.0;

/// An integer option in `min..=max`, with a message naming the range.
fn parse_in_range<T>(s: &str, min: T, max: T) -> Result<T, String>
where
    T: std::str::FromStr + PartialOrd + std::fmt::Display + Copy,
{
    let n: T = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a whole number from {min} to {max}"))?;
    if n < min || n > max {
        return Err(format!("{n} is out of range ({min} to {max})"));
    }
    Ok(n)
}

/// `--threads`: 0 (one per core) to [`crate::render::MAX_THREADS`].
///
/// # Errors
/// Not a number, or above the limit.
pub fn parse_threads(s: &str) -> Result<usize, String> {
    parse_in_range(s, 0, crate::render::MAX_THREADS)
        .map_err(|e| format!("{e}: 0 means one thread per core"))
}

/// `--repeat`: 1 to [`MAX_REPEAT`].
///
/// # Errors
/// Not a number, or out of range.
pub fn parse_repeat(s: &str) -> Result<usize, String> {
    parse_in_range(s, 1, MAX_REPEAT)
}

/// `bench --mesh`: 8 to [`MAX_BENCH_TRIANGLES`].
///
/// # Errors
/// Not a number, or out of range.
pub fn parse_bench_triangles(s: &str) -> Result<u32, String> {
    parse_in_range(s, 8, MAX_BENCH_TRIANGLES)
}

/// Samples per pixel: 1 to [`crate::scene::MAX_SPP`].
///
/// # Errors
/// Not a number, or out of range.
pub fn parse_spp(s: &str) -> Result<u32, String> {
    parse_in_range(s, 1, crate::scene::MAX_SPP)
}

/// `report --time-budget`: seconds, 0 to [`MAX_TIME_BUDGET`].
///
/// # Errors
/// Not a number, not finite, or out of range.
pub fn parse_time_budget(s: &str) -> Result<f64, String> {
    let t: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number of seconds"))?;
    if !(0.0..=MAX_TIME_BUDGET).contains(&t) {
        return Err(format!(
            "{s} seconds is out of range (0 to {MAX_TIME_BUDGET})"
        ));
    }
    Ok(t)
}

/// `--width`, `--height`, `--size`, `--res`: 1 to [`crate::scene::MAX_RESOLUTION`] pixels.
///
/// # Errors
/// Not a number, or out of range.
pub fn parse_resolution(s: &str) -> Result<u32, String> {
    parse_in_range(s, 1, crate::scene::MAX_RESOLUTION)
}

/// A number that must be finite: "NaN is not a number", "inf is not finite".
///
/// # Errors
/// Not a number, NaN or an infinity.
pub fn parse_finite(s: &str) -> Result<f64, String> {
    let t = s.trim();
    let v: f64 = t.parse().map_err(|_| format!("'{s}' is not a number"))?;
    if v.is_nan() {
        Err(format!("'{t}' is not a number"))
    } else if v.is_infinite() {
        Err(format!("'{t}' is not finite"))
    } else {
        Ok(v)
    }
}

/// `render --max-aniso`: 1 to [`crate::texture::MAX_ANISOTROPY_LIMIT`].
///
/// # Errors
/// Not a finite number, or out of range.
pub fn parse_max_aniso(s: &str) -> Result<f32, String> {
    let max = crate::texture::MAX_ANISOTROPY_LIMIT;
    let v = parse_finite(s)?;
    if !(1.0..=f64::from(max)).contains(&v) {
        // Named as in a preset, where the same bound applies.
        return Err(format!("{v} is out of range: max_anisotropy is 1 to {max}"));
    }
    Ok(v as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_bounded_with_a_message() {
        assert_eq!(parse_threads("8"), Ok(8));
        assert_eq!(
            parse_threads("100000"),
            Err("100000 is out of range (0 to 1024): 0 means one thread per core".into())
        );
        assert_eq!(
            parse_bench_triangles("2000000000"),
            Err("2000000000 is out of range (8 to 8388608)".into())
        );
        assert!(parse_repeat("0").is_err());
        assert!(
            parse_spp("99999999999")
                .unwrap_err()
                .contains("not a whole number")
        );
        for bad in ["1e300", "NaN", "-1", "inf"] {
            assert!(parse_time_budget(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_time_budget("0.5"), Ok(0.5));
        assert_eq!(
            parse_resolution("0"),
            Err("0 is out of range (1 to 16384)".into())
        );
        assert_eq!(parse_finite("NaN"), Err("'NaN' is not a number".into()));
        assert_eq!(parse_finite("-inf"), Err("'-inf' is not finite".into()));
        assert_eq!(parse_finite("-7e-1"), Ok(-0.7));
        assert_eq!(parse_max_aniso("nan"), Err("'nan' is not a number".into()));
        assert_eq!(
            parse_max_aniso("0.5"),
            Err("0.5 is out of range: max_anisotropy is 1 to 64".into())
        );
    }
}
