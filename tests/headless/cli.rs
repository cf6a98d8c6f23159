//! The command line as a user runs it.

use crate::common::{failure, success, texplore, texplore_json as json};

#[test]
fn map_prints_the_lecture_values_as_json() {
    let v = json(&[
        "map",
        "spherical",
        "1",
        "0",
        "0",
        "--json",
        "--res",
        "100",
        "50",
    ]);
    assert!((v["u"].as_f64().unwrap() - 0.25).abs() < 1e-6);
    assert!((v["v"].as_f64().unwrap() - 0.5).abs() < 1e-6);
    assert_eq!(v["column"], 25);
    assert_eq!(v["row"], 25);
    // The lecture's lookup: (int)(99 * 0.25) = 24.
    let v = json(&[
        "map",
        "spherical",
        "1",
        "0",
        "0",
        "--json",
        "--res",
        "100",
        "50",
        "--lookup",
        "lecture",
    ]);
    assert_eq!(v["column"], 24);
    assert_eq!(v["row"], 24);
    // Negative coordinates and the probe's axis.
    let v = json(&["map", "light-probe", "0", "0", "-1", "--json"]);
    assert!((v["u"].as_f64().unwrap() - 1.0).abs() < 1e-6);
    let v = json(&["map", "panoramic", "0", "0", "-1", "--json"]);
    assert!((v["u"].as_f64().unwrap() - 0.5).abs() < 1e-6);
}

#[test]
fn map_explains_the_formula() {
    let text = success(&texplore(&["map", "cylindrical", "-1", "0.5", "0"]));
    assert!(
        text.contains("phi = atan2(x, z)")
            && text.contains("phi += 2 pi")
            && text.contains("u = phi / (2 pi) = 0.7500"),
        "{text}"
    );
}

#[test]
fn render_writes_a_png_with_the_preset_inside() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("e.png");
    success(&texplore(&[
        "render",
        "presets/earth.ron",
        "-o",
        out_png.to_str().unwrap(),
        "--width",
        "40",
        "--height",
        "30",
        "--spp",
        "1",
        "-q",
    ]));
    let img = image::open(&out_png).unwrap();
    assert_eq!((img.width(), img.height()), (40, 30));
    // Rendering the PNG renders the preset embedded in it, with the overrides it was saved with.
    let again = dir.path().join("again.png");
    success(&texplore(&[
        "render",
        out_png.to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
        "-q",
    ]));
    assert_eq!(image::open(&again).unwrap().to_rgb8(), img.to_rgb8());
}

#[test]
fn errors_are_one_line_naming_the_file() {
    let err = failure(&texplore(&[
        "render",
        "presets/does-not-exist.ron",
        "-o",
        "/tmp/x.png",
    ]));
    assert!(
        err.starts_with("error: presets/does-not-exist.ron"),
        "{err}"
    );
    let err = failure(&texplore(&["map", "sphere", "0", "0", "1"]));
    assert!(err.contains("spherical"), "{err}");
}

#[test]
fn probe_writes_an_hdr_probe() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("p.hdr");
    success(&texplore(&[
        "probe",
        "assets/courtyard_1024x512.hdr",
        "-o",
        p.to_str().unwrap(),
        "--size",
        "64",
    ]));
    let img = texplore::texture::load_image(&p, true).unwrap();
    assert_eq!((img.width(), img.height()), (64, 64));
    // Outside the disc is black; the centre is not.
    assert_eq!(img.texel_top(0, 0), texplore::math::Rgb::BLACK);
    assert!(img.texel_top(32, 32).max_channel() > 0.0);
}

/// The kernel line `bench` prints for the Earth with `args` after `bench`, and `TEXPLORE_SIMD` set
/// to `env` (unset with `None`).
fn bench_path(args: &[&str], env: Option<&str>) -> String {
    let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_texplore"));
    cmd.current_dir(crate::common::root())
        .args([
            "bench",
            "presets/earth.ron",
            "--width",
            "16",
            "--height",
            "12",
        ])
        .args(["--repeat", "1", "--threads", "1"])
        .args(args)
        .env_remove("TEXPLORE_SIMD");
    if let Some(v) = env {
        cmd.env("TEXPLORE_SIMD", v);
    }
    let out = success(&cmd.output().expect("run texplore"));
    out.lines()
        .find(|l| l.starts_with("kernel: "))
        .unwrap_or_else(|| panic!("no kernel line in {out}"))
        .to_owned()
}

#[test]
fn the_simd_path_is_chosen_by_the_option_or_the_environment() {
    let auto = bench_path(&[], None);
    let width = texplore::render::kernel_width(texplore::render::SimdMode::Auto);
    assert!(auto.ends_with(&format!("{width} rays a packet")), "{auto}");
    for (args, env) in [
        (&["--simd", "scalar"][..], None),
        (&[][..], Some("off")),
        (&[][..], Some("scalar")),
    ] {
        assert!(
            bench_path(args, env).ends_with("1 ray a packet (asked for)"),
            "{args:?} {env:?}"
        );
    }
    // The option wins over the environment.
    assert_eq!(bench_path(&["--simd", "auto"], Some("off")), auto);
    let e = failure(&texplore(&["bench", "--simd", "fast", "presets/earth.ron"]));
    assert!(
        e.contains("`fast` is not a path: use auto or scalar"),
        "{e}"
    );
}
