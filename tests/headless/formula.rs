//! A student's own mapping (issue 28): the lecture's four mappings written as formulas give
//! the built-in (u, v) and the built-in renders under every filter; mistakes are recognised
//! with their hint; hostile formulas give clear errors or marked pixels; presets and the
//! command line carry formulas.

use crate::common::texplore_json as json;
use crate::common::{build_with, failure, filtered, render_on, root, sized, success, texplore};
use glam::{DVec2, DVec3};
use std::path::Path;
use std::time::{Duration, Instant};
use strum::VariantArray;
use texplore::mapping::formula::compare::{
    Mistake, agreement, lecture_formula, mistakes, one_texel, sample_points,
};
use texplore::mapping::formula::inputs_of;
use texplore::mapping::{FormulaMapping, Mapping, map_uv_f64};
use texplore::render::{SimdMode, render_blocking_with, thread_pool};
use texplore::scene::{
    AssetCache, MappingDesc, SceneDesc, TextureDesc, build_scene, load_preset, parse_preset, to_ron,
};
use texplore::snapshot::compare;
use texplore::texture::Filter;

const LECTURE: [Mapping; 4] = [
    Mapping::Rectangular,
    Mapping::Cylindrical,
    Mapping::Spherical,
    Mapping::LightProbe,
];

fn lecture(m: Mapping) -> FormulaMapping {
    let (u, v) = lecture_formula(m).expect("the lecture writes it");
    FormulaMapping::new(u, v).unwrap_or_else(|e| panic!("{m}: {e}"))
}

fn formula(u: &str, v: &str) -> MappingDesc {
    MappingDesc::Formula {
        u: u.into(),
        v: v.into(),
    }
}

/// On the lecture's surfaces and on a grid filling [-1, 1]^3 (off the axes, where the probe's
/// beta is undefined), the formulas give the built-in (u, v) to 1e-6.
#[test]
fn the_lecture_mappings_as_formulas_agree_with_the_builtin_ones_on_a_grid() {
    let steps: Vec<f64> = (0..8).map(|i| -0.875 + 0.25 * f64::from(i)).collect();
    for m in LECTURE {
        let f = lecture(m);
        let mut points = sample_points(m, 48);
        for &x in &steps {
            for &y in &steps {
                for &z in &steps {
                    points.push((DVec3::new(x, y, z), DVec2::ZERO));
                }
            }
        }
        for (p, mesh) in points {
            let got = f.eval(&inputs_of(p, mesh));
            let want = map_uv_f64(m, p);
            let du = (got.x - want.x)
                - (got.x - want.x).round() * f64::from(u8::from(m.u_is_periodic()));
            assert!(
                du.abs() < 1e-6 && (got.y - want.y).abs() < 1e-6,
                "{m} at {p}: formula {got}, built-in {want}"
            );
        }
    }
}

/// The preset of each lecture mapping, small, with its texture's mapping replaced by the
/// lecture's formula.
fn preset_pair(name: &str, m: Mapping) -> (SceneDesc, SceneDesc) {
    let path = root().join("presets").join(format!("{name}.ron"));
    let desc = load_preset(&path).expect("preset");
    let mut with_formula = desc.clone();
    let (u, v) = lecture_formula(m).expect("lecture");
    let mut replaced = 0;
    for o in &mut with_formula.objects {
        let t = o.material.texture_mut();
        if t.mapping().and_then(MappingDesc::builtin) == Some(m) {
            t.set_mapping(formula(u, v));
            replaced += 1;
        }
    }
    assert!(replaced > 0, "{name} has no {m} texture");
    (desc, with_formula)
}

