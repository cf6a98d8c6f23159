//! The command line: `texplore` with no subcommand opens the window; the subcommands run the
//! same scenes headless. One file per subcommand.

mod bench;
mod map;
mod mesh_info;
mod probe;
mod render;
mod report;
mod snapshot;

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
    /// Preset or screenshot to open in the window (default: the Earth).
    #[arg(value_name = "FILE")]
    pub open: Option<PathBuf>,
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
    /// Speed against error: time each antialiasing mode and measure its error against a reference.
    Report(report::ReportArgs),
}

/// Runs a subcommand.
///
/// # Errors
/// Anything the subcommand reports, with context naming the file.
pub fn run(command: Command) -> Result<()> {
    match command {
        Command::Render(a) => render::run(&a),
        Command::Snapshot(a) => snapshot::run(&a),
        Command::Map(a) => map::run(&a),
        Command::Probe(a) => probe::run(&a),
        Command::Bench(a) => bench::run(&a),
        Command::MeshInfo(a) => mesh_info::run(&a),
        Command::Report(a) => report::run(&a),
    }
}
