//! The scene panel's clip, bump and normal map editors and the (u, v) transform of the main
//! texture, driven headless with `egui_kittest` as a user would: each switch shows in the
//! preset's fields and in the pixels, bump and normal maps exclude each other, every edit is
//! one undo step, and a missing image leaves the scene as it was.

use crate::gui_common::{
    choose, desc, harness, harness_with, image_bytes, select, settle, small_earth, undo,
};
use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use std::path::{Path, PathBuf};
use texplore::gui::{AppOptions, BrowseFor, Browser, ExplorerApp};
use texplore::inspect::Inspection;
use texplore::math::Vec2;
use texplore::names::Named;
use texplore::scene::{
    AssetCache, ChannelDesc, MaterialDesc, ObjectDesc, ScalarDesc, SceneDesc, TextureDesc,
    TextureKind, build_scene, load_preset, save_preset,
};
use texplore::texture::{Channel, Lookup};

fn redo(h: &mut Harness<'_, ExplorerApp>) {
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    settle(h);
}

/// A built-in preset at 160 x 120 and 4 spp, written to `dir/presets` with copies of the
/// `assets` it reads in `dir/assets` (so its `../assets/...` paths hold), after `edit`.
fn small_preset(
    dir: &Path,
    name: &str,
    assets: &[&str],
    edit: impl FnOnce(&mut SceneDesc),
) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut desc = load_preset(&root.join("presets").join(format!("{name}.ron"))).expect("preset");
    desc.render.width = 160;
    desc.render.height = 120;
    desc.render.spp = 4;
    edit(&mut desc);
    std::fs::create_dir_all(dir.join("presets")).expect("presets folder");
    std::fs::create_dir_all(dir.join("assets")).expect("assets folder");
    for a in assets {
        std::fs::copy(root.join("assets").join(a), dir.join("assets").join(a)).expect("copy");
    }
    let path = dir.join("presets").join(format!("{name}-small.ron"));
    save_preset(&desc, &path).expect("write preset");
    path
}

const BOARD_IMAGE: &str = "cutout_holes_256.png";

/// The `cutout` preset with its board solid (no clip map).
fn solid_board(dir: &Path) -> PathBuf {
    small_preset(dir, "cutout", &[BOARD_IMAGE], |d| {
        assert!(
            d.objects[1].alpha.is_some(),
            "the preset's board is clip-mapped"
        );
        d.objects[1].alpha = None;
    })
}

const BUMP_ASSETS: [&str; 3] = [
    "brick_gray_512.png",
    "brick_normal_512.png",
    "gravel_gray_512.png",
];

/// What the renderer does at the centre of pixel (x, y).
fn inspect_all(desc: &SceneDesc, preset: &Path) -> Vec<Option<Inspection>> {
    let scene = build_scene(desc, preset, &mut AssetCache::new()).expect("build");
    let (w, h) = (desc.render.width, desc.render.height);
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| scene.inspect(Vec2::new(x as f32 + 0.5, y as f32 + 0.5)))
        .collect()
}