/// The renders under each filter equal the built-in mapping's within the snapshot tolerance
/// (the footprint filters read the formula's derivatives: symbolic or finite differences).
#[test]
fn the_lecture_formulas_render_as_the_builtin_mappings_under_every_filter() {
    let mut cache = AssetCache::new();
    for (name, m) in [
        ("rectangle", Mapping::Rectangular),
        ("cylinder", Mapping::Cylindrical),
        ("earth", Mapping::Spherical),
        ("light-probe", Mapping::LightProbe),
    ] {
        let path = root().join("presets").join(format!("{name}.ron"));
        let (builtin, own) = preset_pair(name, m);
        for &filter in Filter::VARIANTS {
            let overrides = || texplore::scene::Overrides {
                filter: filtered(filter).filter,
                ..sized(96, 72, 1)
            };
            let a = build_with(&builtin, &path, overrides(), &mut cache);
            let b = build_with(&own, &path, overrides(), &mut cache);
            let (fa, fb) = (render_on(&a, 2), render_on(&b, 2));
            let c = compare(
                &fa.to_display(a.settings.exposure_scale).rgb(),
                &fb.to_display(b.settings.exposure_scale).rgb(),
            );
            assert!(
                c.passes(),
                "{name} under {filter}: formula and built-in renders differ: {} of pixels, mean {}, max {}",
                c.bad_fraction,
                c.mean_diff,
                c.max_diff
            );
            let marked: u64 = b
                .materials
                .iter()
                .map(|mat| mat.texture().non_finite_count())
                .sum();
            assert_eq!(marked, 0, "{name} under {filter}: no pixel is NaN");
        }
    }
}

/// A formula mapping runs per lane in the kernel's packets: the image is the width-1 kernel's, the
/// marked pixels (NaN below the equator, where sqrt(y) is) included.
#[test]
fn a_formula_mapping_renders_the_same_in_packets_and_at_width_one() {
    let path = root().join("presets/earth.ron");
    let (_, own) = preset_pair("earth", Mapping::Spherical);
    let mut half = own.clone();
    half.objects[0]
        .material
        .texture_mut()
        .set_mapping(formula("fract(atan2(x, z) / tau) + sqrt(y) * 0", "sqrt(y)"));
    let pool = thread_pool(2).expect("pool");
    for (desc, marked) in [(own, false), (half, true)] {
        let scene = build_with(&desc, &path, sized(64, 48, 1), &mut AssetCache::new());
        let auto = pool.install(|| render_blocking_with(&scene, SimdMode::Auto, |_| {}));
        let counted = scene.materials[0].texture().non_finite_count();
        assert_eq!(counted > 0, marked, "{counted} hits counted");
        let scalar = pool.install(|| render_blocking_with(&scene, SimdMode::Scalar, |_| {}));
        let display =
            |f: &texplore::render::Film| f.to_display(scene.settings.exposure_scale).rgb();
        assert_eq!(display(&auto), display(&scalar));
        // Both paths count the same hits.
        assert_eq!(scene.materials[0].texture().non_finite_count(), 2 * counted);
    }
}

/// Each common mistake, written as a student would, gets its hint and no other; the correct
/// formulas get none.
#[test]
fn each_common_mistake_gets_its_hint_and_a_correct_formula_none() {
    let tol = one_texel(2048, 1024);
    let v_ok = "1 - acos(y / sqrt(x*x + y*y + z*z)) / pi";
    let u_ok = "fract(atan2(x, z) / tau)";
    let sphere = sample_points(Mapping::Spherical, 64);
    for (u, v, want) in [
        (v_ok, u_ok, Mistake::Swapped),
        ("1 - fract(atan2(x, z) / tau)", v_ok, Mistake::MirroredU),
        ("fract(atan2(z, x) / tau)", v_ok, Mistake::Atan2Arguments),
        (u_ok, "acos(y) / pi", Mistake::FlippedV),
        (
            "fract(atan2(x, z) / tau + 0.25)",
            v_ok,
            Mistake::QuarterTurn,
        ),
        ("(atan2(x, z) + pi) / tau", v_ok, Mistake::HalfTurn),
        ("fract(atan2(x, z) / 360)", v_ok, Mistake::Degrees),
        (u_ok, "1 - acos(y) / 180", Mistake::Degrees),
    ] {
        let f = FormulaMapping::new(u, v).expect("compiles");
        let found = mistakes(&f, Mapping::Spherical, &sphere, tol);
        assert_eq!(found, vec![want], "u = {u}, v = {v}");
        assert!(!want.hint(Mapping::Spherical).is_empty());
    }
    // The lecture's acos(y) without the flip is named as such.
    assert!(
        Mistake::FlippedV
            .hint(Mapping::Spherical)
            .contains("1 - acos(y) / pi")
    );
    // The probe: v upside down, and the image turned by a quarter.
    let probe = sample_points(Mapping::LightProbe, 64);
    let (pu, pv) = lecture_formula(Mapping::LightProbe).expect("probe");
    let flipped = FormulaMapping::new(pu, &format!("1 - {pv}")).expect("compiles");
    assert_eq!(
        mistakes(&flipped, Mapping::LightProbe, &probe, tol),
        vec![Mistake::FlippedV]
    );
    let turned = FormulaMapping::new(&format!("1 - {pv}"), pu).expect("compiles");
    assert_eq!(
        mistakes(&turned, Mapping::LightProbe, &probe, tol),
        vec![Mistake::QuarterTurn]
    );
    for m in LECTURE {
        let points = sample_points(m, 64);
        let f = lecture(m);
        assert!(mistakes(&f, m, &points, tol).is_empty(), "{m}");
        assert_eq!(agreement(&f, m, &points, tol).share(), 1.0, "{m}");
    }
    // Something unrelated agrees nowhere and gets no hint: nothing to say but the number.
    let noise = FormulaMapping::new("x * y", "z").expect("compiles");
    assert!(mistakes(&noise, Mapping::Spherical, &sphere, tol).is_empty());
    assert!(agreement(&noise, Mapping::Spherical, &sphere, tol).share() < 0.05);
}

