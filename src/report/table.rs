//! The report's tables: CSV rows, the Pareto front, the time to reach an error by log-log
//! interpolation, and the Markdown summary.

use super::{METRIC_DEFINITIONS, Mode, Row, SceneReport};
use crate::names::Named as _;
use std::fmt::Write as _;
use std::time::Duration;

/// The equal-quality targets of the report: time to reach these RMSEs.
pub const RMSE_TARGETS: [f64; 3] = [0.03, 0.01, 0.003];

/// The columns of `report.csv`, in order.
pub const CSV_COLUMNS: [&str; 19] = [
    "scene",
    "mode",
    "filter",
    "sampler",
    "spp",
    "width",
    "height",
    "threads",
    "runs",
    "time_ms_median",
    "time_ms_min",
    "samples_per_s",
    "rmse",
    "psnr_db",
    "rel_mse",
    "ssim",
    "flip",
    "rmse_linear",
    "pareto",
];

/// Which rows lie on the Pareto front of (time, RMSE): no other row is at least as fast with a
/// lower error. Ties in time keep only the lowest error.
#[must_use]
pub fn pareto_front(rows: &[Row]) -> Vec<bool> {
    rows.iter()
        .map(|r| {
            !rows.iter().any(|o| {
                let faster_or_equal = o.time <= r.time;
                let better = o.metrics.rmse < r.metrics.rmse;
                let strictly = o.time < r.time || o.metrics.rmse < r.metrics.rmse;
                faster_or_equal && (better || (o.metrics.rmse == r.metrics.rmse && strictly))
            })
        })
        .collect()
}

/// When a mode reaches an error level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reach {
    /// Already below the target at its first (cheapest) measurement, which took this long.
    AtFirst(Duration),
    /// Crossed between two measurements; the time is interpolated on the log-log curve.
    Interpolated(Duration),
    /// Never reached; the lowest error measured.
    NotReached(f64),
}

impl Reach {
    /// The time, if reached.
    #[must_use]
    pub fn time(self) -> Option<Duration> {
        match self {
            Self::AtFirst(t) | Self::Interpolated(t) => Some(t),
            Self::NotReached(_) => None,
        }
    }

    /// For tables: `12.3 ms`, `<= 1.2 ms`, or `not reached (best 0.012)`.
    #[must_use]
    pub fn describe(self) -> String {
        match self {
            Self::AtFirst(t) => format!("<= {}", ms(t)),
            Self::Interpolated(t) => ms(t),
            Self::NotReached(best) => format!("not reached (best {best:.4})"),
        }
    }
}

/// The time at which the error curve `points` (time, error), ordered by increasing spp,
/// first reaches `target`: linear interpolation of log(error) against log(time) between the
/// last point above the target and the first at or below it.
#[must_use]
pub fn time_to_reach(points: &[(Duration, f64)], target: f64) -> Reach {
    let Some(i) = points.iter().position(|p| p.1 <= target) else {
        let best = points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        return Reach::NotReached(best);
    };
    if i == 0 {
        return Reach::AtFirst(points[0].0);
    }
    let (t0, e0) = points[i - 1];
    let (t1, e1) = points[i];
    let (lt0, lt1) = (t0.as_secs_f64().ln(), t1.as_secs_f64().ln());
    let (le0, le1, lt) = (e0.ln(), e1.max(1e-300).ln(), target.ln());
    let t = if (le1 - le0).abs() > 0.0 && lt0.is_finite() && lt1.is_finite() {
        (lt0 + (lt - le0) * (lt1 - lt0) / (le1 - le0)).exp()
    } else {
        t1.as_secs_f64()
    };
    // Between the two measurements whatever rounding did.
    let t = t.clamp(
        t0.as_secs_f64().min(t1.as_secs_f64()),
        t0.as_secs_f64().max(t1.as_secs_f64()),
    );
    Reach::Interpolated(Duration::from_secs_f64(t))
}

/// The (time, RMSE) curve of one mode, by increasing spp.
#[must_use]
pub fn curve(rows: &[Row], mode: Mode) -> Vec<(Duration, f64)> {
    let mut r: Vec<&Row> = rows.iter().filter(|r| r.mode == mode).collect();
    r.sort_by_key(|r| r.spp);
    r.iter().map(|r| (r.time, r.metrics.rmse)).collect()
}

