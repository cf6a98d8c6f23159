//! Bounded fuzzing in CI: mutated copies of real presets and of small files of every image
//! format go through the same harnesses as the cargo-fuzz targets (`texplore::robustness`).
//! A panic is a finding; an error naming the file is the right answer.
//!
//! `TEXPLORE_FUZZ_CASES=N` sets the cases per target (default 1000) and `TEXPLORE_FUZZ_SEED=N`
//! the mutations (default 0, so CI is reproducible); the long runs are cargo-fuzz
//! (see the README's "Robustness" section). Inputs that once broke a parser live in
//! `tests/fuzz_regressions/` and are replayed on every run.

use crate::common::{root, success, texplore};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::path::Path;
use texplore::robustness::{
    image_bytes, material_bytes, mesh_bytes, preset_bytes, screenshot_bytes,
};
use texplore::scene::AssetCache;

fn cases() -> u32 {
    std::env::var("TEXPLORE_FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000)
}

/// One edit of an input; positions are fractions of the current length.
#[derive(Clone, Debug)]
enum Mutation {
    FlipBit(f64, u8),
    SetByte(f64, u8),
    Truncate(f64),
    Insert(f64, Vec<u8>),
    Delete(f64, usize),
    /// Copies a run of the input elsewhere (repeats headers, chunks, list items).
    Duplicate(f64, usize, f64),
    /// Replaces the token at a position with an interesting one (presets: numbers, names).
    Token(f64, usize),
}

const TOKENS: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1e30",
    "-1e30",
    "1e-45",
    "NaN",
    "inf",
    "-inf",
    "4294967295",
    "1e9",
    "65536",
    "()",
    "[]",
    "\"\"",
    "Sphere",
    "Plane",
    "Cylinder(capped: true)",
    "Rectangle",
    "Disk",
    "Spherical",
    "Cylindrical",
    "LightProbe",
    "Panoramic",
    "MirrorBall",
    "Uv",
    "Rectangular",
    "Bilinear",
    "Nearest",
    "Clamp",
    "Black",
    "Mirror",
    "Lecture",
    "Constant((1, 1, 1))",
    "UvGrid()",
    "Checker()",
    "Emissive(ls: 1e30)",
    "\"../assets/missing.png\"",
    "\"/dev/null\"",
    "\"../presets\"",
    "\"../assets/LICENSES.md\"",
];

fn apply(input: &[u8], mutations: &[Mutation]) -> Vec<u8> {
    let mut d = input.to_vec();
    let at = |f: f64, len: usize| ((f * len as f64) as usize).min(len);
    for m in mutations {
        let len = d.len();
        match m {
            Mutation::FlipBit(p, b) if len > 0 => {
                let i = at(*p, len - 1);
                d[i] ^= 1 << (b % 8);
            }
            Mutation::SetByte(p, v) if len > 0 => {
                let i = at(*p, len - 1);
                d[i] = *v;
            }
            Mutation::Truncate(p) => d.truncate(at(*p, len)),
            Mutation::Insert(p, bytes) => {
                let i = at(*p, len);
                d.splice(i..i, bytes.iter().copied());
            }
            Mutation::Delete(p, n) => {
                let i = at(*p, len);
                d.drain(i..(i + n).min(len));
            }
            Mutation::Duplicate(p, n, q) => {
                let i = at(*p, len);
                let run: Vec<u8> = d[i..(i + n).min(len)].to_vec();
                let j = at(*q, len);
                d.splice(j..j, run);
            }
            Mutation::Token(p, k) => {
                // Replace the alphanumeric run (or the character) at p.
                let i = at(*p, len);
                let is_word = |c: u8| c.is_ascii_alphanumeric() || b".-_+".contains(&c);
                let (mut s, mut e) = (i, i);
                while s > 0 && is_word(d[s - 1]) {
                    s -= 1;
                }
                while e < len && is_word(d[e]) {
                    e += 1;
                }
                let e = e.max((s + 1).min(len));
                d.splice(s..e, TOKENS[k % TOKENS.len()].bytes());
            }
            _ => {}
        }
    }
    d
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let f = 0.0f64..1.0;
    prop_oneof![
        (f.clone(), any::<u8>()).prop_map(|(p, b)| Mutation::FlipBit(p, b)),
        (f.clone(), any::<u8>()).prop_map(|(p, b)| Mutation::SetByte(p, b)),
        f.clone().prop_map(Mutation::Truncate),
        (f.clone(), prop::collection::vec(any::<u8>(), 1..16))
            .prop_map(|(p, b)| Mutation::Insert(p, b)),
        (f.clone(), 1usize..64).prop_map(|(p, n)| Mutation::Delete(p, n)),
        (f.clone(), 1usize..256, f.clone()).prop_map(|(p, n, q)| Mutation::Duplicate(p, n, q)),
        (f, any::<usize>()).prop_map(|(p, k)| Mutation::Token(p, k)),
    ]
}

