//! Lesson exercises and the comparison with a built-in mapping (issue 28 §2): every shipped
//! exercise's solution agrees with its target and its start does not; a bad exercise is an
//! error naming the file, the line and the field; the `Difference` view paints |du| and |dv|
//! on the object and the visible surface's agreement names the mistake.

use crate::common::{build_with, render_on, root, sized, success, texplore, texplore_json};
use std::sync::atomic::AtomicBool;
use texplore::coverage::visible_agreement;
use texplore::lesson::exercise::{Exercise, SOLUTION_SHARE, Target};
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
            assert!(solved.hint.is_none(), "{}: {:?}", lesson.name, solved.hint);
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

/// The shipped exercise of lesson `prefix`.
fn exercise(prefix: &str) -> Exercise {
    let loaded = load_dir(&root().join("lessons")).expect("lessons");
    loaded
        .lessons
        .into_iter()
        .find(|l| l.name.starts_with(prefix))
        .expect("the lesson")
        .exercises
        .remove(0)
}

/// What *Check* says of `formulas`, in its two steps: `(verdict, what, fix)`. The verdict is
/// how the first step starts: `u agrees`, `v agrees` or `neither u nor v agrees` (a
/// checker's first step has no verdict: `-`).
fn steps(x: &Exercise, formulas: &[&str]) -> (String, String, String) {
    let formulas: Vec<String> = formulas.iter().map(|&f| f.to_owned()).collect();
    let c = x.check(&formulas).expect("the formulas compile");
    assert!(!c.correct(), "{formulas:?}: {}", c.summary(&x.target));
    let h = c.hint.unwrap_or_else(|| panic!("{formulas:?}: no hint"));
    let verdict = ["u agrees", "v agrees", "neither u nor v agrees"]
        .into_iter()
        .find(|v| h.what.starts_with(v))
        .unwrap_or("-");
    (
        verdict.to_owned(),
        h.what.clone(),
        h.fix.unwrap_or_else(|| panic!("{formulas:?}: no fix")),
    )
}

/// One case of a lesson's exercise: the formulas (none: the lesson's start), the verdict the
/// first step starts with, words of the first step and words of the second.
type Case<'a> = (Vec<&'a str>, &'a str, &'a str, &'a str);