#[test]
fn map_formula_prints_the_worked_values_and_compares() {
    let (u, v) = lecture_formula(Mapping::Spherical).expect("spherical");
    let own = json(&[
        "map", "formula", "--u", u, "--v", v, "0.6", "0", "-0.8", "--json",
    ]);
    let builtin = json(&["map", "spherical", "0.6", "0", "-0.8", "--json"]);
    for key in ["u", "v"] {
        assert!((own[key].as_f64().unwrap() - builtin[key].as_f64().unwrap()).abs() < 1e-12);
    }
    assert_eq!(own["column"], builtin["column"]);
    assert_eq!(own["row"], builtin["row"]);
    assert_eq!(own["formula"]["derivatives"], "finite-differences");
    let text = success(&texplore(&[
        "map",
        "formula",
        "--u",
        u,
        "--v",
        "acos(y) / pi",
        "0.6",
        "0",
        "-0.8",
        "--compare",
        "spherical",
    ]));
    assert!(
        text.contains(
            "u = fract(atan2(x, z) / tau) = fract(atan2(0.6000, (-0.8000)) / tau) = 0.3976"
        ),
        "{text}"
    );
    assert!(
        text.contains("compared with the spherical mapping:"),
        "{text}"
    );
    assert!(text.contains("theta = acos(y)"), "{text}");
    assert!(
        text.contains("difference: |du| = 0.0000, |dv| = 0.0000"),
        "{text}"
    );
    // At the equator the flip changes nothing; over the sphere it does.
    assert!(text.contains("% agree within one texel"), "{text}");
    assert!(text.contains("hint: u agrees; v is upside down"), "{text}");
    let right = success(&texplore(&[
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
        "spherical",
    ]));
    assert!(right.contains("100.0 % agree"), "{right}");
    assert!(!right.contains("hint:"), "{right}");
}

#[test]
fn map_formula_errors_show_the_column_and_a_caret() {
    let err = failure(&texplore(&[
        "map", "formula", "--u", "x + w", "--v", "y", "0", "0", "1",
    ]));
    assert!(err.contains("--u: column 5: unknown name `w`"), "{err}");
    assert!(err.contains("x + w\n      ^"), "{err}");
    let err = failure(&texplore(&["map", "formula", "--u", "x", "0", "0", "1"]));
    assert!(err.contains("needs both --u and --v"), "{err}");
    let err = failure(&texplore(&["map", "spherical", "--u", "x", "0", "0", "1"]));
    assert!(err.contains("--u and --v are for `formula`"), "{err}");
    let err = failure(&texplore(&["map", "formulae", "0", "0", "1"]));
    assert!(err.contains("or formula"), "{err}");
}

