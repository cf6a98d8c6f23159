//! Formula mappings: mistakes found with their columns, the derivatives (symbolic against
//! finite differences), the seam of `fract`, non-finite results counted.

use super::compare::lecture_formula;
use super::*;
use crate::mapping::Mapping;

fn err(u: &str) -> FormulaError {
    FormulaMapping::new(u, "y").expect_err(u)
}

#[test]
fn mistakes_are_found_with_their_column() {
    for (text, column, words) in [
        ("x + w", 5, "unknown name `w`"),
        ("x +* 2", 4, "missing a value before `*`"),
        ("atan2(x)", 6, "atan2 takes two arguments, not 1"),
        ("atan2(x, y, z)", 11, "atan2 takes two arguments, not 3"),
        ("clamp(x, 0, 1)", 8, "clamp takes one argument"),
        ("(x", 1, "never closed"),
        ("x)", 2, "without its `(`"),
        ("sqrt x", 1, "`sqrt` is a function: write sqrt(t)"),
        ("2x", 2, "missing an operator before `x`"),
        ("x $ y", 3, "unexpected character `$`"),
        ("1.2.3", 1, "`1.2.3` is not a number"),
        ("x +", 4, "missing a value at the end"),
        ("", 1, "the formula is empty"),
        ("PI * x", 1, "(write pi)"),
        ("min(x, )", 8, "missing a value before `)`"),
        ("x, y", 2, "outside a function's arguments"),
        ("x * 1e-3", 5, "write `1e-3` without an exponent"),
        (
            "min(x, 1 + max(y, z))",
            12,
            "exmex cannot read max inside the second argument of min",
        ),
    ] {
        let e = err(text);
        assert_eq!(e.column, Some(column), "{text}: {e}");
        assert!(e.message.contains(words), "{text}: {e}");
        assert_eq!(e.field, "u");
        assert!(
            e.to_string().starts_with(&format!("u: column {column}: ")),
            "{e}"
        );
    }
    let e = FormulaMapping::new("x", "y + q").expect_err("v");
    assert_eq!(e.field, "v");
    assert_eq!(e.pointer().as_deref(), Some("y + q\n    ^"));
}

#[test]
fn length_and_nesting_are_bounded() {
    let long = "x + ".repeat(30_000) + "x";
    let e = err(&long);
    assert!(e.message.contains("at most 4096"), "{e}");
    assert!(
        e.text.is_empty(),
        "a huge formula is not copied into its error"
    );
    let deep = "(".repeat(MAX_NESTING + 1) + "x" + &")".repeat(MAX_NESTING + 1);
    let e = err(&deep);
    assert_eq!(e.column, Some(MAX_NESTING + 1));
    assert!(e.message.contains("nested deeper"), "{e}");
    let ok = "(".repeat(MAX_NESTING) + "x" + &")".repeat(MAX_NESTING);
    assert!(FormulaMapping::new(&ok, "y").is_ok());
    let calls = "sqrt(".repeat(MAX_NESTING + 1) + "x" + &")".repeat(MAX_NESTING + 1);
    assert!(err(&calls).message.contains("nested deeper"));
}

#[test]
fn the_lecture_formulas_match_the_builtin_mappings() {
    for m in [
        Mapping::Rectangular,
        Mapping::Cylindrical,
        Mapping::Spherical,
        Mapping::LightProbe,
    ] {
        let (u, v) = lecture_formula(m).expect("the lecture writes it");
        let f = FormulaMapping::new(u, v).expect("compiles");
        let points = compare::sample_points(m, 40);
        let a = compare::agreement(&f, m, &points, glam::DVec2::splat(1e-6));
        assert_eq!(a.agreeing, a.points, "{m}: {a:?}");
        assert!(a.max_difference.max_element() < 1e-12, "{m}: {a:?}");
    }
}

