//! Harnesses that feed arbitrary bytes to every parser a user's file reaches, shared by the
//! cargo-fuzz targets in `fuzz/` and the bounded fuzz test in `tests/headless/fuzz.rs`.
//!
//! Each harness returns the library's result for the input and panics only when an invariant a
//! user relies on is broken: a parser panicked, an error does not name the file, a loaded image
//! exceeds the decode limits or holds a non-finite texel, or a scene that built renders NaN. A
//! panic here is a finding; an `Err` is the correct answer to bad input.

use crate::error::{Error, Result};
use crate::render::render_blocking;
use crate::scene::{AssetCache, Overrides, apply_overrides, build_scene, parse_preset};
use crate::texture::{ImageData, MAX_IMAGE_DIMENSION, load_image};
use std::path::Path;

/// Largest render a fuzzed preset is rendered at: enough to reach every shape, texture and
/// mapping of the scene, small enough for thousands of executions a second.
const FUZZ_RENDER: (u32, u32) = (8, 6);

/// Panics unless `e`'s message names `path` (the promise every error of texplore keeps).
fn assert_names(e: &Error, path: &Path) {
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let msg = e.to_string();
    assert!(
        msg.contains(&name),
        "the error does not name the file {name}: {msg}"
    );
    assert!(msg.len() < 4096, "an error message of {} bytes", msg.len());
}

/// Parses `data` as a preset at `preset_path` (asset paths resolve beside it, through `cache`),
/// builds it, and renders it at 8x6, 1 spp.
///
/// # Errors
/// What the parser or the scene build refused, naming `preset_path`.
///
/// # Panics
/// When an invariant breaks (see the module docs): that is a bug in texplore.
pub fn preset_bytes(data: &[u8], preset_path: &Path, cache: &mut AssetCache) -> Result<()> {
    let text = String::from_utf8_lossy(data);
    let result = parse_preset(&text, preset_path).and_then(|mut desc| {
        apply_overrides(
            &mut desc,
            Overrides {
                width: Some(FUZZ_RENDER.0),
                height: Some(FUZZ_RENDER.1),
                spp: Some(1),
                ..Overrides::default()
            },
        );
        let scene = build_scene(&desc, preset_path, cache)?;
        let film = render_blocking(&scene, |_| {});
        assert!(film.is_finite(), "a preset that built rendered NaN or Inf");
        Ok(())
    });
    if let Err(e) = &result {
        // Asset errors name the asset, not the preset; everything else names the preset.
        if !matches!(e, Error::Image { .. } | Error::Io { .. }) {
            assert_names(e, preset_path);
        }
    }
    result
}

/// Writes `data` to `path` and loads it as an image the way a preset's texture is loaded.
///
/// # Errors
/// The decoder's refusal, naming `path`.
///
/// # Panics
/// When an invariant breaks (see the module docs), or `path` cannot be written.
pub fn image_bytes(data: &[u8], path: &Path) -> Result<ImageData> {
    std::fs::write(path, data).expect("the fuzz harness cannot write its scratch file");
    match load_image(path, true) {
        Ok(img) => {
            assert!(img.width() >= 1 && img.height() >= 1);
            assert!(img.width() <= MAX_IMAGE_DIMENSION && img.height() <= MAX_IMAGE_DIMENSION);
            for y in 0..img.height() {
                for x in 0..img.width() {
                    assert!(img.texel_top(x, y).is_finite(), "non-finite texel");
                }
            }
            Ok(img)
        }
        Err(e) => {
            assert_names(&e, path);
            Err(e)
        }
    }
}

/// Writes `data` to `path` (a `.png`) and reads the preset a texplore screenshot carries, the
/// way opening or dropping a PNG on the window does.
///
/// # Errors
/// Not a PNG, no preset inside, or a preset that does not parse, naming `path`.
///
/// # Panics
/// When an invariant breaks (see the module docs), or `path` cannot be written.
pub fn screenshot_bytes(data: &[u8], path: &Path) -> Result<crate::scene::SceneDesc> {
    std::fs::write(path, data).expect("the fuzz harness cannot write its scratch file");
    let result = crate::scene::read_preset_or_png(path);
    if let Err(e) = &result {
        assert_names(e, path);
    }
    result
}

