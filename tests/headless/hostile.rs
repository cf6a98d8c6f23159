//! Hostile outputs: what `-o` may name, and what texplore does with it. Every test drives the
//! real binary and looks at the files afterwards. Renders are 16x12 at 1 spp.
//!
//! No test writes to a device: refusals of non-regular files are shown on FIFOs and folders.

#![cfg(unix)]

use std::os::unix::fs::PermissionsExt;
use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn texplore(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `texplore render presets/checker.ron -o OUT` at 16x12, 1 spp (or another preset).
fn render(preset: &str, out: &Path) -> Output {
    texplore(&[
        "render",
        preset,
        "-o",
        s(out),
        "--width",
        "16",
        "--height",
        "12",
        "--spp",
        "1",
        "-q",
    ])
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn assert_ok(o: &Output) {
    assert!(o.status.success(), "{}", stderr(o));
}

/// Asserts a failure whose message is "cannot write OUT: ..." containing `reason`.
fn assert_refused(o: &Output, out: &Path, reason: &str) {
    assert!(!o.status.success(), "should have failed: {}", out.display());
    let e = stderr(o);
    assert!(
        e.contains(&format!("cannot write {}: ", out.display())) && e.contains(reason),
        "expected 'cannot write {}: ...{reason}...', got: {e}",
        out.display()
    );
    assert!(!e.contains("cannot load image"), "{e}");
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn mkfifo(path: &Path) {
    let st = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(st.success());
}

fn is_fifo(path: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::symlink_metadata(path)
        .unwrap()
        .file_type()
        .is_fifo()
}

/// A complete PNG: decodes, and nothing follows the IEND chunk.
fn assert_complete_png(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    let iend = [0, 0, 0, 0, b'I', b'E', b'N', b'D', 0xAE, 0x42, 0x60, 0x82];
    assert!(
        bytes.ends_with(&iend),
        "{}: bytes after IEND or no IEND",
        path.display()
    );
    let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png).unwrap();
    (img.width(), img.height())
}

#[test]
fn a_fifo_or_a_folder_as_output_is_refused_and_nothing_is_left() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("out.png");
    mkfifo(&fifo);
    let o = render("presets/checker.ron", &fifo);
    assert_refused(&o, &fifo, "it is a FIFO, not a regular file");
    assert!(is_fifo(&fifo), "the FIFO was replaced");
    // A symbolic link to the FIFO: followed, and the FIFO is still refused.
    let link = dir.path().join("link.png");
    std::os::unix::fs::symlink(&fifo, &link).unwrap();
    let o = render("presets/checker.ron", &link);
    assert_refused(&o, &link, "a symbolic link to a FIFO");
    assert!(is_fifo(&fifo));
    // A folder.
    let folder = dir.path().join("folder");
    std::fs::create_dir(&folder).unwrap();
    let o = render("presets/checker.ron", &folder);
    assert_refused(&o, &folder, "it is a directory, not a regular file");
    assert!(names(&folder).is_empty());
    // No temporary file anywhere.
    assert_eq!(names(dir.path()), ["folder", "link.png", "out.png"]);
    // A folder that does not exist.
    let missing = dir.path().join("nope").join("out.png");
    let o = render("presets/checker.ron", &missing);
    assert_refused(&o, &missing, "does not exist");
}

#[test]
fn a_symlink_is_followed_like_cp() {
    let dir = tempfile::tempdir().unwrap();
    let real = dir.path().join("real.png");
    std::fs::write(&real, "old").unwrap();
    let link = dir.path().join("link.png");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    assert_ok(&render("presets/checker.ron", &link));
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink(),
        "the link was replaced by a file"
    );
    assert_eq!(std::fs::read_link(&link).unwrap(), real);
    assert_eq!(assert_complete_png(&real), (16, 12));
    // A link to nowhere is not written through.
    let dangling = dir.path().join("dangling.png");
    std::os::unix::fs::symlink(dir.path().join("absent.png"), &dangling).unwrap();
    let o = render("presets/checker.ron", &dangling);
    assert_refused(&o, &dangling, "does not exist");
    assert!(!dir.path().join("absent.png").exists());
}