/// A preset with a formula mapping and a formula texture saves and loads back the same, and
/// renders.
#[test]
fn formulas_round_trip_through_presets() {
    let text = r#"(
        version: 1,
        camera: (eye: (0, 0, 3.6), projection: Pinhole(fov: 40)),
        render: (width: 32, height: 24, spp: 1),
        objects: [
            (shape: Sphere, material: Matte(cd: Image(path: "../assets/earth_2048x1024.jpg",
                mapping: Formula(u: "fract(atan2(x, z) / tau)", v: "1 - acos(y) / pi")))),
            (shape: Sphere, transform: (translate: (2, 0, 0)),
                material: Matte(cd: Formula(mapping: Cylindrical,
                    grey: "0.05 + 0.75 * 2 * fract((floor(8 * u) + floor(8 * v)) / 2)"))),
            (shape: Sphere, transform: (translate: (-2, 0, 0)),
                material: Matte(cd: Formula(r: "u", g: "v", b: "abs(z)"))),
        ],
    )"#;
    let path = root().join("presets/formula.ron");
    let desc = parse_preset(text, &path).expect("parses");
    let again = parse_preset(&to_ron(&desc), &path).expect("reads back");
    assert_eq!(again, desc);
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("builds");
    let film = render_on(&scene, 2);
    assert!(film.to_display(1.0).rgb().iter().any(|&b| b > 0));
}

fn build_error(material: &str) -> String {
    let text = format!(
        "(version: 1, camera: (eye: (0, 0, 3)), render: (width: 8, height: 8, spp: 1),
          objects: [(shape: Sphere, material: {material})])"
    );
    let path = root().join("presets/hostile.ron");
    let desc = parse_preset(&text, &path).expect("parses: the formulas are only text");
    build_scene(&desc, &path, &mut AssetCache::new())
        .map(|_| ())
        .expect_err("refused")
        .to_string()
}