/// A formula exmex differentiates: its derivatives against central differences of its value.
#[test]
fn symbolic_derivatives_match_finite_differences() {
    let (u, v) = lecture_formula(Mapping::LightProbe).expect("probe");
    for (u, v) in [
        (u, v),
        ("(z + 1) / 2", "(x + 1) / 2"),
        (
            "sin(3 * x) * exp(y) + z ^ 3",
            "ln(2 + x * y) - tan(z / 2) + mesh_u * mesh_v",
        ),
        (
            "asin(x / 2) + atan(y) + sqrt(2 + z)",
            "cos(x) / (1 + y * y)",
        ),
    ] {
        let f = FormulaMapping::new(u, v).expect("compiles");
        assert_eq!(f.derivative_kind(), DerivativeKind::Symbolic, "{u}; {v}");
        for p in [
            [0.3, -0.4, 0.5, 0.2, 0.7],
            [-0.6, 0.1, 0.2, 0.9, 0.1],
            [0.1, 0.8, -0.5, 0.5, 0.5],
        ] {
            let g = f.gradients(&p);
            for k in 0..5 {
                let h = 1e-6;
                let (mut a, mut b) = (p, p);
                a[k] += h;
                b[k] -= h;
                let fd = (f.eval(&a) - f.eval(&b)) / (2.0 * h);
                for (c, want) in [(0, fd.x), (1, fd.y)] {
                    assert!(
                        (g[c][k] - want).abs() < 1e-6 * (1.0 + want.abs()),
                        "{u}; {v} at {p:?}: d{}/d{} symbolic {} finite {want}",
                        ["u", "v"][c],
                        MAPPING_VARS[k],
                        g[c][k]
                    );
                }
            }
        }
    }
}

/// A formula with a function exmex cannot differentiate uses finite differences and says
/// which; across the seam of `fract` the difference is the slope, not the jump.
#[test]
fn finite_differences_name_the_function_and_ignore_the_seam() {
    let (u, v) = lecture_formula(Mapping::Spherical).expect("spherical");
    let f = FormulaMapping::new(u, v).expect("compiles");
    assert_eq!(f.derivative_kind(), DerivativeKind::FiniteDifferences);
    let note = f.derivative_note();
    assert!(note.contains("atan2") && note.contains("fract"), "{note}");
    // Just beside the seam (x = -1e-7, z = 1): u is 0.99999998, and a step across it reads 0.
    let builtin = Mapping::Spherical.map_point(Vec3A::new(-1e-7, 0.0, 1.0));
    let g = f.gradients(&[-1e-7, 0.0, 1.0, 0.0, 0.0]);
    let want = builtin.grad_u;
    for k in 0..3 {
        assert!(
            (g[0][k] - f64::from(want[k])).abs() < 1e-4,
            "du/d{}: {} finite, {} built-in",
            MAPPING_VARS[k],
            g[0][k],
            want[k]
        );
    }
}

/// The screen-space derivatives the filters get: the built-in mapping's.
#[test]
fn tex_coord_derivatives_follow_the_builtin_mapping() {
    for m in [
        Mapping::Spherical,
        Mapping::LightProbe,
        Mapping::Cylindrical,
    ] {
        let (u, v) = lecture_formula(m).expect("lecture");
        let f = FormulaMapping::new(u, v).expect("compiles");
        let p = Vec3A::new(0.48, 0.6, 0.64);
        let (dx, dy) = (
            Vec3A::new(1e-3, 0.0, -0.75e-3),
            Vec3A::new(0.0, 8e-4, -7.5e-4),
        );
        let want = m.map_with_differentials(p, dx, dy, None, m);
        let got = f.tex_coord(p, dx, dy, (Vec2::ZERO, Vec2::ZERO, Vec2::ZERO));
        assert!((got.uv - want.uv).abs().max_element() < 1e-6, "{m}");
        for (a, b) in [(got.duvdx, want.duvdx), (got.duvdy, want.duvdy)] {
            assert!(
                (a - b).abs().max_element() < 1e-5 * (1.0 + b.abs().max_element()),
                "{m}: {a} {b}"
            );
        }
    }
}

#[test]
fn non_finite_results_are_counted_not_raised() {
    let f =
        FormulaMapping::new("acos(2)", "1 / x").expect("compiles: the mistake is in the numbers");
    let tc = f.tex_coord(
        Vec3A::new(0.0, 1.0, 0.0),
        Vec3A::X,
        Vec3A::Y,
        (Vec2::ZERO, Vec2::ZERO, Vec2::ZERO),
    );
    assert!(tc.uv.is_nan());
    assert_eq!(f.non_finite_count(), 1);
    let (lines, uv) = f.explain(&[0.0, 1.0, 0.0, 0.0, 0.0]);
    assert!(!uv.is_finite());
    assert!(
        lines.iter().any(|l| l.contains("marked magenta")),
        "{lines:?}"
    );
}