#[test]
fn switching_a_clip_map_on_cuts_the_board_where_its_alpha_is_zero() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = solid_board(dir.path());
    let mut h = harness(preset.clone());
    select(&mut h, "1: Board");
    let before = desc(&h);
    let image_before = image_bytes(&h);
    let viewport = h.get_by_label("Rendered image").rect();

    choose(&mut h, "clip map", TextureKind::Image.name());
    assert!(h.state().error().is_none(), "{:?}", h.state().error());

    // The preset's field: the board's own image, read through its alpha (the PNG has one).
    let after = desc(&h);
    let board = &after.objects[1];
    assert_eq!(
        board.alpha,
        Some(ScalarDesc::Channel(ChannelDesc {
            texture: before.objects[1].material.texture().clone(),
            channel: Channel::Alpha,
        }))
    );
    assert_eq!(
        ObjectDesc {
            alpha: None,
            ..board.clone()
        },
        before.objects[1],
        "nothing else changed"
    );
    assert_eq!(
        h.get_by_label("Rendered image").rect(),
        viewport,
        "the image did not move"
    );

    // The pixels: where the board's texels around the pixel are all transparent, the floor
    // shows through; where they are all opaque, the board is as it was.
    let alpha = image::open(dir.path().join("assets").join(BOARD_IMAGE))
        .expect("board image")
        .to_rgba8();
    let around = |col: u32, row: u32| {
        let r = 10i64;
        let mut values = Vec::new();
        for dy in -r..=r {
            for dx in -r..=r {
                let (x, y) = (i64::from(col) + dx, i64::from(row) + dy);
                if (0..256).contains(&x) && (0..256).contains(&y) {
                    values.push(alpha.get_pixel(x as u32, y as u32)[3]);
                }
            }
        }
        values
    };
    let image_after = image_bytes(&h);
    let (mut holes, mut solid) = (0, 0);
    for (i, inspection) in inspect_all(&before, &preset).into_iter().enumerate() {
        let Some(ins) = inspection.filter(|ins| ins.object == 1) else {
            continue;
        };
        let Some(t) = ins.texels.iter().find(|t| t.lookup == Lookup::Centred) else {
            continue;
        };
        let values = around(t.column, t.file_row);
        let diff = (0..3)
            .map(|c| image_before[i * 4 + c].abs_diff(image_after[i * 4 + c]))
            .max()
            .unwrap_or(0);
        if values.iter().all(|&a| a == 0) {
            holes += 1;
            assert!(
                diff > 20,
                "pixel {i} is in a hole but did not change ({diff})"
            );
        } else if values.iter().all(|&a| a == 255) {
            solid += 1;
            assert!(
                diff <= 2,
                "pixel {i} is on solid board but changed by {diff}"
            );
        }
    }
    assert!(
        holes >= 30 && solid >= 100,
        "{holes} hole pixels, {solid} solid"
    );

    // One undo step brings the solid board back.
    assert_eq!(h.state().undo_label(), Some("clip map of Board"));
    undo(&mut h);
    assert_eq!(desc(&h), before);
    assert_eq!(image_bytes(&h), image_before);
}

#[test]
fn a_bump_map_switches_the_normal_map_off_and_undo_brings_it_back() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = small_preset(dir.path(), "bumps", &BUMP_ASSETS, |_| {});
    let mut h = harness(preset);
    select(&mut h, "2: Normal-mapped ball");
    let before = desc(&h);
    let normal = before.objects[2].normal.clone().expect("a normal map");
    assert!(before.objects[2].bump.is_none());
    let image_before = image_bytes(&h);
    let viewport = h.get_by_label("Rendered image").rect();
    let note = "The normal map is off";
    assert!(h.query_all_by_label_contains(note).next().is_none());

    choose(&mut h, "bump map", TextureKind::Image.name());
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    let after = desc(&h);
    let ball = &after.objects[2];
    assert!(ball.normal.is_none(), "the normal map is off");
    let bump = ball.bump.as_ref().expect("a bump map");
    // A first bump map starts on the first image in assets/, placed as the normal map it
    // replaces was (the colour is a constant, with no mapping).
    assert!(
        matches!(&bump.height, TextureDesc::Image { path, .. } if path.ends_with("brick_gray_512.png")),
        "{:?}",
        bump.height
    );
    assert_eq!(bump.height.mapping(), normal.map.mapping());
    assert_eq!(bump.height.uv_transform(), normal.map.uv_transform());
    assert!(bump.scale > 0.0);
    assert!(
        h.query_all_by_label_contains(note).next().is_some(),
        "the window says why the normal map went"
    );
    assert_ne!(image_bytes(&h), image_before, "the ball shades differently");
    assert_eq!(h.get_by_label("Rendered image").rect(), viewport);

    // One step: undo gives back the object as it was, normal map and all.
    assert_eq!(
        h.state().undo_label(),
        Some("bump map of Normal-mapped ball")
    );
    undo(&mut h);
    assert_eq!(desc(&h).objects[2], before.objects[2]);
    assert_eq!(desc(&h), before);
    assert_eq!(image_bytes(&h), image_before);
    assert!(h.query_all_by_label_contains(note).next().is_none());

    // Redo, then switch the normal map back on: it comes back as it was, and the bump map
    // goes, with the note saying so.
    redo(&mut h);
    assert!(desc(&h).objects[2].normal.is_none());

    // The bump scale: one edit, one step.
    let switched = desc(&h);
    h.get_by_label("bump scale").set_value_accesskit(0.05);
    settle(&mut h);
    let scale = |d: &SceneDesc| d.objects[2].bump.as_ref().expect("a bump map").scale;
    assert!(
        (scale(&desc(&h)) - 0.05).abs() < 1e-6,
        "{}",
        scale(&desc(&h))
    );
    assert_eq!(
        h.state().undo_label(),
        Some("bump map of Normal-mapped ball")
    );
    undo(&mut h);
    assert_eq!(desc(&h), switched);
    choose(&mut h, "normal map", TextureKind::Image.name());
    let again = desc(&h);
    assert_eq!(again.objects[2].normal.as_ref(), Some(&normal));
    assert!(again.objects[2].bump.is_none());
    assert!(
        h.query_all_by_label_contains("The bump map is off")
            .next()
            .is_some()
    );
    assert_eq!(image_bytes(&h), image_before, "the same render as at first");
}