/// The modes of `rows` in first-seen order.
#[must_use]
pub fn modes(rows: &[Row]) -> Vec<Mode> {
    let mut out: Vec<Mode> = Vec::new();
    for r in rows {
        if !out.contains(&r.mode) {
            out.push(r.mode);
        }
    }
    out
}

fn ms(t: Duration) -> String {
    let v = t.as_secs_f64() * 1e3;
    if v < 10.0 {
        format!("{v:.2} ms")
    } else if v < 1000.0 {
        format!("{v:.1} ms")
    } else {
        format!("{:.2} s", v / 1e3)
    }
}

/// A number written with `P` decimals (`inf` and `NaN` as Rust writes them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fixed<const P: usize>(pub f64);

impl<const P: usize> serde::Serialize for Fixed<P> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&format_args!("{:.P$}", self.0))
    }
}

/// One line of `report.csv`; its fields are [`CSV_COLUMNS`], in order.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CsvRow<'a> {
    /// The scene's name.
    pub scene: &'a str,
    /// The mode as `--modes` takes it.
    pub mode: String,
    /// Its texture filter.
    pub filter: &'static str,
    /// Its pixel sampler.
    pub sampler: &'static str,
    /// Samples per pixel.
    pub spp: u32,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Rayon worker threads.
    pub threads: usize,
    /// Timed runs.
    pub runs: usize,
    /// Median time, ms.
    pub time_ms_median: Fixed<4>,
    /// Fastest run, ms.
    pub time_ms_min: Fixed<4>,
    /// Camera samples per second at the median time.
    pub samples_per_s: Fixed<0>,
    /// RMSE of the sRGB values.
    pub rmse: Fixed<6>,
    /// PSNR in dB.
    pub psnr_db: Fixed<3>,
    /// Relative MSE.
    pub rel_mse: Fixed<6>,
    /// Mean SSIM.
    pub ssim: Fixed<6>,
    /// Mean FLIP (empty without the `flip` feature).
    pub flip: Option<Fixed<6>>,
    /// RMSE of the linear radiance.
    pub rmse_linear: Fixed<7>,
    /// 1 on the Pareto front of (time, RMSE), else 0.
    pub pareto: u8,
}

impl<'a> CsvRow<'a> {
    /// The line of `row`.
    #[must_use]
    pub fn new(row: &'a Row, on_front: bool) -> Self {
        let ms = |t: Duration| Fixed(t.as_secs_f64() * 1e3);
        let m = row.metrics;
        Self {
            scene: &row.scene,
            mode: row.mode.name(),
            filter: row.mode.filter.name(),
            sampler: row.mode.sampler.name(),
            spp: row.spp,
            width: row.width,
            height: row.height,
            threads: row.threads,
            runs: row.runs,
            time_ms_median: ms(row.time),
            time_ms_min: ms(row.time_min),
            samples_per_s: Fixed(row.samples_per_second()),
            rmse: Fixed(m.rmse),
            psnr_db: Fixed(m.psnr),
            rel_mse: Fixed(m.rel_mse),
            ssim: Fixed(m.ssim),
            flip: m.flip.map(Fixed),
            rmse_linear: Fixed(m.rmse_linear),
            pareto: u8::from(on_front),
        }
    }
}

/// `report.csv`: a header of [`CSV_COLUMNS`] and one line per row (fields quoted where they
/// hold a comma, a quote or a line break).
///
/// # Errors
/// Only if serialising fails, which writing to memory does not.
pub fn csv(reports: &[SceneReport]) -> Result<String, csv::Error> {
    let mut w = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    if reports.iter().all(|r| r.rows.is_empty()) {
        w.write_record(CSV_COLUMNS)?;
    }
    for rep in reports {
        let front = pareto_front(&rep.rows);
        for (r, on_front) in rep.rows.iter().zip(front) {
            w.serialize(CsvRow::new(r, on_front))?;
        }
    }
    let bytes = w
        .into_inner()
        .map_err(|e| csv::Error::from(e.into_error()))?;
    // Every field is UTF-8 text: scene names are Rust strings, the rest numbers and names.
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// The "how each metric is computed" section.
#[must_use]
pub fn metrics_section() -> String {
    let mut s = String::from(
        "## Metrics\n\nAll metrics but the last compare display-encoded images against the reference:\n\n",
    );
    for (name, how) in METRIC_DEFINITIONS {
        let _ = writeln!(s, "- **{name}**: {how}.");
    }
    s.push_str(
        "\nTimes are wall-clock medians of the timed runs of a complete render (every pass, \
         film allocation included) after one untimed warm-up run, on the stated number of \
         rayon threads; `runs` in the CSV says how many timed runs there were (fewer than \
         `--repeat` when they would have exceeded the time budget).\n",
    );
    s
}

/// Files written beside the report for one scene (paths relative to `report.md`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SceneFiles {
    /// The error-against-time plot, SVG.
    pub plot_svg: Option<String>,
    /// The same plot, PNG.
    pub plot_png: Option<String>,
    /// Heat maps: (mode, spp, file).
    pub heat_maps: Vec<(Mode, u32, String)>,
}

