//! A lesson's check counts its scenes' summed-area tables as the scenes build them: the check
//! reads each image's header only (a 1 x 1 stand-in), and its tables used to be counted at the
//! stand-in's size, a few bytes, so `lesson --list` never saw tables over the texture budget
//! that the window and `texplore render` then read with EWA instead.

use crate::common::{success, texplore_in};
use crate::memory::{grey_png, greys_2048};
use texplore::scene::{AssetCache, build_scene, load_preset};

/// A preset of `n` spheres in a row, sphere `i` with the image `image(i)` under the footprint
/// filter.
fn spheres(n: usize, image: impl Fn(usize) -> String) -> String {
    let objects: Vec<String> = (0..n)
        .map(|i| {
            format!(
                r#"(shape: Sphere, transform: (translate: ({x}, 0, 0)),
        material: Matte(cd: Image(path: "{}", mapping: Spherical, filter: Footprint)))"#,
                image(i),
                x = 2.5 * i as f32,
            )
        })
        .collect();
    format!(
        "(\n    version: 1,\n    camera: (eye: (0, 0, 9), projection: Pinhole(fov: 40)),\n    \
         render: (width: 32, height: 32, spp: 1),\n    objects: [{}],\n)",
        objects.join(",\n        ")
    )
}

/// The notices' "needs" parts (what each table needs), which a check and a build must agree on
/// (what is left differs: a check counts a pyramid as a third of its image).
fn needs(notices: &[String]) -> Vec<String> {
    notices
        .iter()
        .map(|n| n.split(", above").next().unwrap_or_default().to_owned())
        .collect()
}

#[test]
fn a_checked_scene_counts_the_tables_the_built_scene_reserves() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["a.png", "b.png"] {
        grey_png(&dir.path().join(name), 256, 256);
    }
    let preset = dir.path().join("two.ron");
    std::fs::write(&preset, spheres(2, |i| ["a.png", "b.png"][i].to_owned())).unwrap();
    let desc = load_preset(&preset).unwrap();
    // Under 1 MiB, the images and pyramids fit (about 340 KiB each), their tables (1 MiB
    // each) do not.
    let notices = |mut cache: AssetCache| {
        cache.set_texture_budget(1 << 20);
        build_scene(&desc, &preset, &mut cache).unwrap();
        cache.notices().to_vec()
    };
    let built = notices(AssetCache::new());
    let checked = notices(AssetCache::checking());
    assert_eq!(built.len(), 2, "{built:?}");
    assert!(
        built[0].contains("a.png: its summed-area tables need 1.0 MiB"),
        "{built:?}"
    );
    assert_eq!(needs(&checked), needs(&built), "{checked:?}");
}

#[test]
fn lesson_list_warns_of_tables_over_the_budget_as_render_does() {
    // The scene of `footprint::summed_area_tables_count_in_the_scene_budget`: 24 distinct
    // 2048 x 2048 PNGs under the footprint filter. `texplore render` builds 7 tables and warns
    // of the 17 that do not fit; the lesson's check, reading the headers only, says the same.
    let dir = tempfile::tempdir().unwrap();
    greys_2048(dir.path());
    std::fs::write(
        dir.path().join("p.ron"),
        spheres(24, |i| format!("g{i}.png")),
    )
    .unwrap();
    let lessons = dir.path().join("lessons");
    std::fs::create_dir(&lessons).unwrap();
    std::fs::write(
        lessons.join("01-many.toml"),
        "title = \"Many images\"\npreset = \"../p.ron\"\ntext = \"Two dozen spheres.\"\n\n\
         [[experiment]]\nlabel = \"Four samples\"\nlook_for = \"Less noise.\"\n\
         set = { \"render.spp\" = 4 }\n\n\
         [question]\nask = \"Why?\"\nanswer = \"Because.\"\n",
    )
    .unwrap();
    let out = texplore_in(dir.path(), &["lesson", "--list", "--dir", "lessons"]);
    let listed = success(&out);
    assert!(listed.contains("01-many"), "{listed}");
    let err = String::from_utf8_lossy(&out.stderr);
    let warned: Vec<&str> = err.lines().filter(|l| l.starts_with("warning:")).collect();
    // Once each (the experiment's scene repeats the preset's), naming the lesson and the scene.
    assert_eq!(warned.len(), 17, "{err}");
    assert!(
        warned
            .iter()
            .all(|l| l.contains("01-many.toml: preset \"../p.ron\": ")
                && l.contains("the footprint filter reads it with EWA instead")),
        "{err}"
    );
    assert!(!err.contains("g0.png:"), "{err}");
    assert!(
        err.contains("g23.png: its summed-area tables need 64.1 MiB"),
        "{err}"
    );
}

#[test]
fn the_shipped_lessons_check_without_warnings() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let loaded = texplore::lesson::load_dir(&dir).unwrap();
    assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
    for l in &loaded.lessons {
        assert!(l.warnings.is_empty(), "{}: {:?}", l.name, l.warnings);
    }
}