/// Runs `check` on mutated copies of `seeds` (`cases()` cases).
fn fuzz(seeds: &[Vec<u8>], check: impl FnMut(&[u8])) {
    let check = std::cell::RefCell::new(check);
    // Deterministic by default so CI is reproducible; TEXPLORE_FUZZ_SEED=N explores elsewhere.
    let seed: u64 = std::env::var("TEXPLORE_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &key);
    let config = Config {
        cases: cases(),
        failure_persistence: None,
        ..Config::default()
    };
    let mut runner = TestRunner::new_with_rng(config, rng);
    let strategy = (0..seeds.len(), prop::collection::vec(mutation(), 1..6));
    runner
        .run(&strategy, |(seed, muts)| {
            (check.borrow_mut())(&apply(&seeds[seed], &muts));
            Ok(())
        })
        .unwrap();
}

fn preset_seeds() -> Vec<Vec<u8>> {
    let mut seeds: Vec<Vec<u8>> = std::fs::read_dir(root().join("presets"))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    seeds.sort();
    seeds
}

#[test]
fn mutated_presets_never_panic() {
    let seeds = preset_seeds();
    assert!(seeds.len() >= 5);
    let path = root().join("presets/fuzzed.ron");
    let mut cache = AssetCache::new();
    let (mut ok, mut refused) = (0, 0);
    fuzz(&seeds, |data| match preset_bytes(data, &path, &mut cache) {
        Ok(()) => ok += 1,
        Err(_) => refused += 1,
    });
    eprintln!("presets: {ok} built and rendered, {refused} refused");
    // Both outcomes must occur, or the mutations are not reaching the parser's interesting parts.
    assert!(ok > 0 && refused > 0, "ok {ok}, refused {refused}");
}

/// A small image of every format the loader reads, encoded by the `image` crate.
fn image_seeds(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let rgb = image::RgbImage::from_fn(7, 5, |x, y| {
        image::Rgb([(x * 36) as u8, (y * 50) as u8, 99])
    });
    let hdr =
        image::Rgb32FImage::from_fn(7, 5, |x, y| image::Rgb([x as f32 * 10.0, y as f32, 0.5]));
    let grey16 = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(5, 3, |x, _| {
        image::Luma([x as u16 * 9000])
    });
    let mut out = Vec::new();
    for ext in ["png", "jpg", "tif", "ppm"] {
        let p = dir.join(format!("seed.{ext}"));
        rgb.save(&p).unwrap();
        out.push((ext.to_string(), std::fs::read(&p).unwrap()));
    }
    for ext in ["hdr", "exr"] {
        let p = dir.join(format!("seed.{ext}"));
        image::DynamicImage::ImageRgb32F(hdr.clone())
            .save(&p)
            .unwrap();
        out.push((ext.to_string(), std::fs::read(&p).unwrap()));
    }
    let p = dir.join("seed16.png");
    grey16.save(&p).unwrap();
    out.push(("png".into(), std::fs::read(&p).unwrap()));
    out.push((
        "ppm".into(),
        b"P3\n3 2\n255\n255 0 0 0 255 0 0 0 255\n1 2 3 4 5 6 7 8 9\n".to_vec(),
    ));
    out
}

#[test]
fn mutated_images_of_every_format_never_panic() {
    let dir = tempfile::tempdir().unwrap();
    let seeds = image_seeds(dir.path());
    let bytes: Vec<Vec<u8>> = seeds.iter().map(|(_, b)| b.clone()).collect();
    let (mut ok, mut refused) = (0, 0);
    fuzz(&bytes, |data| {
        // Keep the extension of a seed of the same magic so extension-sniffing paths run too.
        let ext = seeds
            .iter()
            .find(|(_, b)| b.len() >= 4 && data.starts_with(&b[..4]))
            .map_or("bin", |(e, _)| e.as_str());
        match image_bytes(data, &dir.path().join(format!("fuzzed.{ext}"))) {
            Ok(_) => ok += 1,
            Err(_) => refused += 1,
        }
    });
    eprintln!("images: {ok} decoded, {refused} refused");
    assert!(ok > 0 && refused > 0, "ok {ok}, refused {refused}");
}

/// Screenshots: a PNG render of a preset (the preset in its text chunk), mutated.
#[test]
fn mutated_screenshots_never_panic() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("shot.png");
    success(&texplore(&[
        "render",
        "presets/checker.ron",
        "-o",
        png.to_str().expect("a UTF-8 temporary path"),
        "--width",
        "16",
        "--height",
        "12",
        "--spp",
        "1",
    ]));
    let seeds = vec![std::fs::read(&png).unwrap()];
    let target = dir.path().join("fuzzed.png");
    let (mut ok, mut refused) = (0, 0);
    fuzz(&seeds, |data| match screenshot_bytes(data, &target) {
        Ok(_) => ok += 1,
        Err(_) => refused += 1,
    });
    eprintln!("screenshots: {ok} restored, {refused} refused");
    assert!(ok > 0 && refused > 0, "ok {ok}, refused {refused}");
}