#[test]
fn a_uv_scale_of_two_on_the_colour_texture_tiles_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = small_earth(dir.path());
    let mut h = harness(path.clone());
    let before = desc(&h);
    let image_before = image_bytes(&h);

    h.get_by_label("uv scale u").set_value_accesskit(2.0);
    settle(&mut h);

    let after = desc(&h);
    let uv = after.objects[0]
        .material
        .texture()
        .uv_transform()
        .expect("an image has a (u, v) transform");
    assert_eq!(
        uv.scale,
        Vec2::new(2.0, 1.0),
        "the preset's `uv: (scale: (2, 1))`"
    );
    assert_eq!(h.state().undo_label(), Some("texture settings of Earth"));

    // The Earth is there twice around: at the centre pixel u is doubled (and wrapped).
    let centre = Vec2::new(80.5, 60.5);
    let at = |d: &SceneDesc| {
        build_scene(d, &path, &mut AssetCache::new())
            .expect("build")
            .inspect(centre)
            .expect("the Earth at the centre")
            .wrapped_uv
            .expect("(u, v)")
    };
    let (u1, u2) = (at(&before).x, at(&after).x);
    assert!(
        ((2.0 * u1).fract() - u2).abs() < 1e-4,
        "u {u1} tiled by 2 is {u2}"
    );
    let image_after = image_bytes(&h);
    let changed = image_before
        .chunks(4)
        .zip(image_after.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed > 2000, "only {changed} pixels changed");

    undo(&mut h);
    assert_eq!(desc(&h), before);
}

/// Types `missing` into the image field `field` and loads it: one error naming the file, the
/// scene, the render and the undo history as they were, and the field showing the scene's
/// path again.
fn a_missing_image_is_refused(h: &mut Harness<'_, ExplorerApp>, field: &str, missing: &str) {
    let before = desc(h);
    let image_before = image_bytes(h);
    let undo_before = h.state().undo_label().map(str::to_owned);
    let shown = h
        .get_by_role_and_label(Role::TextInput, field)
        .value()
        .expect("a path");
    assert!(shown.starts_with("../assets/"), "{field}: {shown}");

    h.get_by_role_and_label(Role::TextInput, field)
        .scroll_to_me();
    h.run_steps(3);
    h.get_by_role_and_label(Role::TextInput, field).focus();
    h.step();
    h.get_by_role_and_label(Role::TextInput, field)
        .set_text_value_accesskit(missing);
    h.step();
    // The field's own Load, on the row below it (other image fields have one too).
    let below = h
        .get_by_role_and_label(Role::TextInput, field)
        .rect()
        .bottom();
    h.get_all_by_label("Load")
        .filter(|b| b.rect().top() >= below)
        .min_by(|a, b| a.rect().top().total_cmp(&b.rect().top()))
        .expect("a Load button")
        .click();
    settle(h);

    let Some(err) = h.state().error().map(str::to_owned) else {
        panic!("{field}: no error shown; the scene: {:?}", desc(h).objects);
    };
    assert!(err.contains(missing), "{err}");
    assert_eq!(
        h.query_all_by_label_contains(missing).count(),
        1,
        "one message in the window (the field shows the scene's path again)"
    );
    assert_eq!(desc(h), before, "{field}: the scene stays");
    assert_eq!(image_bytes(h), image_before, "{field}: the render stays");
    assert_eq!(
        h.get_by_role_and_label(Role::TextInput, field).value(),
        Some(shown)
    );
    assert_eq!(
        h.state().undo_label().map(str::to_owned),
        undo_before,
        "no undo step"
    );
}

#[test]
fn a_missing_map_image_shows_one_error_and_keeps_the_scene() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = small_preset(dir.path(), "bumps", &BUMP_ASSETS, |_| {});
    let mut h = harness(preset);
    select(&mut h, "1: Brick ball");
    a_missing_image_is_refused(&mut h, "height image", "../assets/missing-height.png");
    select(&mut h, "2: Normal-mapped ball");
    a_missing_image_is_refused(&mut h, "normal image", "../assets/missing-normal.png");
    // A clip map on the floor: its first image is the first in assets/ (no alpha channel, so
    // its luminance), on the bump map's mapping (the floor's colour is a constant).
    select(&mut h, "0: Floor");
    choose(&mut h, "clip map", TextureKind::Image.name());
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    let floor = desc(&h).objects[0].clone();
    let alpha = floor.alpha.as_ref().expect("a clip map");
    assert!(
        matches!(alpha, ScalarDesc::Texture(TextureDesc::Image { path, .. }) if path == "../assets/brick_gray_512.png"),
        "{alpha:?}"
    );
    let height = &floor.bump.as_ref().expect("the floor's bump map").height;
    let texture = alpha.texture().expect("a texture");
    assert_eq!(texture.mapping(), height.mapping());
    assert_eq!(texture.uv_transform(), height.uv_transform());
    a_missing_image_is_refused(&mut h, "alpha image", "../assets/missing-alpha.png");
}

