//! The shipped lessons: every one loads, in lecture order; every experiment applies to its
//! preset and visibly changes the render; `texplore lesson --list` lists them and a bad name or
//! a broken lesson file is an error naming it. The lessons are built into the binary: they list
//! and print from any folder, and a teacher's own (in the user folder) come after them.

use crate::common::{failure, root, success};
use std::path::Path;
use std::process::{Command, Output};
use texplore::lesson::{Lesson, find, load_dir};
use texplore::scene::SimdMode;
use texplore::scene::{AssetCache, SceneDesc, load_preset};
use texplore::snapshot::render_snapshot;

fn shipped() -> Vec<Lesson> {
    let loaded = load_dir(&root().join("lessons")).unwrap();
    let errors: Vec<String> = loaded.errors.iter().map(ToString::to_string).collect();
    assert!(errors.is_empty(), "lessons that do not load: {errors:#?}");
    loaded.lessons
}

/// The render at 64 x 48, 1 sample per pixel unless the description itself asks for a
/// different count than `base` (an experiment about supersampling).
fn small(desc: &SceneDesc, base: &SceneDesc, lesson: &Lesson, cache: &mut AssetCache) -> Vec<u8> {
    let mut d = desc.clone();
    d.snapshot.width = 64;
    d.snapshot.height = 48;
    d.snapshot.spp = if d.render.spp == base.render.spp {
        1
    } else {
        d.render.spp.min(64)
    };
    render_snapshot(&d, &lesson.preset, cache, SimdMode::Auto)
        .unwrap_or_else(|e| panic!("{}: {e}", lesson.file.display()))
        .2
}

#[test]
fn the_lessons_follow_the_lecture() {
    let lessons = shipped();
    let names: Vec<&str> = lessons.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "01-constant-vs-image",
            "02-texel-coordinates",
            "03-spatially-varying-materials",
            "04-rectangular-mapping",
            "05-cylindrical-mapping",
            "06-spherical-mapping",
            "07-light-probes",
            "08-aliasing",
            "09-triangle-meshes",
            "10-the-lectures-examples",
        ]
    );
    for l in &lessons {
        assert!(
            (2..=6).contains(&l.experiments.len()),
            "{}: {} experiments",
            l.name,
            l.experiments.len()
        );
        assert!(!l.title.is_empty() && !l.text.is_empty(), "{}", l.name);
        assert!(!l.question.is_empty() && !l.answer.is_empty(), "{}", l.name);
        for (k, x) in l.experiments.iter().enumerate() {
            assert!(!x.label.is_empty() && !x.look_for.is_empty(), "{}", l.name);
            assert!(x.after.is_none_or(|a| a < k), "{}: {}", l.name, x.label);
        }
    }
    assert_eq!(find(&lessons, "5").unwrap().name, "05-cylindrical-mapping");
    assert_eq!(find(&lessons, "aliasing").unwrap().name, "08-aliasing");
}

#[test]
fn every_experiment_changes_the_image() {
    let mut cache = AssetCache::new();
    for lesson in shipped() {
        let base = load_preset(&lesson.preset).unwrap();
        let base_image = small(&base, &base, &lesson, &mut cache);
        for (k, x) in lesson.experiments.iter().enumerate() {
            let desc = lesson.scene(k, &base).unwrap();
            // An experiment that builds on another changes that one's image.
            let start = match x.after {
                Some(a) => lesson.scene(a, &base).unwrap(),
                None => base.clone(),
            };
            assert_ne!(desc, start, "{}: {}", lesson.name, x.label);
            let before = if x.after.is_some() {
                small(&start, &base, &lesson, &mut cache)
            } else {
                base_image.clone()
            };
            let after = small(&desc, &base, &lesson, &mut cache);
            let pixels = before.len() / 3;
            let changed = before
                .chunks(3)
                .zip(after.chunks(3))
                .filter(|(a, b)| a.iter().zip(*b).any(|(p, q)| p.abs_diff(*q) > 12))
                .count();
            // At least 2 % of the pixels (61 of 3072) change visibly.
            assert!(
                changed * 50 >= pixels,
                "{}: \"{}\" changes only {changed} of {pixels} pixels",
                lesson.name,
                x.label
            );
        }
    }
}

#[test]
fn the_lecture_lookup_never_shows_the_last_column() {
    // The texel-coordinates lesson's claim, on its own scene: the yellow (last) column of the
    // 4-texel image covers a quarter of the rectangle under the centred lookup, none under the
    // lecture's.
    let lessons = shipped();
    let lesson = find(&lessons, "texel-coordinates").unwrap();
    let base = load_preset(&lesson.preset).unwrap();
    let lecture = lesson.experiments[0].apply(&base).unwrap();
    let mut cache = AssetCache::new();
    let yellow = |rgb: &[u8]| {
        rgb.chunks(3)
            .filter(|p| p[0] > 150 && p[1] > 120 && p[2] < 80)
            .count()
    };
    let centred = yellow(&small(&base, &base, lesson, &mut cache));
    let rect_pixels = 64 * 48 / 2; // roughly: the rectangle fills much of the frame
    assert!(centred > rect_pixels / 8, "{centred} yellow pixels");
    assert_eq!(yellow(&small(&lecture, &base, lesson, &mut cache)), 0);
}