/// The lecture's PLY as printed.
const LECTURE_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement face 2\nproperty list int int vertex_indices\nend_header\n-1.0 0.0 -1.0 0.0 0.0\n-1.0 -1.0 1.0 1.0 0.0\n1.0 0.0 1.0 1.0 1.0\n1.0 -1.0 -1.0 0.0 1.0\n3 0 1 2\n3 0 2 3\n";

/// Seeds for the mesh readers: the lecture's PLY, a PLY with `s t`, normals, a comment, an extra
/// element and a quad; binary PLYs of a torus in both byte orders; an OBJ with `vt`, `vn` and a
/// quad. The first byte says which reader (even: PLY, odd: OBJ), as in the cargo-fuzz target.
fn mesh_seeds() -> Vec<Vec<u8>> {
    use texplore::meshio::{PlyFormat, torus, write_ply};
    let tagged = |tag: u8, body: &[u8]| [&[tag][..], body].concat();
    let mut seeds = vec![
        tagged(0, LECTURE_PLY.as_bytes()),
        tagged(0, b"ply\nformat ascii 1.0\ncomment a quad\nobj_info made by hand\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\nelement face 1\nproperty list uchar uint vertex_index\nelement edge 1\nproperty int a\nproperty int b\nend_header\n0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n4 0 1 2 3\n0 1\n"),
        tagged(1, b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf -1/-1/-1 -2/-2/-1 -3/-3/-1\n"),
    ];
    let torus = torus(6, 4, 1.0, 0.3);
    for format in [PlyFormat::BinaryLittleEndian, PlyFormat::BinaryBigEndian] {
        let mut bytes = Vec::new();
        write_ply(&mut bytes, &torus, format).unwrap();
        seeds.push(tagged(0, &bytes));
    }
    seeds
}

#[test]
fn mutated_meshes_never_panic() {
    let dir = tempfile::tempdir().unwrap();
    let seeds = mesh_seeds();
    let (mut ok, mut refused) = (0, 0);
    fuzz(&seeds, |data| {
        let Some((&pick, body)) = data.split_first() else {
            return;
        };
        let ext = if pick % 2 == 0 { "ply" } else { "obj" };
        match mesh_bytes(body, &dir.path().join(format!("fuzzed.{ext}"))) {
            Ok(()) => ok += 1,
            Err(_) => refused += 1,
        }
    });
    eprintln!("meshes: {ok} loaded and traced, {refused} refused");
    assert!(ok > 0 && refused > 0, "ok {ok}, refused {refused}");
}

/// Seeds for the material library: the `fuzz/seeds/material` files (a `map_Kd` library and a
/// colour-only one with other statements).
fn material_seeds() -> Vec<Vec<u8>> {
    let dir = root().join("fuzz/seeds/material");
    let mut seeds: Vec<Vec<u8>> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| std::fs::read(e.unwrap().path()).unwrap())
        .collect();
    seeds.sort();
    seeds
}