/// Errors name the field path and the column.
#[test]
fn preset_formula_errors_name_the_field_and_the_column() {
    let e = build_error(r#"Matte(cd: Checker(mapping: Formula(u: "x", v: "acos(y) / pj")))"#);
    assert!(
        e.contains("objects[0].material.cd.mapping.v: column 11: unknown name `pj`"),
        "{e}"
    );
    let e = build_error(r#"Matte(cd: Formula(grey: "floor(8 * u"))"#);
    assert!(
        e.contains("objects[0].material.cd.grey: column 6: this `(` is never closed"),
        "{e}"
    );
    let e = build_error(r#"Matte(cd: Formula(r: "u", g: "v"))"#);
    assert!(
        e.contains("objects[0].material.cd: Formula: b missing"),
        "{e}"
    );
    // A textured coefficient names its parameter.
    let e = build_error(
        r#"Phong(cd: Constant((1, 1, 1)), ks: Checker(mapping: Formula(u: "x", v: "y +")))"#,
    );
    assert!(
        e.contains("objects[0].material.ks.mapping.v: column 4: missing a value at the end"),
        "{e}"
    );
    let e = build_error(r#"Matte(cd: Formula(grey: "u", r: "v"))"#);
    assert!(e.contains("grey and r both given"), "{e}");
}

/// Deep nesting, 100 kB of text, unknown names: one clear error each, at once. Division by
/// zero and acos(2): the scene builds, the pixels are marked magenta and counted.
#[test]
fn hostile_formulas_give_clear_errors_or_marked_pixels() {
    let start = Instant::now();
    let deep = "(".repeat(10_000) + "x" + &")".repeat(10_000);
    let e = build_error(&format!(r#"Matte(cd: Formula(grey: "{deep}"))"#));
    assert!(
        e.contains("grey: ") && e.contains("at most 4096"),
        "{}",
        &e[..e.len().min(300)]
    );
    let nested = "(".repeat(40) + "x" + &")".repeat(40);
    let e = build_error(&format!(r#"Matte(cd: Formula(grey: "{nested}"))"#));
    assert!(
        e.contains("column 33: brackets nested deeper than 32"),
        "{e}"
    );
    let huge = "x + ".repeat(25_000) + "1";
    let e = build_error(&format!(r#"Matte(cd: Formula(grey: "{huge}"))"#));
    assert!(
        e.contains("100001 bytes long; a formula may have at most 4096"),
        "{e}"
    );
    assert!(
        e.len() < 400,
        "the error does not repeat the text: {} bytes",
        e.len()
    );
    let e = build_error(r#"Matte(cd: Checker(mapping: Formula(u: "longitude", v: "y")))"#);
    assert!(e.contains("unknown name `longitude`"), "{e}");
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "{:?}",
        start.elapsed()
    );

    for (u, v) in [("x / 0", "y"), ("acos(2)", "y"), ("x", "sqrt(-1 - y * y)")] {
        let text = format!(
            r#"(version: 1, camera: (eye: (0, 0, 3)), render: (width: 16, height: 16, spp: 1),
              objects: [(shape: Sphere, material: Emissive(ls: 1, ce: Checker(mapping: Formula(u: "{u}", v: "{v}"))))])"#
        );
        let path = Path::new("hostile.ron");
        let desc = parse_preset(&text, path).expect("parses");
        let scene = build_scene(&desc, path, &mut AssetCache::new()).expect("builds");
        let rgb = render_on(&scene, 2).to_display(1.0).rgb();
        let magenta = rgb
            .chunks(3)
            .filter(|p| p[0] == 255 && p[1] == 0 && p[2] == 255)
            .count();
        let count = scene.materials[0].texture().non_finite_count();
        assert!(magenta > 16, "{u}; {v}: {magenta} magenta pixels");
        assert!(count >= magenta as u64, "{u}; {v}: counted {count}");
    }
}

/// `texplore render` says where a formula was not finite.
#[test]
fn render_warns_of_a_formula_that_is_not_finite() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = dir.path().join("nan.ron");
    std::fs::write(
        &preset,
        r#"(version: 1, camera: (eye: (0, 0, 3)), render: (width: 16, height: 16, spp: 1),
          objects: [(name: "ball", shape: Sphere, material: Matte(cd: Formula(grey: "sqrt(y)")))])"#,
    )
    .expect("write");
    let out = texplore(&[
        "render",
        preset.to_str().expect("utf-8"),
        "-o",
        dir.path().join("nan.png").to_str().expect("utf-8"),
    ]);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    success(&out);
    assert!(
        err.contains(
            "warning: objects[0].material.cd (object \"ball\"): its formula was NaN or infinite at"
        ),
        "{err}"
    );
}

/// A formula texture: the lecture's checker written with floor matches the built-in checker.
#[test]
fn the_checker_written_with_floor_is_the_builtin_checker() {
    let path = root().join("presets/checker.ron");
    let desc = load_preset(&path).expect("preset");
    let mut own = desc.clone();
    for o in &mut own.objects {
        let t = o.material.texture_mut();
        if let TextureDesc::Checker {
            mapping,
            squares,
            colors,
            ..
        } = t.clone()
        {
            let channel = |a: f32, b: f32| {
                format!(
                    "{a} + ({b} - {a}) * 2 * fract((floor({} * u) + floor({} * v)) / 2)",
                    squares.0, squares.1
                )
            };
            *t = TextureDesc::Formula {
                mapping,
                grey: String::new(),
                r: channel(colors.0.0, colors.1.0),
                g: channel(colors.0.1, colors.1.1),
                b: channel(colors.0.2, colors.1.2),
                uv: texplore::mapping::UvTransform::IDENTITY,
            };
        }
    }
    let mut cache = AssetCache::new();
    let a = build_with(&desc, &path, sized(96, 72, 1), &mut cache);
    let b = build_with(&own, &path, sized(96, 72, 1), &mut cache);
    let c = compare(
        &render_on(&a, 2).to_display(1.0).rgb(),
        &render_on(&b, 2).to_display(1.0).rgb(),
    );
    assert!(
        c.passes(),
        "{} {} {}",
        c.bad_fraction,
        c.mean_diff,
        c.max_diff
    );
}
