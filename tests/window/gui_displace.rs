//! The scene panel's displacement editor, driven headless with `egui_kittest` as a user would,
//! on the `displaced` preset's torus knot (6144 triangles, 1-2 levels, so the rebuilds stay
//! fast): switching it on moves the knot's outline, a drag of its scale rebuilds the mesh once
//! (when it ends), too many levels shows the builder's error and keeps the scene, each edit is
//! one undo step, and a generic shape offers no displacement.

use crate::gui_common::{choose, desc, harness, image_bytes, select, settle, small_earth, undo};
use egui::accesskit::Role;
use egui_kittest::kittest::Queryable as _;
use std::path::{Path, PathBuf};
use texplore::math::Vec2;
use texplore::names::Named;
use texplore::scene::{
    AssetCache, DisplaceDesc, SceneDesc, TextureKind, build_scene, load_preset, save_preset,
};

/// The `displaced` preset at 160 x 120 and 4 spp, with its gravel image copied beside it, the
/// displaced knot removed (the bumped one is the object edited), after `edit`.
fn small_displaced(dir: &Path, edit: impl FnOnce(&mut SceneDesc)) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut d = load_preset(&root.join("presets/displaced.ron")).expect("preset");
    d.render.width = 160;
    d.render.height = 120;
    d.render.spp = 4;
    assert_eq!(d.objects[2].name, "Displaced knot");
    d.objects.truncate(2);
    assert!(d.objects[1].bump.is_some() && d.objects[1].displace.is_none());
    edit(&mut d);
    std::fs::create_dir_all(dir.join("presets")).expect("presets folder");
    std::fs::create_dir_all(dir.join("assets")).expect("assets folder");
    for a in ["gravel_gray_512.png", "torus-knot.ply"] {
        std::fs::copy(root.join("assets").join(a), dir.join("assets").join(a)).expect("copy");
    }
    let path = dir.join("presets/displaced-small.ron");
    save_preset(&d, &path).expect("write preset");
    path
}

/// Per pixel (row by row), the object the camera ray at its centre hits, if any.
fn objects_hit(d: &SceneDesc, preset: &Path) -> Vec<Option<usize>> {
    let scene = build_scene(d, preset, &mut AssetCache::new()).expect("build");
    let (w, h) = (d.render.width, d.render.height);
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            scene
                .inspect(Vec2::new(x as f32 + 0.5, y as f32 + 0.5))
                .map(|i| i.object)
        })
        .collect()
}

#[test]
fn switching_displacement_on_moves_the_knots_outline_and_undo_restores_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = small_displaced(dir.path(), |_| {});
    let mut h = harness(preset.clone());
    select(&mut h, "1: Bumped knot");
    let before = desc(&h);
    let image_before = image_bytes(&h);
    let viewport = h.get_by_label("Rendered image").rect();

    choose(&mut h, "displacement", TextureKind::Image.name());
    assert!(h.state().error().is_none(), "{:?}", h.state().error());

    // The preset's field: the bump map's own heights and scale, at the default levels.
    let after = desc(&h);
    let bump = before.objects[1].bump.clone().expect("a bump map");
    assert_eq!(
        after.objects[1].displace,
        Some(DisplaceDesc {
            height: bump.height.clone(),
            scale: bump.scale,
            subdivide: 2,
        })
    );
    let mut same = after.clone();
    same.objects[1].displace = None;
    assert_eq!(same, before, "nothing else changed");
    assert_eq!(h.get_by_label("Rendered image").rect(), viewport);

    // The silhouette: the heights only push out, so pixels that saw the floor or the sky
    // now see the knot, and none the other way round.
    let (was, is) = (objects_hit(&before, &preset), objects_hit(&after, &preset));
    let grown = was
        .iter()
        .zip(&is)
        .filter(|(a, b)| **a != Some(1) && **b == Some(1))
        .count();
    let shrunk = was
        .iter()
        .zip(&is)
        .filter(|(a, b)| **a == Some(1) && **b != Some(1))
        .count();
    assert!(grown >= 40, "only {grown} pixels joined the knot's outline");
    assert!(
        shrunk * 10 <= grown,
        "{shrunk} pixels left the knot, {grown} joined it"
    );
    let image_after = image_bytes(&h);
    let changed = image_before
        .chunks(4)
        .zip(image_after.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed >= grown, "{changed} pixels changed");

    // One step: undo gives back the bump-mapped knot and its image.
    assert_eq!(h.state().undo_label(), Some("displacement of Bumped knot"));
    undo(&mut h);
    assert_eq!(desc(&h), before);
    assert_eq!(image_bytes(&h), image_before);
}

