//! Hostile values: numbers that are not numbers, counts of zero, options that would silently do
//! nothing, a PLY loop that never ends, and the report's reference cache (keyed on every file
//! the scene reads, checksummed, shared by two reports at once). Most tests drive the real
//! binary and look at what it prints and writes; renders are tiny.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};
use texplore::scene::{AssetCache, build_scene, parse_preset};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn texplore(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(root())
        .args(args)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Asserts the command failed and its message contains every one of `parts`.
fn assert_refused(o: &Output, parts: &[&str]) {
    let e = stderr(o);
    assert!(!o.status.success(), "should have failed; stderr: {e}");
    for p in parts {
        assert!(e.contains(p), "expected '{p}' in: {e}");
    }
    assert!(!e.contains("panicked"), "{e}");
}

// ---------------------------------------------------------------------------------------------
// Presets: every number of every kind of field, NaN and infinities refused by name.

/// A preset with every numeric field of every part the format has (camera, render, adaptive,
/// ambient, both lights, transform, the three materials and every texture with numbers).
/// Each `@name` is a number, replaced by its default or by the hostile value under test.
const TEMPLATE: &str = r#"(
    version: 1,
    camera: (eye: (@eye, 1, 4), look_at: (0, @look_at, 0), up: (0, @up, 0),
             projection: Pinhole(fov: @fov)),
    render: (width: 8, height: 6, spp: 1, exposure: @exposure, background: (0, @background, 0),
             adaptive: Some((max_spp: 4, threshold: @threshold))),
    ambient: (ls: @ambient_ls, color: (1, @ambient_color, 1)),
    lights: [
        Directional(direction: (1, @direction, 1), ls: @dir_ls, color: (1, 1, @dir_color)),
        Point(position: (0, @position, 0), ls: @point_ls, color: (@point_color, 1, 1)),
    ],
    objects: [
        (shape: Sphere,
         transform: (translate: (@translate, 0, 0), rotate: (0, @rotate, 0), scale: (1, 1, @scale)),
         material: Phong(ka: @ka, kd: @kd, ks: @ks, cs: (1, @cs, 1), exp: @exp,
             cd: Checker(squares: (@squares, 8), colors: ((@colors, 0.8, 0.8), (0.1, 0.1, 0.1))))),
        (shape: Plane, material: Matte(ka: @matte_ka, kd: @matte_kd,
             cd: Constant((0.5, @constant, 0.5)))),
        (shape: Disk, material: Emissive(ls: @emissive_ls, ce: UvGrid(max_anisotropy: @uv_aniso))),
        (shape: Rectangle, material: Matte(cd: Image(path: "@asset", scale: @image_scale,
             max_anisotropy: @image_aniso))),
        (shape: Mesh(path: "@mesh"), material: Matte(cd: MeshMaterial(max_anisotropy: @mesh_aniso))),
    ],
)"#;

/// Each placeholder, its ordinary value, and the field the error must name.
const FIELDS: &[(&str, &str, &str)] = &[
    ("@eye", "0", "camera.eye"),
    ("@look_at", "0.5", "camera.look_at"),
    ("@up", "1", "camera.up"),
    ("@fov", "50", "camera.projection.fov"),
    ("@exposure", "0", "render.exposure"),
    ("@background", "0", "render.background"),
    ("@threshold", "0.01", "render.adaptive.threshold"),
    ("@ambient_ls", "1", "ambient.ls"),
    ("@ambient_color", "1", "ambient.color"),
    ("@direction", "1", "lights[0].direction"),
    ("@dir_ls", "1", "lights[0].ls"),
    ("@dir_color", "1", "lights[0].color"),
    ("@position", "4", "lights[1].position"),
    ("@point_ls", "1", "lights[1].ls"),
    ("@point_color", "1", "lights[1].color"),
    ("@translate", "0", "objects[0].transform.translate"),
    ("@rotate", "0", "objects[0].transform.rotate"),
    ("@scale", "1", "objects[0].transform.scale"),
    ("@ka", "0.25", "objects[0].material.ka"),
    ("@kd", "0.75", "objects[0].material.kd"),
    ("@ks", "0.25", "objects[0].material.ks"),
    ("@cs", "1", "objects[0].material.cs"),
    ("@exp", "20", "objects[0].material.exp"),
    ("@squares", "8", "objects[0].material.cd.squares"),
    ("@colors", "0.8", "objects[0].material.cd.colors"),
    ("@matte_ka", "0.25", "objects[1].material.ka"),
    ("@matte_kd", "0.75", "objects[1].material.kd"),
    ("@constant", "0.5", "objects[1].material.cd"),
    ("@emissive_ls", "1", "objects[2].material.ls"),
    ("@uv_aniso", "8", "objects[2].material.ce.max_anisotropy"),
    ("@image_scale", "1", "objects[3].material.cd.scale"),
    ("@image_aniso", "8", "objects[3].material.cd.max_anisotropy"),
    ("@mesh_aniso", "8", "objects[4].material.cd.max_anisotropy"),
];

