//! Arbitrary bytes as a mesh file: the first byte picks `.ply` or `.obj`, the rest is the file;
//! it is read, validated, its BVH built and rays shot at it. Run: `cargo +nightly fuzz run mesh`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::LazyLock;

static DIR: LazyLock<PathBuf> = LazyLock::new(|| {
    let dir = std::env::temp_dir().join(format!("texplore-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
});

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else { return };
    let ext = if pick % 2 == 0 { "ply" } else { "obj" };
    let _ = texplore::robustness::mesh_bytes(bytes, &DIR.join(format!("fuzzed.{ext}")));
});
