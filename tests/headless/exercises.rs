//! Lesson exercises and the comparison with a built-in mapping (issue 28 §2): every shipped
//! exercise's solution agrees with its target and its start does not; a bad exercise is an
//! error naming the file, the line and the field; the `Difference` view paints |du| and |dv|
//! on the object and the visible surface's agreement names the mistake.

use crate::common::{build_with, render_on, root, sized};
use std::sync::atomic::AtomicBool;
use texplore::coverage::visible_agreement;
use texplore::lesson::exercise::{SOLUTION_SHARE, Target};
use texplore::lesson::{load_dir, load_lesson};
use texplore::mapping::Mapping;
use texplore::mapping::formula::compare::{CORRECT_SHARE, Mistake};
use texplore::scene::{AssetCache, MappingDesc, build_scene, load_preset};
use texplore::texture::{Compare, View};

#[test]
fn every_shipped_exercise_is_solved_by_its_solution_and_not_by_its_start() {
    let loaded = load_dir(&root().join("lessons")).expect("lessons");
    assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
    let mut targets = Vec::new();
    for lesson in &loaded.lessons {
        for x in &lesson.exercises {
            let solved = x.check(&x.solution).expect("the solution compiles");
            assert!(
                solved.share() >= SOLUTION_SHARE,
                "{}: {}",
                lesson.name,
                solved.summary(&x.target)
            );
            assert!(
                solved.hints.is_empty(),
                "{}: {:?}",
                lesson.name,
                solved.hints
            );
            if let Ok(start) = x.check(&x.start) {
                assert!(
                    start.share() < CORRECT_SHARE,
                    "{}: the start already agrees: {}",
                    lesson.name,
                    start.summary(&x.target)
                );
            }
            targets.push((lesson.name.clone(), x.target.clone()));
        }
    }
    let has = |prefix: &str, t: &dyn Fn(&Target) -> bool| {
        targets.iter().any(|(n, x)| n.starts_with(prefix) && t(x))
    };
    assert!(has("04", &|t| *t == Target::Mapping(Mapping::Rectangular)));
    assert!(has("05", &|t| *t == Target::Mapping(Mapping::Cylindrical)));
    assert!(has("06", &|t| *t == Target::Mapping(Mapping::Spherical)));
    assert!(has("07", &|t| *t == Target::Mapping(Mapping::LightProbe)));
    assert!(
        targets
            .iter()
            .any(|(_, t)| matches!(t, Target::Checker { .. })),
        "a checker exercise"
    );
}

#[test]
fn the_broken_starts_get_their_hints() {
    let loaded = load_dir(&root().join("lessons")).expect("lessons");
    let hints = |prefix: &str| {
        let lesson = loaded
            .lessons
            .iter()
            .find(|l| l.name.starts_with(prefix))
            .expect("the lesson");
        let x = &lesson.exercises[0];
        x.check(&x.start).expect("the start compiles").hints
    };
    let first = |prefix: &str| hints(prefix).first().cloned().unwrap_or_default();
    assert!(
        first("04").contains("u and v are swapped"),
        "{:?}",
        hints("04")
    );
    assert!(
        first("06").contains("v is upside down"),
        "{:?}",
        hints("06")
    );
    assert!(
        first("07").contains("mirrored left to right"),
        "{:?}",
        hints("07")
    );
    // Lesson 5 starts empty: a formula error, not a verdict.
    let lesson5 = loaded
        .lessons
        .iter()
        .find(|l| l.name.starts_with("05"))
        .unwrap();
    let x = &lesson5.exercises[0];
    assert!(x.check(&x.start).is_err());
}

#[test]
fn the_checker_exercise_names_swapped_colours() {
    let loaded = load_dir(&root().join("lessons")).expect("lessons");
    let x = loaded
        .lessons
        .iter()
        .flat_map(|l| &l.exercises)
        .find(|x| matches!(x.target, Target::Checker { .. }))
        .expect("a checker exercise");
    let swapped = vec!["0.1 + 0.8 * 2 * fract((floor(8 * u) + floor(8 * v)) / 2)".to_owned()];
    let c = x.check(&swapped).unwrap();
    assert!(c.share() < 0.01, "{}", c.summary(&x.target));
    assert!(
        c.hints[0].contains("colours are the wrong way round"),
        "{:?}",
        c.hints
    );
}

/// The lesson `body` (its exercise and question) on the small rectangle preset, as a file in
/// `dir`; the error loading it.
fn bad(dir: &std::path::Path, body: &str) -> String {
    let preset = root().join("presets/rectangle.ron");
    let text = format!(
        "title = \"Bad\"\npreset = {:?}\ntext = \"x\"\n\n{body}\n[question]\nask = \"a\"\nanswer = \"b\"\n",
        preset.display().to_string()
    );
    let file = dir.join("bad.toml");
    std::fs::write(&file, text).unwrap();
    load_lesson(&file)
        .expect_err("the lesson is refused")
        .to_string()
}

