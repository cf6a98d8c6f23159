//! A lesson's exercise in the window (issue 28 §2): the fields start from the lesson's
//! formulas, *Check* puts them on the scene (one undo step) and shows the agreement and the
//! hint's first step, *Show the fix* its second, *Show solution* fills the fields, and the solution checks as correct and renders the
//! built-in image.

use crate::gui_common::{desc, image_bytes, settle, small_earth, undo, wait_for_label};
use crate::gui_lessons::{press, root};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use texplore::gui::ExplorerApp;
use texplore::scene::{MappingDesc, load_preset};

/// The percentage a verdict starts with (`97.3 % of ...`, `Correct: 100.0 % of ...`).
pub fn percent(text: &str) -> f64 {
    let before = text.split(" %").next().unwrap_or_default();
    let number = before.rsplit(' ').next().unwrap_or_default();
    number
        .parse()
        .unwrap_or_else(|_| panic!("no percentage in {text:?}"))
}

/// How many bytes of two images differ by more than `by`.
fn differing(a: &[u8], b: &[u8], by: u8) -> usize {
    a.iter()
        .zip(b)
        .filter(|(x, y)| x.abs_diff(**y) > by)
        .count()
}

/// The value of the exercise's field `label`.
fn field(h: &Harness<'_, ExplorerApp>, label: &str) -> String {
    h.get_by_role_and_label(Role::TextInput, label)
        .value()
        .unwrap_or_default()
}

#[test]
fn check_gives_the_hint_and_the_solution_agrees() {
    let dir = tempfile::tempdir().unwrap();
    let preset = small_earth(dir.path());
    // The shipped spherical lesson's exercise, on the small Earth.
    let shipped =
        std::fs::read_to_string(root().join("lessons/06-spherical-mapping.toml")).unwrap();
    let exercise = &shipped[shipped
        .find("[[exercise]]")
        .expect("lesson 6 has an exercise")..];
    let text = format!(
        "title = \"The spherical exercise\"\npreset = {:?}\ntext = \"Write it.\"\n\n{exercise}",
        preset.file_name().unwrap().to_str().unwrap()
    );
    let file = dir.path().join("06-exercise.toml");
    std::fs::write(&file, text).unwrap();
    let lesson = texplore::lesson::load_lesson(&file).unwrap();
    let x = lesson.exercises[0].clone();
    let mut h = crate::gui_lessons::start(lesson);
    settle(&mut h);
    let base = load_preset(&preset).unwrap();
    let builtin = image_bytes(&h);

    // The fields start from the lesson's broken formulas.
    assert_eq!(field(&h, "your u ="), x.start[0]);
    assert_eq!(field(&h, "your v ="), "acos(y) / pi");
    press(&mut h, "Check");
    settle(&mut h);
    // The hint's first step says which formula agrees and what is wrong, not the answer; the
    // second, on *Show the fix*, how to write it.
    let hint = wait_for_label(&mut h, "hint: ");
    assert!(hint.contains("u agrees; v is upside down"), "{hint}");
    assert!(!hint.contains("1 - acos"), "{hint}");
    assert!(h.query_by_label_contains("fix: ").is_none());
    press(&mut h, "Show the fix");
    let fix = wait_for_label(&mut h, "fix: ");
    assert!(fix.contains("write v = 1 - acos(y) / pi"), "{fix}");
    let verdict = wait_for_label(&mut h, "points of the spherical map's surface");
    assert!(percent(&verdict) < 50.0, "{verdict}");
    assert!(
        matches!(
            desc(&h).objects[0].material.texture().mapping(),
            Some(MappingDesc::Formula { v, .. }) if v == "acos(y) / pi"
        ),
        "Check put the formulas on the scene"
    );
    let flipped = image_bytes(&h);
    assert!(
        differing(&builtin, &flipped, 16) * 20 > builtin.len(),
        "the Earth is upside down on screen"
    );

    // One undo step takes the formulas off, and the verdict with them.
    undo(&mut h);
    assert_eq!(desc(&h), base);
    assert!(h.query_by_label_contains("hint: ").is_none());
    assert!(
        h.query_by_label_contains("points of the spherical map's surface")
            .is_none()
    );

    press(&mut h, "Show solution");
    assert_eq!(field(&h, "your u ="), x.solution[0]);
    assert_eq!(field(&h, "your v ="), x.solution[1]);
    assert!(h.query_by_label_contains("hint: ").is_none());
    assert!(h.query_by_label_contains("fix: ").is_none());
    press(&mut h, "Check");
    settle(&mut h);
    let verdict = wait_for_label(&mut h, "Correct: ");
    assert!(percent(&verdict) >= 99.0, "{verdict}");
    assert!(h.query_by_label_contains("hint: ").is_none());
    let solved = image_bytes(&h);
    assert!(
        differing(&builtin, &solved, 2) * 1000 <= builtin.len(),
        "the solution renders the built-in Earth"
    );
}