#[test]
fn mutated_material_libraries_never_panic() {
    let dir = tempfile::tempdir().unwrap();
    let seeds = material_seeds();
    assert!(seeds.len() >= 2);
    let (mut ok, mut refused) = (0, 0);
    fuzz(&seeds, |data| match material_bytes(data, dir.path()) {
        Ok(()) => ok += 1,
        Err(_) => refused += 1,
    });
    eprintln!("material libraries: {ok} built and rendered, {refused} refused");
    assert!(ok > 0 && refused > 0, "ok {ok}, refused {refused}");
}

/// Every input that once broke a parser, replayed: `tests/fuzz_regressions/<target>-<name>`.
#[test]
fn fuzz_regressions_stay_fixed() {
    let dir = root().join("tests/fuzz_regressions");
    let entries = std::fs::read_dir(&dir).unwrap_or_else(|e| {
        panic!(
            "{}: {e} (the regression inputs must be there)",
            dir.display()
        )
    });
    let scratch = tempfile::tempdir().unwrap();
    let mut cache = AssetCache::new();
    let mut replayed = 0;
    for e in entries {
        let e = e.unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        let name = e.file_name().to_string_lossy().into_owned();
        let data = std::fs::read(e.path()).unwrap_or_else(|err| panic!("{name}: {err}"));
        replayed += usize::from(name != "README.md");
        if name.starts_with("preset-") {
            let _ = preset_bytes(&data, &root().join("presets/fuzzed.ron"), &mut cache);
        } else if let Some(rest) = name.strip_prefix("image-") {
            let ext = Path::new(rest)
                .extension()
                .map_or("bin".into(), |x| x.to_string_lossy().into_owned());
            let _ = image_bytes(&data, &scratch.path().join(format!("fuzzed.{ext}")));
        } else if let Some(rest) = name.strip_prefix("mesh-") {
            let is_obj = Path::new(rest)
                .extension()
                .is_some_and(|x| x.eq_ignore_ascii_case("obj"));
            let ext = if is_obj { "obj" } else { "ply" };
            let _ = mesh_bytes(&data, &scratch.path().join(format!("fuzzed.{ext}")));
        } else if name.starts_with("material-") {
            let _ = material_bytes(&data, scratch.path());
        } else if name.starts_with("screenshot-") {
            let _ = screenshot_bytes(&data, &scratch.path().join("fuzzed.png"));
        } else if name != "README.md" {
            panic!("{name}: a regression input must start with a target name");
        }
    }
    assert!(
        replayed > 0,
        "{}: no regression input to replay",
        dir.display()
    );
}
