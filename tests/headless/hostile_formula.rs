//! Hostile formulas (issue 38 §1): a formula of any shape up to the 4096-byte limit works or
//! is refused with a message, and never overflows the stack, in the library (on a thread of a
//! quarter of a worker's stack), `texplore map formula`, `render` of a formula mapping or
//! texture, and `lesson --list` with an exercise's solution. Before, exmex's recursive
//! derivative aborted the process (`fatal runtime error: stack overflow`, exit 134) at 64
//! operands of `/` in `map formula`, 48 in `render`, 100 terms of a lesson's solution.

use crate::common::{root, texplore};
use crate::formulas::{chain, fill, hostile_formulas};
use std::path::Path;
use std::process::Output;
use texplore::mapping::FormulaMapping;
use texplore::mapping::formula::{MAX_FORMULA_BYTES, TEXTURE_VARS};

/// A killed process (an abort is signal 6, exit 134 from a shell) fails here, naming the case.
fn no_abort(o: &Output, what: &str) {
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.code().is_some(),
        "{what}: killed ({}): {e}",
        o.status
    );
    assert!(
        !e.contains("overflowed its stack") && !e.contains("panicked"),
        "{what}: {e}"
    );
}

/// Works, or is refused only past the length limit, saying so.
fn works_or_too_long(o: &Output, formula: &str, what: &str) {
    no_abort(o, what);
    let e = String::from_utf8_lossy(&o.stderr);
    if formula.len() > MAX_FORMULA_BYTES {
        assert!(!o.status.success(), "{what}");
        assert!(e.contains("a formula may have at most 4096"), "{what}: {e}");
    } else {
        assert!(o.status.success(), "{what}: {e}");
    }
}

#[test]
fn every_shape_up_to_the_limit_compiles_with_its_derivatives_on_a_small_stack() {
    let cases = hostile_formulas();
    let worker = std::thread::Builder::new()
        .stack_size(512 * 1024)
        .spawn(move || {
            let p = [0.3, -0.4, 0.5, 0.2, 0.7];
            for (name, text) in &cases {
                match FormulaMapping::new(text, "y") {
                    Ok(f) => {
                        assert!(text.len() <= MAX_FORMULA_BYTES, "{name}");
                        let uv = f.eval(&p);
                        let g = f.gradients(&p);
                        // Exactly what the formula is, where that is easy to say.
                        if text.starts_with("x+x+") {
                            let n = text.matches('x').count();
                            assert!((uv.x - 0.3 * n as f64).abs() < 1e-9 * n as f64, "{name}");
                            assert_eq!(g[0][0], n as f64, "{name}");
                        }
                    }
                    Err(e) => {
                        assert!(text.len() > MAX_FORMULA_BYTES, "{name}: {e}");
                        assert!(e.to_string().starts_with("u: "), "{name}: {e}");
                    }
                }
                // The same text as a colour formula.
                let colour = texplore::mapping::formula::Expr::compile("grey", text, &TEXTURE_VARS);
                if let Err(e) = colour {
                    assert!(!e.message.is_empty(), "{name}");
                }
            }
        })
        .expect("a thread");
    worker.join().expect("no overflow, no panic");
}

#[test]
fn map_formula_works_or_refuses_every_shape() {
    for (name, text) in hostile_formulas() {
        let o = texplore(&[
            "map", "formula", "0.3", "0.2", "0.1", "--u", &text, "--v", "y",
        ]);
        works_or_too_long(&o, &text, &format!("map formula: {name}"));
        if o.status.success() {
            assert!(
                String::from_utf8_lossy(&o.stdout).contains("u = "),
                "{name}"
            );
        }
    }
}

/// A sphere whose checker reads the formula mapping `u` under EWA (the derivatives are read).
fn preset(dir: &Path, u: &str, grey: &str) -> std::path::PathBuf {
    let text = format!(
        r#"(
    version: 1,
    camera: (eye: (0, 0, 4), look_at: (0, 0, 0), up: (0, 1, 0), projection: Pinhole(fov: 40)),
    render: (width: 8, height: 6, spp: 1),
    ambient: (ls: 0.4),
    lights: [Directional(direction: (0.2, 1, 0.4), ls: 2.6)],
    objects: [
        (shape: Sphere, material: Matte(ka: 0.5, kd: 0.9,
            cd: Checker(mapping: Formula(u: "{u}", v: "y"), filter: Ewa))),
        (shape: Sphere, transform: (translate: (1, 0, 0), scale: (0.3, 0.3, 0.3)),
            material: Matte(ka: 0.5, kd: 0.9, cd: Formula(grey: "{grey}"))),
    ],
)"#
    );
    let path = dir.join("formula.ron");
    std::fs::write(&path, text).expect("write preset");
    path
}

#[test]
fn render_works_or_refuses_every_shape_of_formula_mapping_and_texture() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("out.png");
    let (o, p) = (out.to_str().expect("utf-8"), dir.path());
    for (name, text) in hostile_formulas() {
        let ron = preset(p, &text, "u");
        let r = texplore(&["render", ron.to_str().expect("utf-8"), "-o", o]);
        works_or_too_long(&r, &text, &format!("render, mapping: {name}"));
        // As a colour formula (over u, v, x, y, z: mesh_u is refused by name).
        let ron = preset(p, "x", &text);
        let r = texplore(&["render", ron.to_str().expect("utf-8"), "-o", o]);
        no_abort(&r, &format!("render, texture: {name}"));
        if !text.contains("mesh_u") {
            works_or_too_long(&r, &text, &format!("render, texture: {name}"));
        }
    }
}

/// A lesson on the rectangle preset whose exercise's solution is `u`.
fn lesson(dir: &Path, u: &str) {
    let preset = root().join("presets/rectangle.ron");
    let text = format!(
        "title = \"Long\"\npreset = {:?}\ntext = \"x\"\n\n[[exercise]]\ntask = \"t\"\ntarget = \"Rectangular\"\nstart = {{ u = \"\", v = \"\" }}\nsolution = {{ u = \"{u}\", v = \"(x + 1) / 2\" }}\n\n[question]\nask = \"a\"\nanswer = \"b\"\n",
        preset.display().to_string()
    );
    std::fs::write(dir.join("long.toml"), text).expect("write lesson");
}

#[test]
fn lesson_list_takes_a_long_solution() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path().to_str().expect("utf-8");
    // (z + 1) / 2 plus terms that cancel: 100 terms, then as many as fit.
    let hundred = format!("(z + 1) / 2{}", "+x-x".repeat(49));
    let longest = fill("x-x", "+", "(z + 1) / 2");
    for u in [
        hundred,
        longest,
        format!("(z + 1) / 2 + 0 * ({})", chain("*", 200)),
    ] {
        lesson(dir.path(), &u);
        let o = texplore(&["lesson", "--list", "--dir", d]);
        no_abort(&o, &format!("lesson --list, {} bytes", u.len()));
        assert!(
            o.status.success(),
            "{} bytes: {}",
            u.len(),
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(String::from_utf8_lossy(&o.stdout).contains("Long"));
    }
}