#[test]
fn a_formula_that_does_not_compile_is_named_and_not_applied() {
    let dir = tempfile::tempdir().unwrap();
    let preset = small_earth(dir.path());
    let shipped =
        std::fs::read_to_string(root().join("lessons/06-spherical-mapping.toml")).unwrap();
    let exercise = &shipped[shipped.find("[[exercise]]").unwrap()..];
    let text = format!(
        "title = \"The spherical exercise\"\npreset = {:?}\ntext = \"Write it.\"\n\n{exercise}",
        preset.file_name().unwrap().to_str().unwrap()
    );
    let file = dir.path().join("06-exercise.toml");
    std::fs::write(&file, text).unwrap();
    let mut h = crate::gui_lessons::start(texplore::lesson::load_lesson(&file).unwrap());
    let base = load_preset(&preset).unwrap();
    let node = h.get_by_role_and_label(Role::TextInput, "your v =");
    node.focus();
    h.step();
    h.get_by_role_and_label(Role::TextInput, "your v =")
        .set_text_value_accesskit("1 - acos(q) / pi");
    h.step();
    press(&mut h, "Check");
    let error = wait_for_label(&mut h, "unknown name `q`");
    assert!(error.starts_with("v: column 10"), "{error}");
    assert_eq!(desc(&h), base, "nothing was applied");
}

#[test]
fn the_checker_exercise_checks_a_texture_and_writes_no_shipped_file() {
    let shipped = crate::gui_lessons_class::shipped_files();
    let loaded = texplore::lesson::load_dir(&root().join("lessons")).unwrap();
    let lesson = loaded
        .lessons
        .into_iter()
        .find(|l| l.name.starts_with("08"))
        .expect("lesson 8");
    let x = lesson.exercises[0].clone();
    let mut h = crate::gui_lessons::start(lesson);
    settle(&mut h);
    let photo = image_bytes(&h);
    assert_eq!(field(&h, "your grey ="), x.start[0]);

    // The start draws stripes: they agree with the checker on every other row of squares.
    press(&mut h, "Check");
    settle(&mut h);
    let verdict = wait_for_label(&mut h, "points of the (u, v) square");
    assert!((45.0..55.0).contains(&percent(&verdict)), "{verdict}");
    assert!(matches!(
        desc(&h).objects[0].material.texture(),
        texplore::scene::TextureDesc::Formula { grey, .. } if *grey == x.start[0]
    ));
    let stripes = image_bytes(&h);
    assert!(differing(&photo, &stripes, 16) * 10 > photo.len());

    press(&mut h, "Show solution");
    assert_eq!(field(&h, "your grey ="), x.solution[0]);
    press(&mut h, "Check");
    settle(&mut h);
    let verdict = wait_for_label(&mut h, "Correct: ");
    assert!(percent(&verdict) >= 99.0, "{verdict}");
    let checker = image_bytes(&h);
    assert!(differing(&stripes, &checker, 16) * 20 > stripes.len());
    assert!(
        crate::gui_lessons_class::shipped_files() == shipped,
        "no shipped file changed on disk"
    );
}

#[test]
fn check_applies_to_the_exercise_s_own_scene_after_an_experiment() {
    // Issue 36 §4: after the UV-grid experiment, Check put the formulas on the UV grid, not on
    // the Earth the task names.
    let dir = tempfile::tempdir().unwrap();
    let preset = small_earth(dir.path());
    let shipped =
        std::fs::read_to_string(root().join("lessons/06-spherical-mapping.toml")).unwrap();
    let exercise = &shipped[shipped.find("[[exercise]]").unwrap()..];
    let text = format!(
        "title = \"The spherical exercise\"\npreset = {:?}\ntext = \"Write it.\"\n\n\
         [[experiment]]\nlabel = \"The UV grid\"\nlook_for = \"The grid.\"\n\
         set = {{ \"objects[0].material.cd\" = \"UvGrid(mapping: Spherical)\" }}\n\n{exercise}",
        preset.file_name().unwrap().to_str().unwrap()
    );
    let file = dir.path().join("06-exercise.toml");
    std::fs::write(&file, text).unwrap();
    let lesson = texplore::lesson::load_lesson(&file).unwrap();
    let mut h = crate::gui_lessons::start(lesson);
    settle(&mut h);
    let base = load_preset(&preset).unwrap();
    press(&mut h, "The UV grid");
    settle(&mut h);
    assert_ne!(
        desc(&h).objects[0].material.texture(),
        base.objects[0].material.texture()
    );
    press(&mut h, "Show solution");
    press(&mut h, "Check");
    settle(&mut h);
    wait_for_label(&mut h, "Correct: ");
    let d = desc(&h);
    let tex = d.objects[0].material.texture();
    assert!(
        matches!(tex, texplore::scene::TextureDesc::Image { .. }),
        "Check put the formulas on the Earth's image, not on the UV grid: {tex:?}"
    );
    assert!(matches!(tex.mapping(), Some(MappingDesc::Formula { .. })));
}