#[test]
fn lesson_list_names_and_titles() {
    let home = tempfile::tempdir().unwrap();
    let out = success(&lesson_cli(root(), home.path(), &["lesson", "--list"]));
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 10, "{out}");
    assert!(
        lines[0].starts_with("01-constant-vs-image ")
            && lines[0].ends_with("A texture is a colour that varies with location"),
        "{out}"
    );
    assert!(lines[9].starts_with("10-the-lectures-examples "), "{out}");
}

#[test]
fn an_unknown_lesson_lists_the_names() {
    let home = tempfile::tempdir().unwrap();
    let err = failure(&lesson_cli(root(), home.path(), &["lesson", "marmite"]));
    assert!(
        err.contains("no lesson named `marmite`; the lessons are: 01-constant-vs-image, 02-"),
        "{err}"
    );
}

/// Runs `texplore` with `args` from `cwd`, with `data_home` as the user's data folder (so the
/// teacher's lessons folder is `data_home/texplore/lessons`, whatever the machine's user has).
fn lesson_cli(cwd: &Path, data_home: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(cwd)
        .env("XDG_DATA_HOME", data_home)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run texplore {args:?}: {e}"))
}

#[test]
fn lessons_list_and_print_from_any_folder() {
    // A folder with no lessons/ or presets/ in it: the shipped ones are in the binary.
    let elsewhere = tempfile::tempdir().unwrap();
    let out = success(&lesson_cli(
        elsewhere.path(),
        elsewhere.path(),
        &["lesson", "--list"],
    ));
    assert_eq!(out.lines().count(), 10, "{out}");
    let printed = success(&lesson_cli(
        elsewhere.path(),
        elsewhere.path(),
        &["lesson", "1", "--print"],
    ));
    let first = &shipped()[0];
    assert!(
        printed.starts_with(&format!("# {}\n", first.title)),
        "{printed}"
    );
    // The scene it names is a real file (the copy of the shipped presets), with its image.
    let scene = printed
        .lines()
        .find_map(|l| l.strip_prefix("Scene: "))
        .expect("a Scene line");
    let desc = load_preset(Path::new(scene)).unwrap();
    texplore::scene::build_scene(&desc, Path::new(scene), &mut AssetCache::new()).unwrap();
    for x in &first.experiments {
        assert!(
            printed.contains(&format!("Look for: {}", x.look_for)),
            "{printed}"
        );
    }
    assert!(printed.contains(&first.answer), "{printed}");
    // An exercise: its task and start before the question, its solution after the answer.
    let printed = success(&lesson_cli(
        elsewhere.path(),
        elsewhere.path(),
        &["lesson", "6", "--print"],
    ));
    let task = printed.find("Repair the spherical map").expect(&printed);
    let start = printed.find("    v = acos(y) / pi\n").expect(&printed);
    let question = printed.find("## Question").expect(&printed);
    let solution = printed
        .find("Solution of exercise 1:\n    u = fract(atan2(x, z) / tau)\n    v = 1 - acos(")
        .expect(&printed);
    assert!(
        task < start && start < question && question < solution,
        "{printed}"
    );
}

#[test]
fn a_teachers_lessons_follow_the_shipped_ones_and_a_shared_number_is_an_error() {
    let home = tempfile::tempdir().unwrap();
    let mine = home.path().join("texplore/lessons");
    std::fs::create_dir_all(&mine).unwrap();
    // A teacher's copy of lesson 5 still names `../presets/cylinder.ron`: found among the
    // shipped presets.
    let text = std::fs::read_to_string(root().join("lessons/05-cylindrical-mapping.toml")).unwrap();
    for name in ["05-a", "05-b", "5-a"] {
        std::fs::write(mine.join(format!("{name}.toml")), &text).unwrap();
    }
    let elsewhere = tempfile::tempdir().unwrap();
    let list = success(&lesson_cli(
        elsewhere.path(),
        home.path(),
        &["lesson", "--list"],
    ));
    let names: Vec<&str> = list
        .lines()
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    assert_eq!(names.len(), 13, "{list}");
    assert_eq!(&names[10..], ["05-a", "05-b", "5-a"], "{list}");
    let err = failure(&lesson_cli(elsewhere.path(), home.path(), &["lesson", "5"]));
    assert!(
        err.contains("`5` names 4 lessons: 05-cylindrical-mapping, 05-a, 05-b, 5-a"),
        "{err}"
    );
    // The full name picks one.
    let printed = success(&lesson_cli(
        elsewhere.path(),
        home.path(),
        &["lesson", "05-b", "--print"],
    ));
    assert!(printed.contains("presets/cylinder.ron"), "{printed}");
    // The same name in both places names both files.
    std::fs::write(mine.join("08-aliasing.toml"), &text).unwrap();
    let err = failure(&lesson_cli(
        elsewhere.path(),
        home.path(),
        &["lesson", "aliasing"],
    ));
    assert!(
        err.contains("`aliasing` names 2 lessons: ")
            && err.contains("texplore/lessons/08-aliasing.toml"),
        "{err}"
    );
}