#[test]
fn the_worked_formula_substitutes_the_point() {
    let f = FormulaMapping::new("fract(atan2(x, z) / tau)", "(y + 1) / 2").expect("compiles");
    let (lines, _) = f.explain(&[-0.6, 0.5, 0.8, 0.0, 0.0]);
    assert_eq!(
        lines[0],
        "u = fract(atan2(x, z) / tau) = fract(atan2((-0.6000), 0.8000) / tau) = 0.8976"
    );
    assert_eq!(lines[1], "v = (y + 1) / 2 = (0.5000 + 1) / 2 = 0.7500");
}

/// The compiled program gives exmex's own value, bit for bit, on formulas of every operator,
/// precedence and unary minus (exmex's rules: `-x^2` is (-x)^2); its derivatives give exmex's
/// own symbolic derivatives (which texplore no longer runs: they recurse) to rounding.
#[test]
fn the_program_is_exmex_bit_for_bit() {
    let formulas = [
        "fract(atan2(x, z) / tau)",
        "1 - acos(y / sqrt(x*x + y*y + z*z)) / pi",
        "-x^2 + 2^3^2 - y / z / 2 * 3",
        "x - -y * -z",
        "min(max(y, z), x) + abs(sign(x - y)) * clamp(z * 3)",
        "floor(8 * x) + ceil(y) - round(z * 2.5) + fract(-x)",
        "sin(x) * cos(y) / tan(z + 2) + exp(-x * x) - ln(2 + y) + atan(z) + asin(x / 2)",
        "(((x + 1) * (y - 1)) / ((z + 2) * 0.5)) ^ 2",
        "0.001 * x + 250.5 * mesh_u - mesh_v / 10",
        "pi * tau - 2 * pi * x",
        "1 / 0 + acos(2)",
        "x ^ y + z ^ 3 - 2 ^ mesh_u + acos(x / 3) * x / y / z",
    ];
    let points = [
        [0.3, -0.4, 0.5, 0.2, 0.7],
        [-0.6, 0.1, 0.2, 0.9, 0.1],
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [1.7, -2.5, 0.75, -3.0, 12.0],
    ];
    for text in formulas {
        let e = Expr::compile("u", text, &MAPPING_VARS).expect(text);
        for p in &points {
            let (a, b) = (e.eval(p), e.eval_exmex(p));
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                "{text} at {p:?}: program {a}, exmex {b}"
            );
        }
        for (k, name) in MAPPING_VARS.iter().enumerate() {
            let Some(index) = e.slots.iter().position(|&s| s == k) else {
                continue;
            };
            let Ok(theirs) = e.flat.clone().partial(index) else {
                assert!(!e.plain_functions().is_empty(), "{text}: d/d{name}");
                continue;
            };
            if !e.plain_functions().is_empty() {
                continue;
            }
            let ours = e.partial(k).expect("reads it");
            for p in &points {
                let mut values = vec![0.0; e.slots.len()];
                for (v, &slot) in values.iter_mut().zip(&e.slots) {
                    *v = p[slot];
                }
                let (a, b) = (ours.eval(p), theirs.eval(&values).unwrap_or(f64::NAN));
                assert!(
                    (a - b).abs() <= 1e-12 * (1.0 + b.abs()) || (!a.is_finite() && !b.is_finite()),
                    "{text} at {p:?}: d/d{name} {a}, exmex {b}"
                );
            }
        }
    }
}

/// A mapping compiled for a check (the window's UI thread) says what its derivatives will be
/// without building them, and builds the same ones on first use.
#[test]
fn a_checked_mapping_builds_its_derivatives_on_first_use() {
    for (u, v) in [
        ("sin(3 * x) * exp(y) + z ^ 3", "x / y / z"),
        ("fract(atan2(x, z) / tau)", "(y + 1) / 2"),
        ("x + floor(2.5)", "y"),
    ] {
        let (now, later) = (
            FormulaMapping::new(u, v).expect(u),
            FormulaMapping::checked(u, v).expect(u),
        );
        assert_eq!(now.derivative_note(), later.derivative_note(), "{u}");
        if let Derivatives::Symbolic(g) = &later.derivatives {
            assert!(g.get().is_none(), "{u}: not built yet");
        }
        let p = [0.3, -0.4, 0.5, 0.2, 0.7];
        assert_eq!(now.gradients(&p), later.gradients(&p), "{u}");
    }
    // A function of numbers alone is folded away: the derivative stays symbolic.
    assert_eq!(
        FormulaMapping::checked("x + floor(2.5)", "y")
            .expect("compiles")
            .derivative_kind(),
        DerivativeKind::Symbolic
    );
}