#[test]
fn a_bad_exercise_is_an_error_naming_the_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let right = r#"solution = { u = "(z + 1) / 2", v = "(x + 1) / 2" }"#;
    let cases = [
        (
            format!("[[exercise]]\ntask = \"t\"\ntarget = \"Rectanglar\"\nstart = {{ u = \"\", v = \"\" }}\n{right}\n"),
            "bad.toml:7:10: exercise 1: `target` = \"Rectanglar\" is neither a built-in mapping",
        ),
        (
            format!("[[exercise]]\ntask = \"t\"\ntarget = \"Rectangular\"\nstart = {{ u = \"\" }}\n{right}\n"),
            "exercise 1: `start.v` is missing",
        ),
        (
            format!("[[exercise]]\ntask = \"t\"\ntarget = \"Rectangular\"\nstart = {{ grey = \"u\", u = \"\", v = \"\" }}\n{right}\n"),
            "exercise 1: `start.grey`: this exercise's formulas are u and v",
        ),
        (
            "[[exercise]]\ntask = \"t\"\ntarget = \"Rectangular\"\nstart = { u = \"\", v = \"\" }\nsolution = { u = \"(x + 1) / 2\", v = \"(z + 1) / 2\" }\n".to_owned(),
            "9:12: exercise 1: `solution` does not solve it: 1.6 % of 4096 points",
        ),
        (
            "[[exercise]]\ntask = \"t\"\ntarget = \"Rectangular\"\nstart = { u = \"\", v = \"\" }\nsolution = { u = \"(z + 1) / 2\", v = \"(x + 1) / w\" }\n".to_owned(),
            "exercise 1: `solution.v: column 11: unknown name `w`",
        ),
        (
            format!("[[exercise]]\ntask = \"t\"\ntarget = \"Rectangular\"\nstart = {{ u = \"z / 2 + 0.5\", v = \"x / 2 + 0.5\" }}\n{right}\n"),
            "exercise 1: `start` already agrees with the rectangular mapping",
        ),
        (
            format!("[[exercise]]\ntask = \"t\"\ntarget = \"Rectangular\"\nobject = 3\nstart = {{ u = \"\", v = \"\" }}\n{right}\n"),
            "exercise 1: `object` = 3: the scene has no objects[3]",
        ),
        (
            format!("[[exercise]]\ntask = \"t\"\ntarget = \"Rectangular\"\nstrat = {{ u = \"\", v = \"\" }}\n{right}\n"),
            "unknown field `strat`",
        ),
    ];
    for (body, want) in cases {
        let e = bad(dir.path(), &body);
        assert!(e.contains("bad.toml:"), "{e}");
        assert!(e.contains(want), "{want:?} in {e}");
    }
}

/// The Earth at 64 x 48 with the formulas `u`, `v` and the Difference view against the
/// spherical map.
fn earth_difference(u: &str, v: &str) -> texplore::scene::Scene {
    let path = root().join("presets/earth.ron");
    let mut desc = load_preset(&path).unwrap();
    desc.objects[0]
        .material
        .texture_mut()
        .set_mapping(MappingDesc::Formula {
            u: u.into(),
            v: v.into(),
        });
    desc.render.view = View::Difference;
    desc.render.compare = Compare {
        with: Mapping::Spherical,
        tolerance: 1.0,
    };
    build_with(&desc, &path, sized(64, 48, 1), &mut AssetCache::new())
}

#[test]
fn the_difference_view_paints_du_and_dv_and_the_visible_surface_names_the_mistake() {
    let green = |p: &[f32; 4]| p[1] / p[3].max(1e-6) > 0.2 && p[0] / p[3].max(1e-6) < 0.01;
    let agree = |p: &[f32; 4]| {
        let c = texplore::texture::AGREE_COLOUR;
        let w = p[3].max(1e-6);
        (p[0] / w - c.0).abs() < 1e-4
            && (p[1] / w - c.1).abs() < 1e-4
            && (p[2] / w - c.2).abs() < 1e-4
    };
    let never = AtomicBool::new(false);

    let flipped = earth_difference("fract(atan2(x, z) / tau)", "acos(y) / pi");
    let film = render_on(&flipped, 2);
    let greens = film.pixels().iter().filter(|p| green(p)).count();
    assert!(greens > 64 * 48 / 4, "{greens} green pixels");
    let found = visible_agreement(&flipped, 0, flipped.settings.compare, &never)
        .unwrap()
        .expect("a formula mapping");
    assert!(found.agreement.points > 500, "{}", found.agreement.points);
    assert!(found.agreement.share() < 0.2, "{:?}", found.agreement);
    assert_eq!(found.mistakes, vec![Mistake::FlippedV]);

    let right = earth_difference(
        "fract(atan2(x, z) / tau)",
        "1 - acos(y / sqrt(x*x + y*y + z*z)) / pi",
    );
    let film = render_on(&right, 2);
    let on_earth = film
        .pixels()
        .iter()
        .filter(|p| p[0] + p[1] + p[2] > 0.0)
        .count();
    let agreeing = film.pixels().iter().filter(|p| agree(p)).count();
    assert!(on_earth > 64 * 48 / 4);
    assert_eq!(agreeing, on_earth, "every pixel of the Earth agrees");
    let found = visible_agreement(&right, 0, right.settings.compare, &never)
        .unwrap()
        .unwrap();
    assert!(found.agreement.share() >= 0.99, "{:?}", found.agreement);
    assert!(found.mistakes.is_empty());
}

#[test]
fn the_comparison_tolerance_is_checked() {
    let path = root().join("presets/earth.ron");
    let mut desc = load_preset(&path).unwrap();
    for bad in [0.0, -1.0, f32::NAN, 1e7] {
        desc.render.compare.tolerance = bad;
        let e = build_scene(&desc, &path, &mut AssetCache::new())
            .expect_err("refused")
            .to_string();
        assert!(e.contains("render.compare.tolerance"), "{e}");
    }
}
