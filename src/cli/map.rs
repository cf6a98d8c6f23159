//! `texplore map`: the lecture's formulas as a teaching tool, and a student's own
//! (`texplore map formula --u ... --v ...`), compared with a built-in mapping (`--compare`).

use crate::mapping::formula::compare::{Verdict, difference, one_texel, sample_points, share_of};
use crate::mapping::formula::inputs_of;
use crate::mapping::{FormulaError, FormulaMapping, Mapping, explain_mapping_f64, map_uv_f64};
use crate::names::Named as _;
use crate::names::value_parser;
use crate::texture::{Lookup, Wrap, explain_lookup, explain_wrap};
use anyhow::Result;
use glam::{DVec2, DVec3};

/// Which mapping `texplore map` works: a built-in one, or the `formula` given by --u and --v.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapChoice {
    /// One of the lecture's mappings.
    Builtin(Mapping),
    /// `--u` and `--v`.
    Formula,
}

/// A mapping's name, or `formula`.
///
/// # Errors
/// Neither, listing the names.
pub fn parse_map_choice(s: &str) -> Result<MapChoice, String> {
    if s.trim().eq_ignore_ascii_case("formula") {
        return Ok(MapChoice::Formula);
    }
    s.trim()
        .parse::<Mapping>()
        .map(MapChoice::Builtin)
        .map_err(|_| {
            let names: Vec<&str> = <Mapping as strum::VariantArray>::VARIANTS
                .iter()
                .map(|m| m.name())
                .collect();
            format!(
                "'{s}' is not a mapping: {}, or formula (with --u and --v)",
                names.join(", ")
            )
        })
}

/// `texplore map`.
#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct MapArgs {
    /// Which formula turns the hit point into (u, v): a built-in mapping, or `formula` with
    /// --u and --v (your own).
    #[arg(value_parser = parse_map_choice)]
    pub mapping: MapChoice,
    /// Local hit point x (read as f64: the formulas are worked in f64).
    #[arg(allow_hyphen_values = true, value_parser = super::parse_finite)]
    pub x: f64,
    /// Local hit point y.
    #[arg(allow_hyphen_values = true, value_parser = super::parse_finite)]
    pub y: f64,
    /// Local hit point z.
    #[arg(allow_hyphen_values = true, value_parser = super::parse_finite)]
    pub z: f64,
    /// The u formula of `formula`, over x, y, z, mesh_u, mesh_v, pi and tau.
    #[arg(long, allow_hyphen_values = true)]
    pub u: Option<String>,
    /// The v formula of `formula`.
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<String>,
    /// The values of mesh_u and mesh_v (default: the spherical map's (u, v) of the point, the
    /// sphere's own coordinates).
    #[arg(long, num_args = 2, value_names = ["U", "V"], allow_hyphen_values = true, value_parser = super::parse_finite)]
    pub mesh_uv: Option<Vec<f64>>,
    /// Also work this built-in mapping, print the difference, and (for a formula) the share of
    /// the lecture's points where the two agree within one texel of --res, u and v judged
    /// alone, and the hint the window gives: which formula agrees and what is wrong, then the
    /// fix.
    #[arg(long, value_parser = value_parser::<Mapping>())]
    pub compare: Option<Mapping>,
    /// Texture resolution for the column and row (hres vres).
    #[arg(long, num_args = 2, value_names = ["W", "H"], default_values_t = [2048, 1024], value_parser = super::parse_resolution)]
    pub res: Vec<u32>,
    /// How u and v become the printed column and row.
    #[arg(long, default_value_t = Lookup::Centred, value_parser = value_parser::<Lookup>())]
    pub lookup: Lookup,
    /// The texture's wrap mode for coordinates outside [0, 1]: repeat, clamp, mirror or black
    /// (u = 1 and v = 1 are inside). Cylindrical and spherical u always repeat across the seam,
    /// spherical v always clamps, as in the renderer; a formula's follow this mode.
    #[arg(long, default_value_t = Wrap::Repeat, value_parser = value_parser::<Wrap>())]
    pub wrap: Wrap,
    /// Print one JSON object: u, v (before wrapping), column, row (row counted from the bottom,
    /// as v; null outside [0, 1] under wrap black).
    #[arg(long)]
    pub json: bool,
}

/// The mapping worked: a built-in one, or the compiled formula.
enum Chosen {
    Builtin(Mapping),
    Formula(Box<FormulaMapping>),
}

/// The compiled formula of `formula`, or the built-in mapping; a formula's mistake in full.
fn chosen(a: &MapArgs) -> Result<Chosen> {
    match (a.mapping, &a.u, &a.v) {
        (MapChoice::Builtin(m), None, None) => Ok(Chosen::Builtin(m)),
        (MapChoice::Builtin(m), _, _) => {
            anyhow::bail!("--u and --v are for `formula`, not the built-in {m} mapping")
        }
        (MapChoice::Formula, Some(u), Some(v)) => FormulaMapping::new(u, v)
            .map(|f| Chosen::Formula(Box::new(f)))
            .map_err(|e| anyhow::anyhow!(formula_error(&e))),
        (MapChoice::Formula, _, _) => {
            anyhow::bail!(
                "formula needs both --u and --v, e.g. --u \"fract(atan2(x, z) / tau)\" --v \"1 - acos(y) / pi\""
            )
        }
    }
}

/// A formula's mistake as the terminal shows it: the message, the formula and a caret.
fn formula_error(e: &FormulaError) -> String {
    match e.pointer() {
        Some(p) => format!("--{e}\n  {}", p.replace('\n', "\n  ")),
        None => format!("--{e}"),
    }
}

