//! `texplore map`: the lecture's formulas as a teaching tool.

use crate::mapping::{Mapping, explain_mapping_f64};
use crate::names::Named as _;
use crate::names::value_parser;
use crate::texture::{Lookup, Wrap, explain_lookup, explain_wrap};
use glam::DVec3;

/// `texplore map`.
#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct MapArgs {
    /// Which formula turns the hit point into (u, v).
    #[arg(value_parser = value_parser::<Mapping>())]
    pub mapping: Mapping,
    /// Local hit point x (read as f64: the formulas are worked in f64).
    #[arg(allow_hyphen_values = true, value_parser = super::parse_finite)]
    pub x: f64,
    /// Local hit point y.
    #[arg(allow_hyphen_values = true, value_parser = super::parse_finite)]
    pub y: f64,
    /// Local hit point z.
    #[arg(allow_hyphen_values = true, value_parser = super::parse_finite)]
    pub z: f64,
    /// Texture resolution for the column and row (hres vres).
    #[arg(long, num_args = 2, value_names = ["W", "H"], default_values_t = [2048, 1024], value_parser = super::parse_resolution)]
    pub res: Vec<u32>,
    /// How u and v become the printed column and row.
    #[arg(long, default_value_t = Lookup::Centred, value_parser = value_parser::<Lookup>())]
    pub lookup: Lookup,
    /// The texture's wrap mode for coordinates outside [0, 1]: repeat, clamp, mirror or black
    /// (u = 1 and v = 1 are inside). Cylindrical and spherical u always repeat across the seam,
    /// spherical v always clamps, as in the renderer.
    #[arg(long, default_value_t = Wrap::Repeat, value_parser = value_parser::<Wrap>())]
    pub wrap: Wrap,
    /// Print one JSON object: u, v (before wrapping), column, row (row counted from the bottom,
    /// as v; null outside [0, 1] under wrap black).
    #[arg(long)]
    pub json: bool,
}

/// Prints the mapping's formulas and the texel (or the JSON object); every input was checked
/// by the argument parsers, so nothing here fails.
pub fn run(a: &MapArgs) {
    let (hres, vres) = (a.res[0], a.res[1]);
    // f64 throughout: the lecture's arithmetic as written, not the renderer's f32 rounding.
    let p = DVec3::new(a.x, a.y, a.z);
    let lookup = a.lookup;
    let (mapping_lines, uv) = explain_mapping_f64(a.mapping, p);
    // The wraps the renderer applies: the texture's, except across a periodic mapping's seam
    // (repeat) and at the spherical map's poles (clamp).
    let wraps = Wrap::for_mapping(a.mapping, a.wrap);
    let (wrapped, wrap_lines) = explain_wrap(uv.x, uv.y, wraps);
    let texel = wrapped.map(|(u, v)| (lookup.index(u, hres), lookup.index(v, vres)));
    if a.json {
        let out = serde_json::json!({
            "mapping": a.mapping.name(),
            "point": [a.x, a.y, a.z],
            "u": uv.x,
            "v": uv.y,
            "wrap": a.wrap.to_string(),
            "column": texel.map(|t| t.0),
            "row": texel.map(|t| t.1),
            "file_row": texel.map(|t| vres - 1 - t.1),
            "lookup": lookup.name(),
            "res": [hres, vres],
        });
        println!("{out}");
        return;
    }
    println!(
        "{} mapping of the local hit point ({}, {}, {}):",
        a.mapping,
        shortest(a.x),
        shortest(a.y),
        shortest(a.z)
    );
    for line in mapping_lines {
        println!("  {line}");
    }
    for line in wrap_lines {
        println!("  {line}");
    }
    println!(
        "texel in a {hres} x {vres} image ({} lookup):",
        lookup.name()
    );
    match (wrapped, texel) {
        (Some((u, v)), Some((_, row))) => {
            for line in explain_lookup(u, v, hres, vres, lookup) {
                println!("  {line}");
            }
            println!(
                "  (row counts from the bottom, as v does; the file's row from the top is {})",
                vres - 1 - row
            );
        }
        _ => println!("  none: the texture reads black outside [0, 1] under wrap black"),
    }
}

/// A coordinate as typed, in the shortest form that reads back the same (5e-324 stays 5e-324,
/// not 324 digits of zeros).
fn shortest(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !a.is_finite() || (1e-4..1e6).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