/// The template with `hostile` in place of `field` and every other number at its default.
fn preset_with(field: Option<&str>, hostile: &str) -> String {
    let mut text = TEMPLATE.to_string();
    // Longest names first, so `@ka` does not eat the start of `@matte_ka`'s neighbours.
    let mut fields: Vec<_> = FIELDS.to_vec();
    fields.sort_by_key(|f| std::cmp::Reverse(f.0.len()));
    for (name, default, _) in fields {
        let v = if Some(name) == field {
            hostile
        } else {
            default
        };
        text = text.replace(name, v);
    }
    // The files last: `@mesh` is the start of `@mesh_aniso`.
    let text = text
        .replace("@asset", s(&root().join("assets/checker_512.png")))
        .replace("@mesh", s(&root().join("assets/soup-can.obj")));
    assert!(!text.contains('@'), "a placeholder is left: {text}");
    text
}

fn build(text: &str) -> Result<(), String> {
    let path = Path::new("/presets/p.ron");
    let desc = parse_preset(text, path).map_err(|e| e.to_string())?;
    build_scene(&desc, path, &mut AssetCache::new())
        .map(|_| ())
        .map_err(|e| e.to_string())
}

#[test]
fn the_template_builds_with_ordinary_values() {
    build(&preset_with(None, "")).unwrap();
}

#[test]
fn nan_in_every_numeric_field_is_refused_naming_the_file_and_field() {
    for &(name, _, field) in FIELDS {
        let e = build(&preset_with(Some(name), "NaN")).expect_err(field);
        assert_eq!(
            e,
            format!("/presets/p.ron: {field}: NaN is not a number"),
            "{name}"
        );
    }
}

#[test]
fn infinities_in_every_numeric_field_are_refused_naming_the_field() {
    for (&(name, _, field), v) in FIELDS.iter().zip(["inf", "-inf"].iter().cycle()) {
        let e = build(&preset_with(Some(name), v)).expect_err(field);
        assert_eq!(
            e,
            format!("/presets/p.ron: {field}: {v} is not finite"),
            "{name}"
        );
    }
}

#[test]
fn every_projection_angle_is_checked() {
    for (projection, field) in [
        ("Fisheye(fov: NaN)", "camera.projection.fov"),
        (
            "Spherical(h_fov: NaN, v_fov: 90)",
            "camera.projection.h_fov",
        ),
        (
            "Spherical(h_fov: 360, v_fov: NaN)",
            "camera.projection.v_fov",
        ),
    ] {
        let text = preset_with(None, "").replace("Pinhole(fov: 50)", projection);
        assert_eq!(
            build(&text).unwrap_err(),
            format!("/presets/p.ron: {field}: NaN is not a number")
        );
    }
}

/// The issue's case: `ambient: (color: (1, NaN, 1))` rendered black. Now nothing is written.
#[test]
fn render_refuses_a_nan_ambient_colour_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let preset = tmp.path().join("p.ron");
    let text = std::fs::read_to_string(root().join("presets/checker.ron"))
        .unwrap()
        .replacen("ambient: (ls: 0.4)", "ambient: (color: (1, NaN, 1))", 1);
    std::fs::write(&preset, text).unwrap();
    let png = tmp.path().join("out.png");
    let o = texplore(&["render", s(&preset), "-o", s(&png), "-q"]);
    assert_refused(&o, &["p.ron: ambient.color: NaN is not a number"]);
    assert!(!png.exists());
}

