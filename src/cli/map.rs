//! `texplore map`: the lecture's formulas as a teaching tool.

use crate::mapping::{Mapping, explain_lookup, explain_mapping};
use crate::math::Vec3A;
use crate::names::value_parser;
use crate::texture::Lookup;
use anyhow::{Result, bail};

/// `texplore map`.
#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct MapArgs {
    /// The mapping.
    #[arg(value_parser = value_parser::<Mapping>())]
    pub mapping: Mapping,
    /// Local hit point x.
    pub x: f32,
    /// Local hit point y.
    pub y: f32,
    /// Local hit point z.
    pub z: f32,
    /// Texture resolution for the column and row (hres vres).
    #[arg(long, num_args = 2, value_names = ["W", "H"], default_values_t = [2048, 1024])]
    pub res: Vec<u32>,
    /// Texel lookup.
    #[arg(long, default_value_t = Lookup::Centred, value_parser = value_parser::<Lookup>())]
    pub lookup: Lookup,
    /// Print one JSON object: u, v, column, row (row counted from the bottom, as v).
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: &MapArgs) -> Result<()> {
    let (hres, vres) = (a.res[0], a.res[1]);
    if hres == 0 || vres == 0 {
        bail!("--res must be at least 1 x 1");
    }
    let p = Vec3A::new(a.x, a.y, a.z);
    let lookup = a.lookup;
    let uv = a.mapping.map_point(p).uv;
    let wrapped = |t: f32| {
        if a.mapping == Mapping::Rectangular {
            t - t.floor()
        } else {
            t.clamp(0.0, 1.0)
        }
    };
    let (u, v) = (wrapped(uv.x), wrapped(uv.y));
    let (column, row) = (lookup.index(u, hres), lookup.index(v, vres));
    if a.json {
        let out = serde_json::json!({
            "mapping": a.mapping.name(),
            "point": [a.x, a.y, a.z],
            "u": uv.x,
            "v": uv.y,
            "column": column,
            "row": row,
            "file_row": vres - 1 - row,
            "lookup": lookup.name(),
            "res": [hres, vres],
        });
        println!("{out}");
        return Ok(());
    }
    println!(
        "{} mapping of the local hit point ({}, {}, {}):",
        a.mapping, a.x, a.y, a.z
    );
    for line in explain_mapping(a.mapping, p) {
        println!("  {line}");
    }
    if (u, v) != (uv.x, uv.y) {
        println!("  wrapped (repeat) into [0, 1]: u = {u:.4}, v = {v:.4}");
    }
    println!(
        "texel in a {hres} x {vres} image ({} lookup):",
        lookup.name()
    );
    for line in explain_lookup(u, v, hres, vres, lookup) {
        println!("  {line}");
    }
    println!(
        "  (row counts from the bottom, as v does; the file's row from the top is {})",
        vres - 1 - row
    );
    Ok(())
}
