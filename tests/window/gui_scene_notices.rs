//! The summed-area tables' warnings in the window (issue 38 §2): when a footprint filter's
//! tables do not fit what is left of the scene's texture budget, the filter reads EWA instead
//! and the status line says so, as `texplore render` warns on the command line.

use crate::gui_common::{harness, settle};
use egui_kittest::kittest::{NodeT as _, Queryable as _};

/// Two spheres, each with its own 256 x 256 PNG under the footprint filter.
fn two_footprint_spheres(dir: &std::path::Path) -> std::path::PathBuf {
    for (i, name) in ["a.png", "b.png"].iter().enumerate() {
        let img = image::GrayImage::from_fn(256, 256, |x, y| {
            image::Luma([((x + y + 40 * i as u32) % 256) as u8])
        });
        img.save(dir.join(name)).unwrap();
    }
    let sphere = |x: f32, image: &str| {
        format!(
            r#"(shape: Sphere, transform: (translate: ({x}, 0, 0)),
        material: Matte(ka: 0.6, kd: 0.85, cd: Image(path: "{image}", mapping: Spherical, filter: Footprint)))"#
        )
    };
    let preset = format!(
        "(\n    version: 1,\n    camera: (eye: (0, 0, 7), projection: Pinhole(fov: 40)),\n    \
         render: (width: 96, height: 64, spp: 1),\n    objects: [{}, {}],\n)",
        sphere(-1.25, "a.png"),
        sphere(1.25, "b.png")
    );
    let path = dir.join("two.ron");
    std::fs::write(&path, preset).unwrap();
    path
}

#[test]
fn tables_over_the_texture_budget_show_a_warning_in_the_status_line() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(two_footprint_spheres(dir.path()));
    // Under the 1 GiB budget both images have their tables: nothing to say.
    assert!(h.state().scene_notices().is_empty());
    assert!(h.query_by_label_contains("summed-area").is_none());

    // Under 1 MiB, the images (256 KiB each) and their mip pyramids fit, their tables (1 MiB
    // each, 12 bytes a texel and a third) do not.
    h.state_mut().set_texture_budget(1 << 20);
    settle(&mut h);
    let notices = h.state().scene_notices().to_vec();
    assert_eq!(notices.len(), 2, "{notices:?}");
    for (n, file) in notices.iter().zip(["a.png", "b.png"]) {
        assert!(
            n.contains(file)
                && n.contains("its summed-area tables need ")
                && n.contains("the footprint filter reads it with EWA instead"),
            "{n}"
        );
    }
    let shown = h
        .query_by_label_contains("2 warnings: ")
        .expect("the warnings are in the status line");
    let node = shown.accesskit_node();
    let text = node.value().or_else(|| node.label()).unwrap_or_default();
    assert!(
        text.contains("a.png: its summed-area tables need"),
        "the status line shows the first warning: {text}"
    );
    // Back under the full budget, the tables fit and the warnings go.
    h.state_mut()
        .set_texture_budget(texplore::scene::MAX_SCENE_TEXEL_BYTES);
    settle(&mut h);
    assert!(h.state().scene_notices().is_empty());
    assert!(h.query_by_label_contains("warnings: ").is_none());
}