/// A preset is never saved holding a number that does not read back.
#[test]
fn a_preset_with_nan_is_not_saved() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("saved.ron");
    let mut desc = parse_preset(&preset_with(None, ""), &path).unwrap();
    desc.ambient.color.1 = f32::NAN;
    let e = texplore::scene::save_preset(&desc, &path).unwrap_err();
    assert!(
        e.to_string()
            .ends_with("saved.ron: not saved: ambient.color: NaN is not a number"),
        "{e}"
    );
    assert!(!path.exists());
}

// ---------------------------------------------------------------------------------------------
// Command-line numbers.

#[test]
fn map_refuses_points_that_are_not_numbers() {
    for (x, y, z, bad) in [
        ("nan", "nan", "nan", "'nan' is not a number"),
        ("0", "inf", "0", "'inf' is not finite"),
        ("0", "0", "-inf", "'-inf' is not finite"),
    ] {
        let o = texplore(&["map", "spherical", x, y, z]);
        assert_refused(&o, &[bad]);
        assert!(stdout(&o).is_empty(), "{}", stdout(&o));
    }
}

/// A huge point is a direction like any other: |p| is printed as it is, not as `inf`.
#[test]
fn map_explains_a_huge_point_in_finite_numbers() {
    for mapping in ["spherical", "light-probe"] {
        let o = texplore(&["map", mapping, "1e300", "1e300", "1e300"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let out = stdout(&o);
        assert!(out.contains("|p| = 1.7321e300"), "{out}");
        assert!(!out.contains("NaN") && !out.contains("inf"), "{out}");
    }
}

#[test]
fn map_reads_negative_numbers_as_values() {
    let o = texplore(&["map", "spherical", "-7e-1", "0", "0.7", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["point"][0], -0.7);
    // phi = atan2(-0.7, 0.7) = -pi/4, taken into [0, 2 pi): u = 7/8; v at the equator.
    assert!((v["u"].as_f64().unwrap() - 0.875).abs() < 1e-12, "{v}");
    assert!((v["v"].as_f64().unwrap() - 0.5).abs() < 1e-12, "{v}");
}

#[test]
fn every_count_of_zero_is_refused_naming_the_option() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o.png");
    let o = s(&out);
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "report",
                "presets/checker.ron",
                "-o",
                o,
                "--reference-spp",
                "0",
            ],
            "--reference-spp",
        ),
        (
            &["report", "presets/checker.ron", "-o", o, "--repeat", "0"],
            "--repeat",
        ),
        (
            &["report", "presets/checker.ron", "-o", o, "--spp", "1,0"],
            "--spp",
        ),
        (
            &["report", "presets/checker.ron", "-o", o, "--width", "0"],
            "--width",
        ),
        (
            &[
                "report",
                "presets/checker.ron",
                "-o",
                o,
                "--heatmap-spp",
                "0",
            ],
            "--heatmap-spp",
        ),
        (
            &["render", "presets/checker.ron", "-o", o, "--width", "0"],
            "--width",
        ),
        (
            &["render", "presets/checker.ron", "-o", o, "--height", "0"],
            "--height",
        ),
        (
            &["render", "presets/checker.ron", "-o", o, "--spp", "0"],
            "--spp",
        ),
        (
            &["render", "presets/checker.ron", "-o", o, "--adaptive", "0"],
            "--adaptive",
        ),
        (&["bench", "presets/checker.ron", "--width", "0"], "--width"),
        (
            &["bench", "presets/checker.ron", "--repeat", "0"],
            "--repeat",
        ),
        (
            &[
                "probe",
                "assets/courtyard_1024x512.hdr",
                "-o",
                o,
                "--size",
                "0",
            ],
            "--size",
        ),
        (&["map", "uv", "0", "0", "0", "--res", "0", "4"], "--res"),
    ];
    for (args, option) in cases {
        let r = texplore(args);
        assert_refused(&r, &["invalid value '", option, "out of range"]);
    }
    assert!(!out.exists());
}

