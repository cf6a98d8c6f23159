//! `cargo test` runs `texplore snapshot check`: every preset rendered at its snapshot settings
//! must match its golden image in `screenshots/` within the tolerance stated in
//! `texplore::snapshot` (a channel may differ by 2/255 on at most 0.1% of pixels; mean
//! difference at most 0.25/255). On a mismatch `screenshots/<preset>.new.png` and
//! `<preset>.diff.png` are written.

use std::path::Path;
use texplore::scene::SimdMode;
use texplore::scene::{AssetCache, list_presets};
use texplore::snapshot::{Outcome, check_preset};

#[test]
fn every_preset_matches_its_golden_image() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let presets = list_presets(&root.join("presets")).expect("presets/ is readable");
    assert!(
        presets.len() >= 6,
        "expected the book's presets, found {presets:?}"
    );
    let mut cache = AssetCache::new();
    let mut failures = Vec::new();
    for p in &presets {
        match check_preset(
            p,
            &root.join("screenshots"),
            false,
            &mut cache,
            SimdMode::Auto,
        ) {
            Ok(Outcome::Match(_)) => {}
            Ok(other) => failures.push(format!("{}: {other:?}", p.display())),
            Err(e) => failures.push(e.to_string()),
        }
    }
    assert!(
        failures.is_empty(),
        "snapshot mismatches (run `texplore snapshot update` if intended):\n{}",
        failures.join("\n")
    );
}
