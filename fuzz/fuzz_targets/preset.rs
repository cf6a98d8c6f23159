//! Arbitrary bytes as a preset in `presets/`: parse, validate, build (assets resolve as for the
//! shipped presets), render 8x6 at 1 spp. Run: `cargo +nightly fuzz run preset`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::{LazyLock, Mutex};
use texplore::scene::AssetCache;

static CACHE: LazyLock<Mutex<AssetCache>> = LazyLock::new(|| Mutex::new(AssetCache::new()));
static PRESET: LazyLock<PathBuf> =
    LazyLock::new(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../presets/fuzzed.ron"));

fuzz_target!(|data: &[u8]| {
    let mut cache = CACHE.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let _ = texplore::robustness::preset_bytes(data, &PRESET, &mut cache);
});