#[test]
fn an_output_that_is_an_input_by_another_spelling_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("shot.png");
    assert_ok(&render("presets/checker.ron", &shot));
    let before = std::fs::read(&shot).unwrap();
    // Rendering the PNG (its preset inside) over itself, spelled otherwise.
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    let other = dir.path().join("sub").join("..").join("shot.png");
    let o = render(s(&shot), &other);
    assert_refused(&o, &other, "it is the input");
    // ... or through a hard link.
    let hard = dir.path().join("hard.png");
    std::fs::hard_link(&shot, &hard).unwrap();
    let o = render(s(&shot), &hard);
    assert_refused(&o, &hard, "it is the input");
    assert_eq!(std::fs::read(&shot).unwrap(), before);
    // An asset of the preset is an input too.
    let tex = dir.path().join("tex.png");
    image::RgbImage::from_pixel(4, 4, image::Rgb([200, 30, 30]))
        .save(&tex)
        .unwrap();
    let preset = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/rectangle.ron"),
    )
    .unwrap()
    .replace("../assets/coffee_600x400.png", "tex.png");
    let scene = dir.path().join("scene.ron");
    std::fs::write(&scene, preset).unwrap();
    let tex_before = std::fs::read(&tex).unwrap();
    let other_tex = dir.path().join(".").join("tex.png");
    let o = render(s(&scene), &other_tex);
    assert_refused(&o, &other_tex, "it is the input");
    assert_eq!(std::fs::read(&tex).unwrap(), tex_before);
    // A preset saved (the window's Save as) over its own texture.
    let desc = texplore::scene::load_preset(&scene).unwrap();
    let e = texplore::scene::save_preset(&desc, &other_tex)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with(&format!(
            "cannot write {}: it is the input",
            other_tex.display()
        )),
        "{e}"
    );
    assert_eq!(std::fs::read(&tex).unwrap(), tex_before);
    // The probe's panorama.
    let pano = dir.path().join("pano.hdr");
    image::DynamicImage::ImageRgb32F(image::Rgb32FImage::from_pixel(
        8,
        4,
        image::Rgb([0.5, 1.5, 4.0]),
    ))
    .save(&pano)
    .unwrap();
    let pano_before = std::fs::read(&pano).unwrap();
    let spelled = dir.path().join("sub/../pano.hdr");
    let o = texplore(&["probe", s(&pano), "-o", s(&spelled), "--size", "8"]);
    assert_refused(&o, &spelled, "it is the input");
    assert_eq!(std::fs::read(&pano).unwrap(), pano_before);
}

#[test]
fn the_users_files_beside_the_output_survive() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    // The old fixed temporary name belongs to the user here.
    let mine = dir.path().join("out.png.tmp");
    std::fs::write(&mine, "mine").unwrap();
    // And a symbolic link at the probe's old temporary name points at a victim.
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "victim").unwrap();
    std::os::unix::fs::symlink(&victim, dir.path().join("out.tmp.png")).unwrap();
    assert_ok(&render("presets/checker.ron", &out));
    assert_eq!(assert_complete_png(&out), (16, 12));
    assert_eq!(std::fs::read_to_string(&mine).unwrap(), "mine");
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "victim");
    assert_eq!(
        names(dir.path()),
        ["out.png", "out.png.tmp", "out.tmp.png", "victim.txt"]
    );
}

#[test]
fn an_overwritten_output_keeps_its_mode_and_a_read_only_one_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    std::fs::write(&out, "old").unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o640)).unwrap();
    assert_ok(&render("presets/checker.ron", &out));
    assert_eq!(assert_complete_png(&out), (16, 12));
    let mode = std::fs::metadata(&out).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o640, "mode {mode:o}");
    // Read-only: refused (even for root), the file untouched.
    let ro = dir.path().join("ro.png");
    std::fs::write(&ro, "keep me").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o444)).unwrap();
    let o = render("presets/checker.ron", &ro);
    assert_refused(&o, &ro, "permission denied");
    assert_eq!(std::fs::read_to_string(&ro).unwrap(), "keep me");
    assert_eq!(names(dir.path()), ["out.png", "ro.png"]);
}