#[test]
fn no_float_option_accepts_nan_or_infinities() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o.png");
    let o = s(&out);
    for bad in ["NaN", "inf", "-inf"] {
        let cases: &[(Vec<&str>, &str)] = &[
            (
                vec!["render", "presets/checker.ron", "-o", o, "--max-aniso", bad],
                "--max-aniso",
            ),
            (
                vec!["render", "presets/checker.ron", "-o", o, "--adaptive"],
                "--adaptive",
            ),
            (
                vec![
                    "report",
                    "presets/checker.ron",
                    "-o",
                    o,
                    "--time-budget",
                    bad,
                ],
                "--time-budget",
            ),
        ];
        for (args, option) in cases {
            let mut args = args.clone();
            let adaptive = format!("16,{bad}");
            if *option == "--adaptive" {
                args.push(&adaptive);
            }
            let r = texplore(&args);
            assert_refused(&r, &["invalid value '", option]);
        }
    }
    let r = texplore(&[
        "render",
        "presets/checker.ron",
        "-o",
        o,
        "--max-aniso",
        "0.5",
    ]);
    assert_refused(&r, &["0.5 is out of range: max_anisotropy is 1 to 64"]);
    assert!(!out.exists());
}

#[test]
fn a_heat_map_spp_that_is_not_rendered_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("report");
    let o = texplore(&[
        "report",
        "presets/checker.ron",
        "--spp",
        "1,4",
        "--heatmap-spp",
        "2",
        "--no-cache",
        "-o",
        s(&out),
    ]);
    assert_refused(&o, &["--heatmap-spp 2 is not among --spp 1,4"]);
    assert!(!out.exists());
}

#[test]
fn render_writes_only_png() {
    let tmp = tempfile::tempdir().unwrap();
    let jpg = tmp.path().join("out.jpg");
    let o = texplore(&["render", "presets/checker.ron", "-o", s(&jpg), "-q"]);
    assert_refused(&o, &["out.jpg"]);
    assert!(!jpg.exists());
}

// ---------------------------------------------------------------------------------------------
// A parser loop without progress.

/// The issue's case (a PLY of a few hundred bytes): an element of 2^64 - 1 items without
/// properties. It used to loop forever; now it loads at once (the items take no bytes).
#[test]
fn a_ply_element_of_no_properties_and_a_huge_count_is_read_at_once() {
    let tmp = tempfile::tempdir().unwrap();
    let ply = tmp.path().join("junk.ply");
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nelement junk 18446744073709551615\nelement face 1\n\
                property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    std::fs::write(&ply, text).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_texplore"))
        .args(["mesh-info", s(&ply)])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t0.elapsed() > Duration::from_secs(30) {
            child.kill().unwrap();
            panic!("mesh-info on a PLY with an empty element of 2^64 - 1 items did not return");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("vertices   3") && out.contains("triangles  1"),
        "{out}"
    );
}

// ---------------------------------------------------------------------------------------------
// The report's reference cache.

/// A folder holding a copy of the soup can (OBJ, MTL, label image) and a preset looking at it
/// through its `map_Kd`.
fn soup_can_scene(dir: &Path) -> PathBuf {
    for f in ["soup-can.obj", "soup-can.mtl", "soup-can-label.png"] {
        std::fs::copy(root().join("assets").join(f), dir.join(f)).unwrap();
    }
    let preset = dir.join("can.ron");
    std::fs::write(
        &preset,
        r#"(
    version: 1,
    camera: (eye: (0, 0.5, 4), look_at: (0, 0, 0), projection: Pinhole(fov: 45)),
    objects: [
        (shape: Mesh(path: "soup-can.obj"), material: Emissive(ce: MeshMaterial(max_anisotropy: 8))),
    ],
)"#,
    )
    .unwrap();
    preset
}

