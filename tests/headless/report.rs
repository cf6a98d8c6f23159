//! `texplore report` and the report library: files, columns, error against spp, the reference
//! cache, progress and cancellation.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicBool, Ordering};
use texplore::report::{
    Mode, ReferenceSettings, ReportConfig, ReportError, Stage, run_scene, table::CSV_COLUMNS,
};
use texplore::sampler::PixelSampler;
use texplore::scene::load_preset;
use texplore::texture::Filter;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn report(out: &Path, cache: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(root())
        .args([
            "report",
            "presets/earth.ron",
            "--modes",
            "nearest/jittered,bilinear/jittered",
            "--spp",
            "1,4",
            "--reference-spp",
            "64",
            "--width",
            "48",
            "--height",
            "36",
            "--repeat",
            "2",
            "--quiet",
            "--cache",
        ])
        .arg(cache)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap()
}

fn csv_rows(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (header, rows)
}

fn cached_exrs(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "exr"))
        .collect()
}

#[test]
fn a_tiny_report_writes_every_file_and_reuses_its_reference() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, cache) = (tmp.path().join("out"), tmp.path().join("cache"));
    let run = report(&out, &cache);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );

    // CSV: the documented columns, one row per (mode, spp).
    let (header, rows) = csv_rows(&out.join("report.csv"));
    assert_eq!(header, CSV_COLUMNS.map(String::from).to_vec());
    assert_eq!(rows.len(), 4);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    for r in &rows {
        assert_eq!(r.len(), header.len());
        assert_eq!(r[col("scene")], "earth");
        assert_eq!(
            (r[col("width")].as_str(), r[col("height")].as_str()),
            ("48", "36")
        );
        assert!(r[col("time_ms_median")].parse::<f64>().unwrap() > 0.0);
        let rmse: f64 = r[col("rmse")].parse().unwrap();
        let ssim: f64 = r[col("ssim")].parse().unwrap();
        let flip: f64 = r[col("flip")].parse().unwrap();
        assert!(rmse > 0.0 && rmse < 0.5, "{rmse}");
        assert!(ssim > 0.0 && ssim < 1.0, "{ssim}");
        assert!(flip > 0.0 && flip < 1.0, "{flip}");
    }
    // Jittered supersampling converges toward the reference.
    let rmse_of = |mode: &str, spp: &str| -> f64 {
        rows.iter()
            .find(|r| r[col("mode")] == mode && r[col("spp")] == spp)
            .unwrap()[col("rmse")]
        .parse()
        .unwrap()
    };
    for mode in ["nearest/jittered", "bilinear/jittered"] {
        assert!(
            rmse_of(mode, "4") < rmse_of(mode, "1") * 0.8,
            "{mode}: {} -> {}",
            rmse_of(mode, "1"),
            rmse_of(mode, "4")
        );
    }

    // Markdown, plots and heat maps.
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    for needle in [
        "## earth",
        "★",
        "Time to reach an RMSE",
        "64 spp, bilinear texture filter, jittered sampler, box pixel filter",
        "rendered now",
        "SSIM",
        "FLIP",
    ] {
        assert!(md.contains(needle), "report.md lacks {needle:?}:\n{md}");
    }
    let svg = std::fs::read_to_string(out.join("earth/error_vs_time.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains(">\nnearest/jittered\n</text>"));
    let png = image::open(out.join("earth/error_vs_time.png")).unwrap();
    assert_eq!((png.width(), png.height()), (1000, 600));
    for mode in ["nearest_jittered", "bilinear_jittered"] {
        let heat = image::open(out.join(format!("earth/heat_{mode}_1spp.png"))).unwrap();
        assert_eq!(heat.width(), 200); // the colour bar's minimum width
        assert!(heat.height() > 36);
    }

    // The second run loads the reference instead of rendering it again.
    let exrs = cached_exrs(&cache);
    assert_eq!(exrs.len(), 1);
    let stamp = std::fs::metadata(&exrs[0]).unwrap().modified().unwrap();
    let again = report(&out, &cache);
    assert!(again.status.success());
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("loaded from the cache"), "{md}");
    assert_eq!(cached_exrs(&cache), exrs);
    assert_eq!(
        std::fs::metadata(&exrs[0]).unwrap().modified().unwrap(),
        stamp
    );
    // The same image: the measured errors are identical.
    let (_, rows2) = csv_rows(&out.join("report.csv"));
    let col_rmse = header.iter().position(|h| h == "rmse").unwrap();
    for (a, b) in rows.iter().zip(&rows2) {
        assert_eq!(a[col_rmse], b[col_rmse]);
    }
}

/// An adaptive mode spends more samples than spp on some pixels, and says so in its name and in
/// its samples per second.
#[test]
fn adaptive_modes_parse_and_take_extra_samples() {
    let modes = Mode::parse_list("ewa/regular+adaptive, bilinear/regular").unwrap();
    assert_eq!(modes.len(), 2);
    assert!(modes[0].adaptive && !modes[1].adaptive);
    assert_eq!(modes[0].name(), "ewa/regular+adaptive");
    let tmp = tempfile::tempdir().unwrap();
    let mut config = tiny_config(Some(tmp.path().to_path_buf()));
    config.modes = modes;
    config.spp = vec![1];
    let desc = load_preset(&root().join("presets/earth.ron")).unwrap();
    let never = std::sync::atomic::AtomicBool::new(false);
    let rep = texplore::report::run_scene(
        "earth",
        &desc,
        &root().join("presets/earth.ron"),
        &config,
        &mut |_| {},
        &never,
    )
    .unwrap();
    let (a, b) = (&rep.rows[0], &rep.rows[1]);
    let pixels = f64::from(a.width * a.height);
    assert!(
        a.samples > pixels * 1.05,
        "adaptive took {} samples for {pixels} pixels",
        a.samples
    );
    assert!((b.samples - pixels).abs() < 0.5, "{}", b.samples);
}