/// Writes `data` to `path` (`.ply` or `.obj`), reads it as a mesh, builds its BVH and shoots rays
/// at it from around its bounding box, as loading a mesh into a scene and rendering it does.
///
/// # Errors
/// The reader's or the validation's refusal, naming `path`.
///
/// # Panics
/// When an invariant breaks (see the module docs): a NaN in a hit, a (u, v) outside the file's
/// values, or a reader that panicked.
pub fn mesh_bytes(data: &[u8], path: &Path) -> Result<()> {
    use crate::geometry::{Mesh, Shading};
    use crate::math::{Ray, Vec3A};
    use strum::VariantArray;
    std::fs::write(path, data).expect("the fuzz harness cannot write its scratch file");
    let result = crate::meshio::load_mesh(path).and_then(|d| Mesh::new(d, path));
    let mesh = match result {
        Ok(m) => m,
        Err(e) => {
            assert_names(&e, path);
            return Err(e);
        }
    };
    let b = mesh.bbox();
    let (lo, hi) = (Vec3A::from(b.min), Vec3A::from(b.max));
    let centre = (lo + hi) * 0.5;
    let reach = (hi - lo).length().max(1.0);
    if !(reach.is_finite() && centre.is_finite()) {
        return Ok(()); // coordinates near f32::MAX: no ray from outside the box is finite
    }
    for i in 0..64u32 {
        // Rays from a sphere around the box toward points inside it.
        let a = i as f32 * 2.399_963; // golden angle
        let z = 1.0 - (i as f32 + 0.5) / 32.0;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let dir_out = Vec3A::new(r * a.cos(), z, r * a.sin());
        let target = lo + (hi - lo) * Vec3A::new(0.5 + 0.4 * a.sin(), 0.5, 0.5 + 0.4 * a.cos());
        let origin = centre + dir_out * reach * 2.0;
        let ray = Ray::new(origin, target - origin);
        for &shading in Shading::VARIANTS {
            if let Some(h) = mesh.intersect(&ray, f32::INFINITY, shading) {
                assert!(h.t.is_finite() && h.p.is_finite(), "hit {h:?}");
                assert!(h.n.is_finite() && h.ns.is_finite(), "normal {h:?}");
                if let Some(uv) = h.uv {
                    assert!(uv.is_finite(), "uv {h:?}");
                }
                if let Some((dpdu, dpdv)) = h.dpduv {
                    assert!(dpdu.is_finite() && dpdv.is_finite(), "dp/du {h:?}");
                }
            }
        }
    }
    Ok(())
}

/// The OBJ [`material_bytes`] pairs with the fuzzed library: a textured quad using material
/// `m` from `fuzzed.mtl`.
const MATERIAL_OBJ: &str = "mtllib fuzzed.mtl\nusemtl m\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n\
                            vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";

/// Writes `data` as the material library `fuzzed.mtl` in `dir`, beside an OBJ quad that uses its
/// material `m` and a 2x2 image `label.png` a `map_Kd` may name; loads the OBJ, then builds
/// and renders (8x6, 1 spp) a scene showing the quad through its `MeshMaterial`, as a preset
/// naming an OBJ does.
///
/// # Errors
/// The library's refusal (naming `fuzzed.mtl`), or the scene's (naming the preset or the image).
///
/// # Panics
/// When an invariant breaks (see the module docs), or the scratch files cannot be written.
pub fn material_bytes(data: &[u8], dir: &Path) -> Result<()> {
    let mtl = dir.join("fuzzed.mtl");
    let obj = dir.join("fuzzed.obj");
    let label = dir.join("label.png");
    std::fs::write(&mtl, data).expect("the fuzz harness cannot write its scratch file");
    std::fs::write(&obj, MATERIAL_OBJ).expect("the fuzz harness cannot write its scratch file");
    if !label.exists() {
        crate::texture::save_png(
            &label,
            2,
            2,
            &[200, 10, 10, 10, 200, 10, 10, 10, 200, 90, 90, 90],
            &[],
        )
        .expect("the fuzz harness cannot write its scratch image");
    }
    let data = crate::meshio::read_obj(&obj).inspect_err(|e| assert_names(e, &obj))?;
    if let Some(problem) = data.material_problem.as_deref() {
        assert!(
            problem.contains("fuzzed.mtl"),
            "a material problem that does not name the library: {problem}"
        );
    }
    let preset = dir.join("fuzzed.ron");
    let text = "(version: 1, camera: (eye: (0, 3, 0.01)), render: (width: 8, height: 6, spp: 1), \
                objects: [(shape: Mesh(path: \"fuzzed.obj\"), material: Matte(cd: MeshMaterial()))])";
    let desc = parse_preset(text, &preset).expect("the harness's own preset parses");
    match build_scene(&desc, &preset, &mut AssetCache::new()) {
        Ok(scene) => {
            let film = render_blocking(&scene, |_| {});
            assert!(
                film.is_finite(),
                "a material that built rendered NaN or Inf"
            );
            Ok(())
        }
        Err(e) => {
            if !matches!(e, Error::Image { .. } | Error::Io { .. }) {
                assert_names(&e, &preset);
            }
            Err(e)
        }
    }
}