#[test]
fn browse_beside_a_height_image_loads_the_chosen_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = small_preset(dir.path(), "bumps", &BUMP_ASSETS, |_| {});
    let gravel = dir.path().join("assets/gravel_gray_512.png");
    let asked = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let log = asked.clone();
    let options = AppOptions {
        browser: Browser::replaced_by(move |what, _, _| {
            log.lock().expect("lock").push(what);
            Some(gravel.clone())
        }),
        ..AppOptions::default()
    };
    let mut h = harness_with(preset, options);
    select(&mut h, "1: Brick ball");
    let before = desc(&h);
    let image_before = image_bytes(&h);
    let field = h
        .get_by_role_and_label(Role::TextInput, "height image")
        .rect();
    h.get_all_by_label("Browse…")
        .filter(|b| b.rect().top() >= field.bottom())
        .min_by(|a, b| a.rect().top().total_cmp(&b.rect().top()))
        .expect("a Browse… button")
        .click();
    settle(&mut h);

    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(*asked.lock().expect("lock"), vec![BrowseFor::Image]);
    let bump = desc(&h).objects[1].bump.clone().expect("a bump map");
    assert!(
        matches!(&bump.height, TextureDesc::Image { path, .. } if path == "../assets/gravel_gray_512.png"),
        "the path, relative to the preset: {:?}",
        bump.height
    );
    assert_eq!(
        h.get_by_role_and_label(Role::TextInput, "height image")
            .value(),
        Some("../assets/gravel_gray_512.png".to_owned())
    );
    assert_ne!(image_bytes(&h), image_before, "the ball shows gravel bumps");
    assert_eq!(h.state().undo_label(), Some("bump map of Brick ball"));
    undo(&mut h);
    assert_eq!(desc(&h), before);
}

#[test]
fn values_beyond_the_drag_ranges_are_shown_and_kept() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = small_preset(dir.path(), "bumps", &BUMP_ASSETS, |d| {
        d.objects[1].bump.as_mut().expect("a bump map").scale = 3.0;
        d.objects[2].normal.as_mut().expect("a normal map").strength = -25.0;
        if let MaterialDesc::Phong { exp, .. } = &mut d.objects[1].material {
            *exp = ScalarDesc::Value(20_000.0);
        }
    });
    let mut h = harness(preset);
    let before = desc(&h);
    select(&mut h, "1: Brick ball");
    assert_eq!(
        h.get_by_label("bump scale").value().as_deref(),
        Some("3.000")
    );
    // So is a coefficient beyond its drag range.
    assert_eq!(
        h.get_by_label("exponent").value().as_deref(),
        Some("20000.0")
    );
    select(&mut h, "2: Normal-mapped ball");
    assert_eq!(
        h.get_by_label("normal strength").value().as_deref(),
        Some("-25.00")
    );
    assert_eq!(desc(&h), before, "showing them changed nothing");
    assert_eq!(h.state().undo_label(), None);
}

#[test]
fn every_number_field_keeps_a_preset_value_beyond_its_drag_range() {
    // The ambient field drags over 0..=100; a preset may say 150 (it validates up to 1e6).
    let dir = tempfile::tempdir().expect("temp dir");
    let path = small_earth(dir.path());
    let mut d = load_preset(&path).expect("preset");
    d.ambient.ls = 150.0;
    save_preset(&d, &path).expect("write preset");
    let mut h = harness(path);
    let before = desc(&h);
    let field = h.get_by_label("ambient ls");
    field.scroll_to_me();
    h.run_steps(3);
    let shown: f32 = h
        .get_by_label("ambient ls")
        .value()
        .expect("a value")
        .parse()
        .expect("a number");
    assert!((shown - 150.0).abs() < 1e-3, "{shown}");
    assert_eq!(desc(&h), before, "showing it changed nothing");
    assert_eq!(h.state().undo_label(), None);
}