/// One scene's section of `report.md`.
#[must_use]
pub fn markdown_scene(rep: &SceneReport, files: &SceneFiles) -> String {
    let mut s = String::new();
    let (w, h, threads) = rep
        .rows
        .first()
        .map_or((0, 0, 0), |r| (r.width, r.height, r.threads));
    let _ = writeln!(s, "## {}\n", rep.scene);
    let _ = writeln!(
        s,
        "{w}x{h} pixels, {threads} threads. Reference: {}; {}.\n",
        rep.reference.describe(),
        if rep.reference.file.is_some() {
            "read from that file".to_string()
        } else if rep.reference_cached {
            "loaded from the cache".to_string()
        } else {
            format!("rendered now in {:.1} s", rep.reference_time.as_secs_f64())
        }
    );
    if let Some(svg) = &files.plot_svg {
        let _ = writeln!(s, "![RMSE against time, {}]({svg})\n", rep.scene);
    }

    // Table sorted by time, front marked.
    let front = pareto_front(&rep.rows);
    let mut order: Vec<usize> = (0..rep.rows.len()).collect();
    order.sort_by(|&a, &b| rep.rows[a].time.cmp(&rep.rows[b].time));
    s.push_str("Sorted by time; ★ marks the Pareto front (no faster render has a lower RMSE).\n\n");
    s.push_str(
        "| front | mode | spp | time | M samples/s | RMSE | PSNR dB | relMSE | SSIM | FLIP | RMSE linear |\n",
    );
    s.push_str("|:-:|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
    for i in order {
        let r = &rep.rows[i];
        let m = r.metrics;
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.1} | {:.4} | {:.2} | {:.5} | {:.4} | {} | {:.5} |",
            if front[i] { "★" } else { "" },
            r.mode.name(),
            r.spp,
            ms(r.time),
            r.samples_per_second() / 1e6,
            m.rmse,
            m.psnr,
            m.rel_mse,
            m.ssim,
            m.flip.map_or_else(|| "–".to_owned(), |f| format!("{f:.4}")),
            m.rmse_linear
        );
    }

    // Equal quality.
    s.push_str("\nTime to reach an RMSE (log-log interpolation between the measured spp; `<=` when the lowest spp already reaches it):\n\n| mode |");
    for t in RMSE_TARGETS {
        let _ = write!(s, " RMSE {t} |");
    }
    s.push_str("\n|---|");
    for _ in RMSE_TARGETS {
        s.push_str("--:|");
    }
    s.push('\n');
    let modes = modes(&rep.rows);
    let mut fastest: Vec<Option<(Duration, Mode)>> = vec![None; RMSE_TARGETS.len()];
    for &mode in &modes {
        let c = curve(&rep.rows, mode);
        let _ = write!(s, "| {} |", mode.name());
        for (k, &target) in RMSE_TARGETS.iter().enumerate() {
            let reach = time_to_reach(&c, target);
            let _ = write!(s, " {} |", reach.describe());
            if let Some(t) = reach.time()
                && fastest[k].is_none_or(|(best, _)| t < best)
            {
                fastest[k] = Some((t, mode));
            }
        }
        s.push('\n');
    }
    s.push('\n');
    for (k, &target) in RMSE_TARGETS.iter().enumerate() {
        match fastest[k] {
            Some((t, mode)) => {
                let _ = writeln!(
                    s,
                    "- RMSE {target}: fastest is **{}** in {}.",
                    mode.name(),
                    ms(t)
                );
            }
            None => {
                let _ = writeln!(s, "- RMSE {target}: no mode reached it.");
            }
        }
    }
    if let Some(png) = &files.plot_png {
        let _ = writeln!(s, "\nPlot as PNG: [{png}]({png}).");
    }
    if !files.heat_maps.is_empty() {
        s.push_str(
            "\n### Where the error is\n\nPer-pixel FLIP error against the reference, magma colour map from 0 (black) to 1 (pale yellow); the bar under each map is the scale.\n\n",
        );
        for (mode, spp, file) in &files.heat_maps {
            let _ = writeln!(
                s,
                "- {} at {spp} spp: ![{}]({file})",
                mode.name(),
                mode.name()
            );
        }
    }
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::Metrics;
    use crate::sampler::PixelSampler;
    use crate::texture::Filter;

    fn row(ms_: u64, rmse: f64, spp: u32) -> Row {
        Row {
            scene: "s".into(),
            mode: Mode::new(Filter::Bilinear, PixelSampler::Jittered),
            samples: f64::from(100 * spp),
            spp,
            width: 10,
            height: 10,
            threads: 2,
            runs: 3,
            time: Duration::from_millis(ms_),
            time_min: Duration::from_millis(ms_),
            metrics: Metrics {
                rmse,
                flip: Some(0.0),
                ..Metrics::default()
            },
        }
    }

    #[test]
    fn pareto_front_keeps_only_undominated_rows() {
        let rows = [
            row(10, 0.05, 1),
            row(20, 0.06, 2), // slower and worse than the first: dominated
            row(30, 0.02, 4),
            row(40, 0.02, 8), // as good as the third but slower: dominated
            row(50, 0.01, 16),
        ];
        assert_eq!(pareto_front(&rows), vec![true, false, true, false, true]);
    }

    #[test]
    fn time_to_reach_interpolates_on_the_log_log_curve() {
        let d = Duration::from_millis;
        // Error halves when time quadruples (slope -1/2): 0.04 at 10 ms, 0.02 at 40 ms.
        let pts = [(d(10), 0.04), (d(40), 0.02)];
        // 0.02 * sqrt(2) = 0.028284 lies halfway in log space: sqrt(10 * 40) = 20 ms.
        let t = time_to_reach(&pts, 0.02 * 2f64.sqrt()).time().unwrap();
        assert!((t.as_secs_f64() - 0.020).abs() < 1e-9, "{t:?}");
        assert_eq!(time_to_reach(&pts, 0.05), Reach::AtFirst(d(10)));
        assert_eq!(time_to_reach(&pts, 0.01), Reach::NotReached(0.02));
        assert_eq!(time_to_reach(&pts, 0.02), Reach::Interpolated(d(40)));
    }

    #[test]
    fn csv_has_a_header_and_one_line_per_row() {
        let rep = SceneReport {
            scene: "a,b".into(),
            rows: vec![row(10, 0.05, 1), row(30, 0.02, 4)]
                .into_iter()
                .map(|r| Row {
                    scene: "a,b".into(),
                    ..r
                })
                .collect(),
            reference: crate::report::ReferenceSettings::default(),
            reference_cached: true,
            reference_file: None,
            reference_problem: None,
            reference_not_stored: None,
            reference_time: Duration::ZERO,
            error_maps: vec![],
        };
        let text = csv(&[rep]).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        // The serialised struct's fields are the documented columns, in order.
        assert_eq!(lines[0], CSV_COLUMNS.join(","));
        assert!(text.ends_with(",1\n") && !text.contains('\r'), "{text:?}");
        // 10 ms for 100 samples, then the metrics with their fixed decimals.
        assert!(
            lines[1].ends_with(
                ",1,10,10,2,3,10.0000,10.0000,10000,0.050000,0.000,0.000000,0.000000,0.000000,0.0000000,1"
            ),
            "{}",
            lines[1]
        );
        assert!(lines[1].starts_with("\"a,b\",bilinear/jittered,bilinear,jittered,1,"));
        assert!(lines[2].ends_with(",1"), "{}", lines[2]);
        // No rows: the header alone.
        assert_eq!(csv(&[]).unwrap(), format!("{}\n", CSV_COLUMNS.join(",")));
    }
}