fn tiny_config(cache: Option<PathBuf>) -> ReportConfig {
    ReportConfig {
        modes: vec![Mode::new(Filter::Bilinear, PixelSampler::Jittered)],
        spp: vec![1, 2],
        repeat: 1,
        width: Some(24),
        height: Some(18),
        reference: ReferenceSettings {
            spp: 16,
            cache_dir: cache,
            ..ReferenceSettings::default()
        },
        ..ReportConfig::default()
    }
}

#[test]
fn the_library_reports_progress_rows_and_the_cache() {
    let path = root().join("presets/checker.ron");
    let desc = load_preset(&path).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let config = tiny_config(Some(tmp.path().to_path_buf()));
    let cancel = AtomicBool::new(false);
    let mut updates = Vec::new();
    let mut live_rows = 0;
    let rep = run_scene(
        "checker",
        &desc,
        &path,
        &config,
        &mut |p| {
            updates.push((p.done, p.total, p.stage.clone()));
            live_rows += usize::from(p.row.is_some());
        },
        &cancel,
    )
    .unwrap();
    assert!(!rep.reference_cached);
    assert_eq!(rep.rows.len(), 2);
    assert_eq!(live_rows, 2, "each row is handed to the callback when done");
    assert_eq!(updates[0].2, Stage::Reference);
    let (done, total, _) = *updates.last().unwrap();
    assert_eq!(done, total, "progress ends at 100%");
    assert!(
        updates.windows(2).all(|w| w[0].0 <= w[1].0),
        "progress never goes back"
    );
    assert!(rep.rows.iter().all(|r| r.threads >= 1 && r.runs == 1));

    let again = run_scene("checker", &desc, &path, &config, &mut |_| {}, &cancel).unwrap();
    assert!(again.reference_cached);
    assert_eq!(rep.rows[0].metrics, again.rows[0].metrics);

    // A different reference setting is a different cache entry.
    let mut other = config.clone();
    other.reference.spp = 8;
    let third = run_scene("checker", &desc, &path, &other, &mut |_| {}, &cancel).unwrap();
    assert!(!third.reference_cached);
}

#[test]
fn raising_the_cancel_flag_stops_the_report() {
    let path = root().join("presets/checker.ron");
    let desc = load_preset(&path).unwrap();
    let cancel = AtomicBool::new(false);
    let result = run_scene(
        "checker",
        &desc,
        &path,
        &tiny_config(None),
        &mut |_| cancel.store(true, Ordering::Relaxed),
        &cancel,
    );
    assert!(matches!(result, Err(ReportError::Cancelled)), "{result:?}");
}

#[test]
fn bad_modes_are_refused_with_the_valid_names() {
    let tmp = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(root())
        .args([
            "report",
            "presets/earth.ron",
            "--modes",
            "bilinear/wobbly",
            "-o",
        ])
        .arg(tmp.path())
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("wobbly") && err.contains("jittered"), "{err}");
}

/// The report's numbers do not change: a fixed small run's CSV against the one saved in
/// `tests/report_expected.csv` (written by `texplore report` with these arguments before the
/// CSV writer moved to the `csv` crate). Every column but the timings must match exactly; the
/// timings (and the Pareto flags they decide) vary from run to run, so they must only parse.
#[test]
fn the_csv_matches_the_saved_report() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let run = Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(root())
        .args([
            "report",
            "presets/earth.ron",
            "presets/checker.ron",
            "--modes",
            "nearest/jittered,ewa/regular+adaptive",
            "--spp",
            "1,4",
            "--reference-spp",
            "32",
            "--width",
            "40",
            "--height",
            "30",
            "--repeat",
            "1",
            "--threads",
            "2",
            "--no-cache",
            "--quiet",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let (header, rows) = csv_rows(&out.join("report.csv"));
    let (saved_header, saved) = csv_rows(&root().join("tests/report_expected.csv"));
    assert_eq!(header, saved_header);
    assert_eq!(header, CSV_COLUMNS.map(String::from).to_vec());
    assert_eq!(rows.len(), saved.len());
    let timing = ["time_ms_median", "time_ms_min", "samples_per_s"];
    for (row, want) in rows.iter().zip(&saved) {
        for (k, name) in header.iter().enumerate() {
            if timing.contains(&name.as_str()) {
                let v: f64 = row[k]
                    .parse()
                    .unwrap_or_else(|e| panic!("{name} = {:?}: {e}", row[k]));
                assert!(v > 0.0 && v.is_finite(), "{name} = {v}");
            } else if name == "pareto" {
                assert!(row[k] == "0" || row[k] == "1", "pareto = {:?}", row[k]);
            } else {
                assert_eq!(row[k], want[k], "{name} of {}", want[..4].join(","));
            }
        }
    }
}