/// The RMSE column of a report's CSV, as written.
fn rmse(out: &Path) -> Vec<String> {
    let csv = std::fs::read_to_string(out.join("report.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "rmse").unwrap();
    lines
        .map(|l| l.split(',').nth(col).unwrap().to_string())
        .collect()
}

fn reference_line(o: &Output) -> String {
    assert!(o.status.success(), "{}", stderr(o));
    stderr(o)
        .lines()
        .find(|l| l.contains("reference"))
        .unwrap_or_default()
        .to_string()
}

/// A change to the files of [`soup_can_scene`]'s folder.
type Edit = dyn Fn(&Path);

#[test]
fn editing_the_mesh_its_mtl_or_its_map_kd_renders_the_reference_again() {
    let tmp = tempfile::tempdir().unwrap();
    let preset = soup_can_scene(tmp.path());
    let cache = tmp.path().join("cache");
    let out = tmp.path().join("out");
    let run = || reference_line(&crate::common::tiny_report(&[&preset], &out, Some(&cache)));
    assert!(run().contains("rendered"));
    assert!(run().contains("from the cache"));
    let edits: [(&str, &Edit); 3] = [
        ("the map_Kd image", &|d: &Path| {
            std::fs::copy(
                root().join("assets/checker_512.png"),
                d.join("soup-can-label.png"),
            )
            .unwrap();
        }),
        ("the .mtl", &|d: &Path| {
            let mtl = std::fs::read_to_string(d.join("soup-can.mtl")).unwrap();
            std::fs::write(
                d.join("soup-can.mtl"),
                mtl.replace("map_Kd soup-can-label.png", "Kd 0.2 0.9 0.3"),
            )
            .unwrap();
        }),
        ("the mesh", &|d: &Path| {
            let obj = std::fs::read_to_string(d.join("soup-can.obj")).unwrap();
            // Every vertex moves up by half a unit.
            let moved: String = obj
                .lines()
                .map(|l| match l.strip_prefix("v ") {
                    Some(rest) => {
                        let v: Vec<f64> = rest
                            .split_whitespace()
                            .map(|x| x.parse().unwrap())
                            .collect();
                        format!("v {} {} {}\n", v[0], v[1] + 0.5, v[2])
                    }
                    None => format!("{l}\n"),
                })
                .collect();
            std::fs::write(d.join("soup-can.obj"), moved).unwrap();
        }),
    ];
    for (what, edit) in edits {
        edit(tmp.path());
        assert!(run().contains("rendered"), "after editing {what}");
        // The numbers are those of a reference rendered from the edited files.
        let cached = rmse(&out);
        let fresh_out = tmp.path().join("fresh");
        assert!(
            crate::common::tiny_report(&[&preset], &fresh_out, None)
                .status
                .success()
        );
        assert_eq!(cached, rmse(&fresh_out), "after editing {what}");
        assert!(run().contains("from the cache"), "after editing {what}");
    }
}

#[test]
fn a_bit_flipped_cached_reference_is_rendered_again_and_said_so() {
    let tmp = tempfile::tempdir().unwrap();
    let cache = tmp.path().join("cache");
    let out = tmp.path().join("out");
    let preset = root().join("presets/checker.ron");
    assert!(
        reference_line(&crate::common::tiny_report(&[&preset], &out, Some(&cache)))
            .contains("rendered")
    );
    let good = rmse(&out);
    let exr = std::fs::read_dir(&cache)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "exr"))
        .unwrap();
    let mut bytes = std::fs::read(&exr).unwrap();
    let at = bytes.len() - 8;
    bytes[at] ^= 0x04;
    std::fs::write(&exr, &bytes).unwrap();
    let line = reference_line(&crate::common::tiny_report(&[&preset], &out, Some(&cache)));
    assert!(
        line.contains("rendered") && line.contains("checksum mismatch") && line.contains(s(&exr)),
        "{line}"
    );
    assert_eq!(rmse(&out), good);
    // Stored again whole: the next report uses it.
    assert!(
        reference_line(&crate::common::tiny_report(&[&preset], &out, Some(&cache)))
            .contains("from the cache")
    );
}

/// Two reports sharing `--cache`, started together, both succeed with the same numbers
/// (three rounds, each on an empty cache, so both render and store the same reference).
#[test]
fn two_reports_sharing_a_cache_both_succeed() {
    let tmp = tempfile::tempdir().unwrap();
    let preset = root().join("presets/checker.ron");
    for round in 0..3 {
        let cache = tmp.path().join(format!("cache{round}"));
        let outs = [
            tmp.path().join(format!("a{round}")),
            tmp.path().join(format!("b{round}")),
        ];
        let (a, b) = std::thread::scope(|scope| {
            let a = scope.spawn(|| crate::common::tiny_report(&[&preset], &outs[0], Some(&cache)));
            let b = scope.spawn(|| crate::common::tiny_report(&[&preset], &outs[1], Some(&cache)));
            (a.join().unwrap(), b.join().unwrap())
        });
        assert!(a.status.success(), "round {round}: {}", stderr(&a));
        assert!(b.status.success(), "round {round}: {}", stderr(&b));
        assert_eq!(rmse(&outs[0]), rmse(&outs[1]));
    }
}

