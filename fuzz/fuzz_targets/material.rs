//! Arbitrary bytes as the `.mtl` library an OBJ names: read with the OBJ, then the quad it
//! textures is built into a scene through `MeshMaterial` and rendered. Run:
//! `cargo +nightly fuzz run material`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::LazyLock;

static DIR: LazyLock<PathBuf> = LazyLock::new(|| {
    let dir = std::env::temp_dir().join(format!("texplore-fuzz-mtl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
});

fuzz_target!(|data: &[u8]| {
    let _ = texplore::robustness::material_bytes(data, &DIR);
});
