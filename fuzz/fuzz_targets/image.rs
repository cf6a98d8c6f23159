//! Arbitrary bytes as an image file: the first byte picks the extension (the decoder sniffs the
//! content first, the extension second), the rest is the file. Run:
//! `cargo +nightly fuzz run image -- -rss_limit_mb=2048`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::LazyLock;

const EXTENSIONS: [&str; 8] = ["png", "jpg", "tif", "ppm", "pgm", "hdr", "exr", "bin"];

static DIR: LazyLock<PathBuf> = LazyLock::new(|| {
    let dir = std::env::temp_dir().join(format!("texplore-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
});

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else { return };
    let ext = EXTENSIONS[usize::from(pick) % EXTENSIONS.len()];
    let path = DIR.join(format!("fuzzed.{ext}"));
    let _ = texplore::robustness::image_bytes(bytes, &path);
});