#[test]
fn a_scale_drag_rebuilds_once_when_it_ends_and_off_and_on_brings_it_back() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = small_displaced(dir.path(), |d| {
        let bump = d.objects[1].bump.take().expect("a bump map");
        d.objects[1].displace = Some(DisplaceDesc {
            height: bump.height,
            scale: 0.15,
            subdivide: 1,
        });
    });
    let mut h = harness(preset);
    select(&mut h, "1: Bumped knot");
    let before = desc(&h);
    let image_before = image_bytes(&h);
    let scale = |d: &SceneDesc| d.objects[1].displace.as_ref().expect("displaced").scale;
    assert_eq!(
        h.get_by_label("displacement scale").value().as_deref(),
        Some("0.150")
    );

    // Drag the scale to the right: while the button is down the field shows the new value
    // but the scene (and so the mesh) stays as it was.
    let field = h.get_by_label("displacement scale");
    field.scroll_to_me();
    h.run_steps(3);
    let from = h.get_by_label("displacement scale").rect().center();
    h.hover_at(from);
    h.run_steps(2);
    h.drag_at(from);
    h.step();
    for i in 1..=8 {
        h.hover_at(from + egui::vec2(10.0 * i as f32, 0.0));
        h.step();
    }
    // The field reports the value it started the frame with: one still frame more.
    h.step();
    let shown: f32 = h
        .get_by_label("displacement scale")
        .value()
        .expect("a value")
        .parse()
        .expect("a number");
    assert!(shown > 0.16, "the field follows the drag: {shown}");
    assert_eq!(desc(&h), before, "nothing applied during the drag");
    assert!(
        h.query_all_by_label_contains("(on release)")
            .next()
            .is_some()
    );
    h.drop_at(from + egui::vec2(80.0, 0.0));
    settle(&mut h);

    // Released: applied once, one undo step, a new image.
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    let dragged = desc(&h);
    assert!(
        (scale(&dragged) - shown).abs() < 1e-6,
        "{} against {shown}",
        scale(&dragged)
    );
    assert_ne!(image_bytes(&h), image_before);
    assert_eq!(h.state().undo_label(), Some("displacement of Bumped knot"));
    undo(&mut h);
    assert_eq!(desc(&h), before, "one step undoes the whole drag");
    assert_eq!(image_bytes(&h), image_before);

    // A typed value (here set as a screen reader does) applies at once.
    h.get_by_label("displacement scale")
        .set_value_accesskit(0.05);
    settle(&mut h);
    let typed = desc(&h);
    assert!((scale(&typed) - 0.05).abs() < 1e-6, "{}", scale(&typed));

    // Off, then on again: the same displacement, edited scale and all.
    choose(&mut h, "displacement", "None");
    assert_eq!(desc(&h).objects[1].displace, None);
    assert_eq!(h.state().undo_label(), Some("displacement of Bumped knot"));
    choose(&mut h, "displacement", TextureKind::Image.name());
    assert_eq!(desc(&h), typed);
}