#[test]
fn concurrent_renders_to_one_output_leave_one_complete_png() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let spawn = |w: &str, h: &str| {
        Command::new(env!("CARGO_BIN_EXE_texplore"))
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args(["render", "presets/checker.ron", "-o", s(&out)])
            .args([
                "--width",
                w,
                "--height",
                h,
                "--spp",
                "1",
                "-q",
                "--threads",
                "1",
            ])
            .spawn()
            .unwrap()
    };
    for _ in 0..4 {
        let mut a = spawn("16", "12");
        let mut b = spawn("24", "18");
        assert!(a.wait().unwrap().success());
        assert!(b.wait().unwrap().success());
        let size = assert_complete_png(&out);
        assert!(size == (16, 12) || size == (24, 18), "{size:?}");
        assert_eq!(names(dir.path()), ["out.png"]);
    }
}

#[test]
fn the_extension_is_checked_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    // A 4096x4096 probe of the 1024x512 courtyard takes 11 s in a debug build; the refusal
    // takes milliseconds.
    let noext = dir.path().join("noext");
    let t0 = Instant::now();
    let o = texplore(&[
        "probe",
        "assets/courtyard_1024x512.hdr",
        "-o",
        s(&noext),
        "--size",
        "4096",
    ]);
    let dt = t0.elapsed();
    assert_refused(&o, &noext, "no extension (use .hdr, .exr, .png");
    assert!(dt < Duration::from_secs(1), "took {dt:?}");
    // A render is a PNG (its preset travels in a PNG text chunk) or the linear EXR / HDR:
    // .jpg is refused, not written as a PNG under a JPEG name.
    let jpg = dir.path().join("out.jpg");
    let o = render("presets/checker.ron", &jpg);
    assert_refused(&o, &jpg, "unknown extension '.jpg' (use .png, .exr, .hdr)");
    assert!(names(dir.path()).is_empty());
    // A probe writes the format its extension names.
    let probe_jpg = dir.path().join("probe.jpg");
    let o = texplore(&[
        "probe",
        "assets/courtyard_1024x512.hdr",
        "-o",
        s(&probe_jpg),
        "--size",
        "16",
    ]);
    assert_ok(&o);
    let bytes = std::fs::read(&probe_jpg).unwrap();
    assert_eq!(&bytes[..3], &[0xFF, 0xD8, 0xFF], "not a JPEG");
    assert_eq!(
        image::guess_format(&bytes).unwrap(),
        image::ImageFormat::Jpeg
    );
    let img = image::load_from_memory(&bytes).unwrap();
    assert_eq!((img.width(), img.height()), (16, 16));
    assert_eq!(names(dir.path()), ["probe.jpg"]);
}

#[test]
fn report_refuses_a_file_as_its_folder_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("report");
    std::fs::write(&file, "mine").unwrap();
    let t0 = Instant::now();
    let o = texplore(&[
        "report",
        "presets/checker.ron",
        "-o",
        s(&file),
        "--no-cache",
        "-q",
    ]);
    assert!(t0.elapsed() < Duration::from_secs(1));
    assert_refused(&o, &file, "it is a file, not a folder");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    // report.csv taken by a FIFO in the folder: refused before the renders.
    let folder = dir.path().join("out");
    std::fs::create_dir(&folder).unwrap();
    let csv = folder.join("report.csv");
    mkfifo(&csv);
    let o = texplore(&[
        "report",
        "presets/checker.ron",
        "-o",
        s(&folder),
        "--no-cache",
        "-q",
    ]);
    assert_refused(&o, &csv, "it is a FIFO");
    assert!(is_fifo(&csv));
}