#[test]
fn two_presets_with_one_file_stem_keep_their_own_plots() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    let checker = std::fs::read_to_string(root().join("presets/checker.ron")).unwrap();
    let checker = checker.replace("../assets/", s(&root().join("assets/")));
    std::fs::write(a.join("scene.ron"), &checker).unwrap();
    // The second scene is the first with a brighter ambient light: different numbers.
    let brighter = checker.replacen("ambient: (ls: 0.4)", "ambient: (ls: 3)", 1);
    assert_ne!(brighter, checker);
    std::fs::write(b.join("scene.ron"), brighter).unwrap();
    let out = tmp.path().join("out");
    let o = crate::common::tiny_report(&[&a.join("scene.ron"), &b.join("scene.ron")], &out, None);
    assert!(o.status.success(), "{}", stderr(&o));
    for name in ["a-scene", "b-scene"] {
        for f in ["error_vs_time.svg", "error_vs_time.png"] {
            assert!(out.join(name).join(f).is_file(), "{name}/{f}");
        }
    }
    assert!(!out.join("scene").exists());
    let csv = std::fs::read_to_string(out.join("report.csv")).unwrap();
    assert!(
        csv.contains("\na-scene,") && csv.contains("\nb-scene,"),
        "{csv}"
    );
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("a-scene/error_vs_time.svg") && md.contains("b-scene/error_vs_time.svg"));
}

// ---------------------------------------------------------------------------------------------
// Reads that bypassed crate::input.

#[cfg(unix)]
#[test]
fn a_golden_image_that_is_not_a_file_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    let presets = tmp.path().join("presets");
    let shots = tmp.path().join("shots");
    std::fs::create_dir_all(&presets).unwrap();
    std::fs::create_dir_all(shots.join("checker.png")).unwrap();
    let checker = std::fs::read_to_string(root().join("presets/checker.ron")).unwrap();
    std::fs::write(
        presets.join("checker.ron"),
        checker.replace("../assets/", s(&root().join("assets/"))),
    )
    .unwrap();
    let o = texplore(&[
        "snapshot",
        "check",
        "--presets",
        s(&presets),
        "--screenshots",
        s(&shots),
    ]);
    assert_refused(&o, &["checker.png", "not a regular file (a directory)"]);
}

// ---------------------------------------------------------------------------------------------
// Every float of the format, found by walking a description through serde (not a hand-kept
// list): each set to infinity through the lesson path machinery is refused naming its field.

/// A description with every part that holds numbers: each material kind with every parameter
/// textured or set, each texture kind, (u, v) transforms, clip, bump, normal and displacement
/// maps.
const EVERYTHING: &str = r#"(
    version: 1,
    camera: (eye: (0, 1, 4), look_at: (0, 0.5, 0), up: (0, 1, 0), projection: Pinhole(fov: 50)),
    render: (width: 8, height: 6, spp: 1, exposure: 0.5, background: (0, 0.1, 0),
             adaptive: Some((max_spp: 4, threshold: 0.01))),
    ambient: (ls: 1, color: (1, 0.9, 1)),
    lights: [
        Directional(direction: (1, 1, 1), ls: 1, color: (1, 1, 0.9)),
        Point(position: (0, 4, 0), ls: 1, color: (0.9, 1, 1)),
    ],
    objects: [
        (shape: Sphere,
         transform: (translate: (0.5, 0, 0), rotate: (0, 10, 0), scale: (1, 1, 1.5)),
         material: Phong(ka: 0.25, kd: 0.75,
             ks: (texture: Image(path: "../assets/coffee_600x400.png", scale: 0.5), channel: Green),
             cs: (1, 0.9, 1), exp: 20, ce: (0.1, 0.2, 0.3),
             cd: Checker(squares: (8, 8), colors: ((0.8, 0.8, 0.8), (0.1, 0.1, 0.1)),
                 uv: (scale: (2, 3), rotate: 10, offset: (0.25, 0.5)))),
         alpha: (texture: Image(path: "../assets/coffee_600x400.png", scale: 0.9), channel: Red),
         bump: (height: Image(path: "../assets/gravel_gray_512.png", mapping: Spherical, scale: 0.8), scale: 0.02)),
        (shape: Plane, material: Matte(ka: 0.25, kd: 0.75, cd: Constant((0.5, 0.4, 0.5))),
         normal: (map: Image(path: "../assets/coffee_600x400.png", mapping: Rectangular, scale: 0.7), strength: 0.9)),
        (shape: Disk, material: Emissive(ls: 1.5, ce: UvGrid(max_anisotropy: 8, uv: (rotate: 5)))),
        (shape: Rectangle, material: Reflective(ka: 0.1, kd: 0.5, kr: 0.8,
             cd: Image(path: "../assets/coffee_600x400.png", scale: 0.9, max_anisotropy: 8),
             cr: (0.9, 0.8, 0.7))),
        (shape: Mesh(path: "../assets/torus-knot.ply"),
         material: Matte(cd: MeshMaterial(max_anisotropy: 8)),
         displace: (height: Image(path: "../assets/gravel_gray_512.png", mapping: Uv, scale: 0.9), scale: 0.15, subdivide: 1)),
    ],
)"#;