/// Prints the mapping's formulas and the texel (or the JSON object).
///
/// # Errors
/// A formula that does not compile, or --u/--v without `formula`.
pub fn run(a: &MapArgs) -> Result<()> {
    let (hres, vres) = (a.res[0], a.res[1]);
    // f64 throughout: the lecture's arithmetic as written, not the renderer's f32 rounding.
    let p = DVec3::new(a.x, a.y, a.z);
    let lookup = a.lookup;
    let chosen = chosen(a)?;
    let mesh = match &a.mesh_uv {
        Some(m) => DVec2::new(m[0], m[1]),
        None => map_uv_f64(Mapping::Spherical, p),
    };
    let (name, mapping_lines, uv, wraps) = match &chosen {
        Chosen::Formula(f) => {
            let (lines, uv) = f.explain(&inputs_of(p, mesh));
            ("formula".to_owned(), lines, uv, (a.wrap, a.wrap))
        }
        Chosen::Builtin(m) => {
            let m = *m;
            let (lines, uv) = explain_mapping_f64(m, p);
            // The wraps the renderer applies: the texture's, except across a periodic
            // mapping's seam (repeat) and at the spherical map's poles (clamp).
            (m.to_string(), lines, uv, Wrap::for_mapping(m, a.wrap))
        }
    };
    let formula = match &chosen {
        Chosen::Formula(f) => Some(f),
        Chosen::Builtin(_) => None,
    };
    let (wrapped, wrap_lines) = explain_wrap(uv.x, uv.y, wraps);
    let texel = wrapped.map(|(u, v)| (lookup.index(u, hres), lookup.index(v, vres)));
    let compared = a.compare.map(|m| {
        let (lines, other) = explain_mapping_f64(m, p);
        (m, lines, other, difference(m, uv, other))
    });
    let tol = one_texel(hres, vres);
    let checked = match (formula, a.compare) {
        (Some(f), Some(m)) => {
            let points = sample_points(m, 64);
            Some(Verdict::judge(f, m, &points, tol))
        }
        _ => None,
    };
    if a.json {
        let mut out = serde_json::json!({
            "mapping": name,
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
        if let Some(f) = formula {
            out["formula"] = serde_json::json!({
                "u": f.u().text(),
                "v": f.v().text(),
                "mesh_uv": [mesh.x, mesh.y],
                "derivatives": match f.derivative_kind() {
                    crate::mapping::DerivativeKind::Symbolic => "symbolic",
                    crate::mapping::DerivativeKind::FiniteDifferences => "finite-differences",
                },
            });
        }
        if let Some((m, _, other, d)) = &compared {
            out["compare"] = serde_json::json!({
                "mapping": m.name(),
                "u": other.x,
                "v": other.y,
                "du": d.x,
                "dv": d.y,
            });
            if let Some(verdict) = &checked {
                let agree = &verdict.agreement;
                let hint = verdict.hint(*m);
                out["compare"]["agreement"] = serde_json::json!(agree.share());
                out["compare"]["u_agreement"] =
                    serde_json::json!(share_of(verdict.u_agreeing, agree.points));
                out["compare"]["v_agreement"] =
                    serde_json::json!(share_of(verdict.v_agreeing, agree.points));
                out["compare"]["points"] = serde_json::json!(agree.points);
                out["compare"]["non_finite"] = serde_json::json!(agree.non_finite);
                out["compare"]["hints"] = verdict.mistakes().iter().map(|k| k.hint(*m)).collect();
                out["compare"]["hint"] = serde_json::json!(hint.as_ref().map(|h| &h.what));
                out["compare"]["fix"] =
                    serde_json::json!(hint.as_ref().and_then(|h| h.fix.as_ref()));
            }
        }
        println!("{out}");
        return Ok(());
    }
    println!(
        "{name} mapping of the local hit point ({}, {}, {}):",
        shortest(a.x),
        shortest(a.y),
        shortest(a.z)
    );
    if formula.is_some_and(|f| f.reads_mesh()) {
        println!(
            "  mesh_u = {}, mesh_v = {}",
            shortest(mesh.x),
            shortest(mesh.y)
        );
    }
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
    if let Some((m, lines, _, d)) = compared {
        println!("compared with the {m} mapping:");
        for line in lines {
            println!("  {line}");
        }
        let n = crate::mapping::explain_number;
        println!(
            "  difference: |du| = {}, |dv| = {} ({} and {} texels of {hres} x {vres}{})",
            n(d.x),
            n(d.y),
            n(d.x * f64::from(hres)),
            n(d.y * f64::from(vres)),
            if m.u_is_periodic() {
                "; u compared modulo 1, across the seam"
            } else {
                ""
            }
        );
        if let Some(verdict) = checked {
            print_check(m, &verdict);
        }
    }
    Ok(())
}

/// The agreement over the lecture's points, u and v alone, and the hint's two steps (the
/// window's words).
fn print_check(m: Mapping, verdict: &Verdict) {
    let n = crate::mapping::explain_number;
    let agree = &verdict.agreement;
    println!(
        "  over {} points of the {m} map's surface: {:.1} % agree within one texel (largest |du| = {}, |dv| = {}){}",
        agree.points,
        100.0 * agree.share(),
        n(agree.max_difference.x),
        n(agree.max_difference.y),
        if agree.non_finite > 0 {
            format!("; {} points give NaN or infinity", agree.non_finite)
        } else {
            String::new()
        }
    );
    if verdict.correct() {
        return;
    }
    println!(
        "  u alone agrees at {:.1} % of them, v at {:.1} %",
        100.0 * share_of(verdict.u_agreeing, agree.points),
        100.0 * share_of(verdict.v_agreeing, agree.points)
    );
    if let Some(h) = verdict.hint(m) {
        println!("  hint: {}", h.what);
        if let Some(fix) = h.fix {
            println!("  fix: {fix}");
        }
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
