//! Arbitrary bytes as a PNG screenshot opened or dropped on the window: the preset in its text
//! chunk is read and parsed. Run: `cargo +nightly fuzz run screenshot`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::LazyLock;

static PATH: LazyLock<PathBuf> = LazyLock::new(|| {
    let dir = std::env::temp_dir().join(format!("texplore-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir.join("screenshot.png")
});

fuzz_target!(|data: &[u8]| {
    let _ = texplore::robustness::screenshot_bytes(data, &PATH);
});