/// Every float leaf of a JSON tree: its path as the lesson dialect spells it, and the field an
/// error names (the path without enum variants and without indices into a number's
/// components).
fn float_leaves(v: &serde_json::Value, lesson: &str, field: &str, out: &mut Vec<(String, String)>) {
    use serde_json::Value;
    match v {
        Value::Number(n) if n.is_f64() => out.push((lesson.to_string(), field.to_string())),
        Value::Array(items) => {
            let numbers = items.iter().all(|i| i.is_number() || i.is_array());
            for (k, i) in items.iter().enumerate() {
                let l = format!("{lesson}[{k}]");
                let f = if numbers {
                    field.to_string()
                } else {
                    format!("{field}[{k}]")
                };
                float_leaves(i, &l, &f, out);
            }
        }
        Value::Object(map) => {
            for (key, i) in map {
                // An enum variant (`Phong`, `Checker`, `Pinhole`): paths step into it unnamed.
                if key.starts_with(|c: char| c.is_ascii_uppercase()) {
                    float_leaves(i, lesson, field, out);
                } else {
                    let join = |p: &str| {
                        if p.is_empty() {
                            key.clone()
                        } else {
                            format!("{p}.{key}")
                        }
                    };
                    float_leaves(i, &join(lesson), &join(field), out);
                }
            }
        }
        _ => {}
    }
}

#[test]
fn every_float_of_the_format_refuses_infinity_naming_its_field() {
    use texplore::lesson::edit::set_path;
    let preset = root().join("presets/everything.ron");
    let desc = texplore::scene::parse_preset(EVERYTHING, &preset).expect("the template parses");
    let tree = serde_json::to_value(&desc).unwrap();
    let mut leaves = Vec::new();
    float_leaves(&tree, "", "", &mut leaves);
    // The walk reaches the fields the hand-kept list above never had.
    for must in [
        "objects[0].material.ce",
        "objects[0].material.cd.uv.offset",
        "objects[0].bump.scale",
        "objects[1].normal.strength",
        "objects[3].material.kr",
        "objects[3].material.cr",
        "objects[4].displace.scale",
    ] {
        assert!(
            leaves.iter().any(|(_, f)| f == must),
            "{must} not among {leaves:?}"
        );
    }
    let mut failures = Vec::new();
    for (path, field) in &leaves {
        // The edit checks the numbers of the scene it makes, as loading a preset does.
        let refused = match set_path(&desc, path, "inf") {
            Ok(d) => texplore::scene::check_numbers(&d).map_err(|r| d.refusal_message(&r)),
            Err(e) => Err(e),
        };
        // The field as every message names it (with the object's name, if it has one).
        let named = desc.name_field(&texplore::field::FieldPath::parse(field).unwrap());
        match refused {
            Err(e) if e.contains(&format!("{named}: inf is not finite")) => {}
            Err(e) => failures.push(format!("{path}: refused without naming {field}: {e}")),
            Ok(()) => failures.push(format!("{path}: inf accepted")),
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} fields:\n{}",
        failures.len(),
        leaves.len(),
        failures.join("\n")
    );
}