#[test]
fn too_many_levels_show_the_builders_error_and_keep_the_scene() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = small_displaced(dir.path(), |d| {
        let bump = d.objects[1].bump.clone().expect("a bump map");
        d.objects[1].displace = Some(DisplaceDesc {
            height: bump.height,
            scale: 0.15,
            subdivide: 1,
        });
    });
    let mut h = harness(preset);
    select(&mut h, "1: Bumped knot");
    let before = desc(&h);
    let image_before = image_bytes(&h);
    assert_eq!(h.state().undo_label(), None);

    // 6144 triangles x 4^5 is over the 4 M limit.
    choose(&mut h, "subdivision levels", "5 (x1024)");
    let Some(err) = h.state().error().map(str::to_owned) else {
        panic!("no error; the scene: {:?}", desc(&h).objects[1].displace);
    };
    assert!(
        err.contains(
            "objects[1].displace.subdivide (object \"Bumped knot\"): 5 levels would make 6291456 triangles"
        ),
        "{err}"
    );
    assert!(err.contains("use fewer levels"), "{err}");
    assert_eq!(
        h.query_all_by_label_contains("5 levels would make").count(),
        1,
        "the window shows the error once"
    );
    assert_eq!(desc(&h), before, "the scene stays");
    assert_eq!(image_bytes(&h), image_before, "the render stays");
    assert_eq!(h.state().undo_label(), None, "no undo step");
    assert_eq!(
        h.get_by_role_and_label(Role::ComboBox, "subdivision levels")
            .value()
            .as_deref(),
        Some("1 (x4)"),
        "the menu shows the levels the scene has"
    );

    // Two levels build: one step, and undo goes back to one.
    choose(&mut h, "subdivision levels", "2 (x16)");
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(
        desc(&h).objects[1].displace.as_ref().map(|d| d.subdivide),
        Some(2)
    );
    assert_ne!(image_bytes(&h), image_before);
    assert_eq!(h.state().undo_label(), Some("displacement of Bumped knot"));
    undo(&mut h);
    assert_eq!(desc(&h), before);
    assert_eq!(image_bytes(&h), image_before);

    // A displaced mesh made a sphere: no error (the builder refuses a displaced sphere), the
    // displacement waits, and undo brings the knot back displaced.
    choose(&mut h, "Shape", "Sphere");
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(desc(&h).objects[1].displace, None);
    assert!(
        h.query_by_label("displacement").is_none(),
        "a sphere has no displacement editor"
    );
    assert_eq!(h.state().undo_label(), Some("shape of Bumped knot"));

    // A mesh again, then displacement on: it comes back as it was.
    choose(&mut h, "Shape", "Mesh");
    h.get_by_role_and_label(Role::TextInput, "mesh file")
        .set_text_value_accesskit("../assets/torus-knot.ply");
    h.step();
    // The Load on the mesh field's row (the bump map's image has one too).
    let row = h
        .get_by_role_and_label(Role::TextInput, "mesh file")
        .rect()
        .center()
        .y;
    h.get_all_by_label("Load")
        .min_by(|a, b| {
            let (da, db) = (a.rect().center().y - row, b.rect().center().y - row);
            da.abs().total_cmp(&db.abs())
        })
        .expect("a Load button")
        .click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(desc(&h).objects[1].displace, None);
    choose(&mut h, "displacement", TextureKind::Image.name());
    assert_eq!(desc(&h).objects[1].displace, before.objects[1].displace);
    undo(&mut h);
    undo(&mut h);
    undo(&mut h);
    assert_eq!(desc(&h), before);
    assert_eq!(image_bytes(&h), image_before);
}

#[test]
fn a_sphere_offers_no_displacement() {
    let dir = tempfile::tempdir().expect("temp dir");
    let h = harness(small_earth(dir.path()));
    let before = desc(&h);
    // The maps are there, the displacement editor is not; the bump map's tooltip says only a
    // mesh can be displaced.
    assert!(
        h.query_by_role_and_label(Role::ComboBox, "bump map")
            .is_some()
    );
    assert!(h.query_by_label("Displacement").is_none());
    assert!(h.query_by_label("displacement").is_none());
    assert!(h.query_by_label("displacement scale").is_none());
    assert!(h.query_by_label("subdivision levels").is_none());
    assert_eq!(desc(&h), before);
    assert_eq!(h.state().undo_label(), None);
}