/// The exercise of lesson `prefix` on each case: the verdict (which formula agrees), the first
/// step (what is wrong, not how to write it) and the second (the fix, the formula to write).
fn expect_steps(prefix: &str, cases: &[Case<'_>]) {
    let x = exercise(prefix);
    for (formulas, verdict, what, fix) in cases {
        let start: Vec<&str> = x.start.iter().map(String::as_str).collect();
        let formulas = if formulas.is_empty() {
            &start
        } else {
            formulas
        };
        let (v, w, f) = steps(&x, formulas);
        let case = format!("lesson {prefix}, {formulas:?}:\n  hint: {w}\n  fix: {f}");
        assert_eq!(v, *verdict, "{case}");
        assert!(w.contains(what), "{what:?} in {case}");
        assert!(f.contains(fix), "{fix:?} in {case}");
        // The first step does not give the answer away.
        assert!(!w.contains("write"), "{case}");
        for answer in &x.solution {
            assert!(!w.contains(answer.as_str()), "{case}");
        }
    }
}

/// Lesson 4, the rectangle: its start (swapped), then v upside down, u not brought into
/// [0, 1], v from y.
#[test]
fn lesson_4_start_and_three_mistakes_get_the_verdict_and_both_hint_steps() {
    expect_steps(
        "04",
        &[
            (
                vec![],
                "neither u nor v agrees",
                "u and v are swapped",
                "u = (z + 1) / 2 and v = (x + 1) / 2",
            ),
            (
                vec!["(z + 1) / 2", "(1 - x) / 2"],
                "u agrees",
                "v is upside down",
                "write v = (x + 1) / 2",
            ),
            (
                vec!["z", "(x + 1) / 2"],
                "v agrees",
                "u runs over the wrong range",
                "z runs from -1 to 1, so bring it into [0, 1]: write u = (z + 1) / 2",
            ),
            (
                vec!["(z + 1) / 2", "(y + 1) / 2"],
                "u agrees",
                "v follows the wrong axis",
                "v follows x: write v = (x + 1) / 2",
            ),
        ],
    );
}

/// Lesson 5, the cylinder: it starts from empty fields (Check names the empty formula);
/// issue 37's v = y, an angle not divided by 2 pi, v from z, and u in degrees.
#[test]
fn lesson_5_start_and_four_mistakes_get_the_verdict_and_both_hint_steps() {
    expect_steps(
        "05",
        &[
            (
                vec!["atan2(x, z) / (2 * pi)", "y"],
                "u agrees",
                "v runs over the wrong range",
                "y runs from -1 to 1, so bring it into [0, 1]: write v = (y + 1) / 2",
            ),
            (
                vec!["atan2(x, z)", "clamp((y + 1) / 2)"],
                "v agrees",
                "u is not a share of a whole turn",
                "a whole turn is 2 pi (tau)",
            ),
            (
                vec!["fract(atan2(x, z) / tau)", "(z + 1) / 2"],
                "u agrees",
                "v follows the wrong axis",
                "the height along the cylinder's axis, y: write v = (y + 1) / 2",
            ),
            (
                vec!["fract(atan2(x, z) / 360)", "(y + 1) / 2"],
                "v agrees",
                "u mixes degrees and radians",
                "divide by tau (2 pi), not 360: write u = fract(atan2(x, z) / tau)",
            ),
        ],
    );
    let x = exercise("05");
    let e = x
        .check(&x.start)
        .expect_err("empty formulas do not compile");
    assert!(e.to_string().starts_with("u: "), "{e}");
}

/// Lesson 6, the sphere: its start (the missing 1 -), asin for acos, degrees, and u a half
/// turn off.
#[test]
fn lesson_6_start_and_three_mistakes_get_the_verdict_and_both_hint_steps() {
    expect_steps(
        "06",
        &[
            (
                vec![],
                "u agrees",
                "v is upside down at the poles",
                "write v = 1 - acos(y) / pi",
            ),
            (
                vec!["fract(atan2(x, z) / tau)", "asin(y) / pi"],
                "u agrees",
                "v is measured from the equator",
                "theta = acos(y) is the angle from the north pole",
            ),
            (
                vec!["fract(atan2(x, z) / tau)", "1 - acos(y) / 180"],
                "u agrees",
                "v mixes degrees and radians",
                "divide by pi, not 180: write v = 1 - acos(y) / pi",
            ),
            (
                vec!["fract(atan2(x, z) / tau + 0.5)", "1 - acos(y) / pi"],
                "v agrees",
                "u is a half turn off",
                "do not add 0.5 or pi to it",
            ),
        ],
    );
}

/// Lesson 7, the light probe: its start (mirrored), v upside down, the image turned, u
/// without (1 + ...) / 2, and alpha measured from +x.
#[test]
fn lesson_7_start_and_four_mistakes_get_the_verdict_and_both_hint_steps() {
    let probe = exercise("07");
    let (pu, pv) = (probe.solution[0].as_str(), probe.solution[1].as_str());
    let unshifted = "acos(z / sqrt(x*x + y*y + z*z)) / pi * x / sqrt(x*x + y*y)";
    let from_x = "(1 + acos(x / sqrt(x*x + y*y + z*z)) / pi * z / sqrt(z*z + y*y)) / 2";
    let turned = format!("1 - {pv}");
    expect_steps(
        "07",
        &[
            (
                vec![],
                "v agrees",
                "the image is mirrored left to right",
                "plus r cos beta, not minus: write u = (1 + acos(z",
            ),
            (
                vec![pu, &turned],
                "u agrees",
                "v is upside down",
                "v = (1 + r sin beta) / 2",
            ),
            (
                vec![&turned, pu],
                "neither u nor v agrees",
                "the image is turned by a quarter turn",
                "beta is measured from +x toward +y",
            ),
            (
                vec![unshifted, pv],
                "v agrees",
                "u runs over the wrong range",
                "(t + 1) / 2 takes t from [-1, 1] into [0, 1]: write u = (1 + acos(z",
            ),
            (
                vec![from_x, pv],
                "v agrees",
                "u follows the wrong axis",
                "the probe looks along +z",
            ),
        ],
    );
}

/// Lesson 8, the checker: its start (stripes), the colours exchanged, 4 x 4 squares, and the
/// right squares in the wrong greys. A texture's first step has no u or v verdict.
#[test]
fn lesson_8_start_and_three_mistakes_get_both_hint_steps() {
    expect_steps(
        "08",
        &[
            (
                vec![],
                "-",
                "the colour changes along u only: these are stripes, not squares",
                "add v's term: 0.9 where floor(8 u) + floor(8 v) is even and 0.1 where it is odd",
            ),
            (
                vec!["0.1 + 0.8 * 2 * fract((floor(8 * u) + floor(8 * v)) / 2)"],
                "-",
                "their colours are the wrong way round",
                "the square at u, v = 0 has the first colour",
            ),
            (
                vec!["0.9 - 0.8 * 2 * fract((floor(4 * u) + floor(4 * v)) / 2)"],
                "-",
                "the squares are the wrong size: 4 x 4 of them, not 8 x 8",
                "multiply u by 8 and v by 8",
            ),
            (
                vec!["0.8 - 0.6 * 2 * fract((floor(8 * u) + floor(8 * v)) / 2)"],
                "-",
                "the pattern is right but the greys are not: 0.8 and 0.2",
                "0.9 where floor(8 u) + floor(8 v) is even",
            ),
        ],
    );
}

/// A formula that fits no common mistake gets the verdict and, as its fix, the lesson's own
/// solution of the formula that is wrong.
#[test]
fn an_unknown_mistake_gets_the_verdict_and_the_lessons_solution() {
    let x = exercise("05");
    let (v, what, fix) = steps(&x, &["fract(atan2(x, z) / tau)", "y * y"]);
    assert_eq!(v, "u agrees", "{what}");
    assert!(what.contains("v fits no common mistake"), "{what}");
    assert_eq!(fix, "the lesson's solution writes v = clamp((y + 1) / 2)");
}

/// `texplore map formula --compare` prints the window's two steps, word for word.
#[test]
fn map_compare_prints_the_hint_the_lessons_panel_gives() {
    let x = exercise("05");
    let (u, v) = ("atan2(x, z) / (2 * pi)", "y");
    let checked = x.check(&[u.to_owned(), v.to_owned()]).unwrap();
    let hint = checked.hint.expect("a hint");
    let text = success(&texplore(&[
        "map",
        "formula",
        "--u",
        u,
        "--v",
        v,
        "0.6",
        "0.3",
        "-0.8",
        "--compare",
        "cylindrical",
    ]));
    assert!(
        text.contains("over 8192 points of the cylindrical map's surface: 0.0 % agree"),
        "{text}"
    );
    assert!(
        text.contains("u alone agrees at 100.0 % of them, v at 0.0 %"),
        "{text}"
    );
    assert!(
        text.contains(&format!("\n  hint: {}\n", hint.what)),
        "{text}"
    );
    assert!(
        text.contains(&format!("\n  fix: {}\n", hint.fix.as_deref().unwrap())),
        "{text}"
    );
    assert!(
        text.contains("hint: u agrees; v runs over the wrong range"),
        "{text}"
    );
    let json = texplore_json(&[
        "map",
        "formula",
        "--u",
        u,
        "--v",
        v,
        "0.6",
        "0.3",
        "-0.8",
        "--compare",
        "cylindrical",
        "--json",
    ]);
    assert_eq!(json["compare"]["u_agreement"], 1.0);
    assert_eq!(json["compare"]["v_agreement"], 0.0);
    assert_eq!(json["compare"]["hint"], hint.what.as_str());
    assert_eq!(json["compare"]["fix"], hint.fix.as_deref().unwrap());
    // The right formulas: no verdict line, no hint, no fix.
    let right = success(&texplore(&[
        "map",
        "formula",
        "--u",
        &x.solution[0],
        "--v",
        &x.solution[1],
        "0.6",
        "0.3",
        "-0.8",
        "--compare",
        "cylindrical",
    ]));
    assert!(right.contains("100.0 % agree"), "{right}");
    for word in ["alone agrees", "hint:", "fix:"] {
        assert!(!right.contains(word), "{right}");
    }
}

#[test]
fn the_checker_exercise_names_swapped_colours() {
    let x = exercise("08");
    let swapped = vec!["0.1 + 0.8 * 2 * fract((floor(8 * u) + floor(8 * v)) / 2)".to_owned()];
    let c = x.check(&swapped).unwrap();
    assert!(c.share() < 0.01, "{}", c.summary(&x.target));
    assert!(
        c.hint
            .as_ref()
            .is_some_and(|h| h.what.contains("colours are the wrong way round")),
        "{:?}",
        c.hint
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
