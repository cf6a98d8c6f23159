//! `texplore snapshot check|update`.

use crate::scene::{AssetCache, list_presets};
use crate::snapshot::{MAX_BAD_FRACTION, MAX_MEAN_DIFF, Outcome, PIXEL_TOLERANCE, check_preset};
use anyhow::{Result, bail};
use clap::ValueEnum;
use std::path::PathBuf;

/// `texplore snapshot`.
#[derive(Debug, clap::Args)]
pub struct SnapshotArgs {
    /// check: compare with the goldens; update: rewrite them.
    pub action: SnapshotAction,
    /// Only these presets (file stems, e.g. `earth`).
    pub names: Vec<String>,
    /// Where the presets are.
    #[arg(long, default_value = "presets")]
    pub presets: PathBuf,
    /// Where the golden images are.
    #[arg(long, default_value = "screenshots")]
    pub screenshots: PathBuf,
}

/// What `snapshot` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SnapshotAction {
    /// Compare renders with the goldens; exit non-zero on a mismatch.
    Check,
    /// Rewrite the goldens.
    Update,
}

pub fn run(a: &SnapshotArgs, simd: crate::scene::SimdMode) -> Result<()> {
    let update = a.action == SnapshotAction::Update;
    let mut presets = list_presets(&a.presets)?;
    if presets.is_empty() {
        bail!(
            "{}: no presets (*.ron) here, nothing to {}",
            a.presets.display(),
            if update { "update" } else { "check" }
        );
    }
    if !a.names.is_empty() {
        // Every name must be a preset: a typo never passes as a smaller, green check.
        let stem = |p: &PathBuf| p.file_stem().map(|s| s.to_string_lossy().into_owned());
        let unknown: Vec<&str> = a
            .names
            .iter()
            .filter(|n| {
                !presets
                    .iter()
                    .any(|p| stem(p).as_deref() == Some(n.as_str()))
            })
            .map(String::as_str)
            .collect();
        if !unknown.is_empty() {
            let known: Vec<String> = presets.iter().filter_map(stem).collect();
            bail!(
                "no preset named {} in {} (there are: {})",
                unknown.join(", "),
                a.presets.display(),
                known.join(", ")
            );
        }
        presets.retain(|p| stem(p).is_some_and(|s| a.names.contains(&s)));
    }
    let mut cache = AssetCache::new();
    let mut failed = 0;
    for p in &presets {
        let name = p.file_stem().unwrap_or_default().to_string_lossy();
        match check_preset(p, &a.screenshots, update, &mut cache, simd)? {
            Outcome::Match(c) => println!(
                "ok       {name} (max diff {}, mean {:.3})",
                c.max_diff, c.mean_diff
            ),
            Outcome::Updated => println!("updated  {name}"),
            Outcome::Missing { new } => {
                failed += 1;
                println!(
                    "missing  {name}: no golden image of this size; the render is in {}",
                    new.display()
                );
            }
            Outcome::Mismatch {
                comparison: c,
                new,
                diff,
            } => {
                failed += 1;
                println!(
                    "MISMATCH {name}: {:.3}% of pixels differ by more than {PIXEL_TOLERANCE}/255 (limit {:.1}%), mean diff {:.3} (limit {MAX_MEAN_DIFF}), max {}; new render {}, diff x8 {}",
                    c.bad_fraction * 100.0,
                    MAX_BAD_FRACTION * 100.0,
                    c.mean_diff,
                    c.max_diff,
                    new.display(),
                    diff.display()
                );
            }
        }
    }
    if failed > 0 {
        bail!(
            "{failed} of {} snapshots do not match (run `texplore snapshot update` if the change is intended)",
            presets.len()
        );
    }
    Ok(())
}