/// A temporary folder with an empty `lessons/` in it, and the text of lesson 5 with its preset
/// paths made absolute (so a copy of it loads from there).
fn lesson_folder() -> (tempfile::TempDir, std::path::PathBuf, String) {
    let dir = tempfile::tempdir().unwrap();
    let lessons = dir.path().join("lessons");
    std::fs::create_dir(&lessons).unwrap();
    let good = std::fs::read_to_string(root().join("lessons/05-cylindrical-mapping.toml"))
        .unwrap()
        .replace("../presets/", &format!("{}/presets/", root().display()));
    (dir, lessons, good)
}

#[test]
fn a_broken_lesson_is_named_with_its_line_and_the_others_still_list() {
    let (dir, lessons, good) = lesson_folder();
    std::fs::write(lessons.join("01-good.toml"), &good).unwrap();
    // A typo in a path of the preset, on the line of the second experiment's `set`.
    let bad = good.replace("cd.path", "cd.pth");
    let line = 1 + bad[..bad.find("cd.pth").unwrap()].matches('\n').count();
    std::fs::write(lessons.join("02-typo.toml"), &bad).unwrap();
    let out = lesson_cli(
        dir.path(),
        dir.path(),
        &["lesson", "--list", "--dir", "lessons"],
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    let err = failure(&out);
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    assert!(stdout.starts_with("01-good "), "{stdout}");
    assert!(
        err.contains(&format!("lessons/02-typo.toml:{line}:")) && err.contains("pth"),
        "{err}"
    );
    assert!(
        err.contains("1 of 2 lesson files in lessons did not load"),
        "{err}"
    );
}

#[test]
fn every_character_of_every_lesson_draws_in_the_window() {
    // The window draws text in egui's bundled fonts: Ubuntu Light, and Hack for the formula
    // paragraphs (indented), with egui's icon font as fallback. A character none of them has is
    // an empty box (and a failure in the window tests).
    use ab_glyph::{Font as _, FontRef};
    let fonts: Vec<FontRef<'static>> = [
        epaint_default_fonts::UBUNTU_LIGHT,
        epaint_default_fonts::HACK_REGULAR,
    ]
    .iter()
    .map(|f| FontRef::try_from_slice(f).unwrap())
    .collect();
    let mut missing = Vec::new();
    for l in shipped() {
        let x_text = l
            .experiments
            .iter()
            .flat_map(|x| [x.label.as_str(), x.look_for.as_str()]);
        // An exercise's task and formulas (the fields are monospace: Hack).
        let exercises = l.exercises.iter().flat_map(|x| {
            std::iter::once(x.task.as_str())
                .chain(x.start.iter().map(String::as_str))
                .chain(x.solution.iter().map(String::as_str))
        });
        let all = [l.title.as_str(), &l.text, &l.question, &l.answer]
            .into_iter()
            .chain(x_text)
            .chain(exercises);
        for s in all {
            for c in s.chars().filter(|c| !c.is_whitespace()) {
                // Hack draws the formulas, Ubuntu the rest: a character must be in both.
                if fonts.iter().any(|f| f.glyph_id(c).0 == 0)
                    && !missing.contains(&(c, l.name.clone()))
                {
                    missing.push((c, l.name.clone()));
                }
            }
        }
    }
    assert!(
        missing.is_empty(),
        "characters the window cannot draw: {missing:?}"
    );
}

#[test]
fn lesson_list_escapes_control_characters_in_titles() {
    let (dir, lessons, good) = lesson_folder();
    let title_line = good
        .lines()
        .find(|l| l.starts_with("title"))
        .expect("a title line");
    // An escape sequence that would clear the screen, and a bell, in TOML's own escapes.
    let hostile = good.replace(
        title_line,
        r#"title = "Clear\u001b[2J\u001b[Hscreen\u0007""#,
    );
    std::fs::write(lessons.join("01-hostile.toml"), hostile).unwrap();
    let out = lesson_cli(
        dir.path(),
        dir.path(),
        &["lesson", "--list", "--dir", "lessons"],
    );
    let stdout = success(&out);
    assert!(
        !stdout.contains('\u{1b}') && !stdout.contains('\u{7}'),
        "{stdout:?}"
    );
    assert!(
        stdout.contains(r"Clear\u{1b}[2J\u{1b}[Hscreen\u{7}"),
        "{stdout}"
    );
}
