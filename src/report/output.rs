//! Writing a report's files: `report.csv`, `report.md`, and per scene the error-against-time
//! plot (SVG and PNG) and the heat maps.

use super::{ReportError, SceneReport, plot, table};
use std::path::{Path, PathBuf};

/// A name safe as a file name: letters, digits, `-`, `_` and `.` kept, anything else `_`.
#[must_use]
pub fn file_safe(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with('.') {
        format!("_{s}")
    } else {
        s
    }
}

/// `names` with a repeated one numbered (`earth`, `earth_2`), so no two scenes write into
/// one folder (two names can become one file name, `a b` and `a_b`).
fn unique(names: Vec<String>) -> Vec<String> {
    let mut out: Vec<String> = Vec::with_capacity(names.len());
    for n in names {
        let mut candidate = n.clone();
        let mut k = 1;
        while out.contains(&candidate) {
            k += 1;
            candidate = format!("{n}_{k}");
        }
        out.push(candidate);
    }
    out
}

/// Every report file goes through the one atomic writer (see [`crate::output`]).
fn write(path: &Path, bytes: &[u8]) -> Result<(), ReportError> {
    crate::output::write_bytes(path, &[], bytes).map_err(ReportError::Scene)
}

fn png(path: &Path, width: u32, height: u32, rgb: &[u8]) -> Result<(), ReportError> {
    crate::texture::save_png(path, width, height, rgb, &[]).map_err(ReportError::Scene)
}

/// A plot that could not be drawn, naming the file it was for.
fn plotting(path: &Path, e: &plot::PlotError) -> ReportError {
    ReportError::Invalid(format!("{}: {e}", path.display()))
}

/// Writes every file of `reports` into `dir` (created if missing) and returns their paths.
/// `header` opens `report.md` (the command line, the machine, the load).
///
/// # Errors
/// A file cannot be written.
pub fn write_outputs(
    dir: &Path,
    reports: &[SceneReport],
    header: &str,
) -> Result<Vec<PathBuf>, ReportError> {
    std::fs::create_dir_all(dir).map_err(|e| ReportError::io(dir, e))?;
    let mut written = Vec::new();
    let csv = dir.join("report.csv");
    let text =
        table::csv(reports).map_err(|e| ReportError::Invalid(format!("{}: {e}", csv.display())))?;
    write(&csv, text.as_bytes())?;
    written.push(csv);
    let mut md = format!("# Speed against error\n\n{header}\n");
    let names = unique(reports.iter().map(|r| file_safe(&r.scene)).collect());
    for (rep, name) in reports.iter().zip(names) {
        let sub = dir.join(&name);
        std::fs::create_dir_all(&sub).map_err(|e| ReportError::io(&sub, e))?;
        let chart = plot::error_vs_time(rep);
        let svg = sub.join("error_vs_time.svg");
        write(
            &svg,
            chart.to_svg().map_err(|e| plotting(&svg, &e))?.as_bytes(),
        )?;
        let png_path = sub.join("error_vs_time.png");
        let rgb = chart.to_rgb().map_err(|e| plotting(&png_path, &e))?;
        png(&png_path, plot::CHART_WIDTH, plot::CHART_HEIGHT, &rgb)?;
        written.extend([svg, png_path]);
        #[cfg(feature = "flip")]
        let heat_maps = heat_maps(rep, &sub, &name, &mut written)?;
        // Without FLIP (`flip` feature off) a report has no error maps.
        #[cfg(not(feature = "flip"))]
        let heat_maps = Vec::new();
        let files = table::SceneFiles {
            plot_svg: Some(format!("{name}/error_vs_time.svg")),
            plot_png: Some(format!("{name}/error_vs_time.png")),
            heat_maps,
        };
        md.push_str(&table::markdown_scene(rep, &files));
    }
    md.push_str(&table::metrics_section());
    let md_path = dir.join("report.md");
    write(&md_path, md.as_bytes())?;
    written.push(md_path);
    Ok(written)
}

/// Writes the heat maps of `rep`'s error maps into `sub` (the scene's folder, `name`), adding
/// each file to `written`; returns each map's mode, spp and path relative to the report.
#[cfg(feature = "flip")]
fn heat_maps(
    rep: &SceneReport,
    sub: &Path,
    name: &str,
    written: &mut Vec<PathBuf>,
) -> Result<Vec<(super::Mode, u32, String)>, ReportError> {
    use crate::names::Named as _;
    let mut out = Vec::new();
    for map in &rep.error_maps {
        let adaptive = if map.mode.adaptive { "_adaptive" } else { "" };
        let file = format!(
            "heat_{}_{}{adaptive}_{}spp.png",
            map.mode.filter.name(),
            map.mode.sampler.name(),
            map.spp
        );
        let path = sub.join(&file);
        let (w, h, rgb) = plot::heat_map(map).map_err(|e| plotting(&path, &e))?;
        png(&path, w, h, &rgb)?;
        out.push((map.mode, map.spp, format!("{name}/{file}")));
        written.push(path);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::{file_safe, unique};

    #[test]
    fn names_become_safe_file_names() {
        assert_eq!(file_safe("earth"), "earth");
        assert_eq!(file_safe("a b/../c"), "a_b_.._c");
        assert_eq!(file_safe(".."), "_..");
        assert_eq!(file_safe(""), "_");
    }

    #[test]
    fn scenes_with_one_file_name_get_numbered_folders() {
        let v = |s: &[&str]| s.iter().map(ToString::to_string).collect::<Vec<_>>();
        assert_eq!(
            unique(v(&["a_b", "a_b", "c", "a_b"])),
            v(&["a_b", "a_b_2", "c", "a_b_3"])
        );
    }
}
