//! The reference cache under attack (issue 26, part 3): its file names are predictable hashes,
//! so a link planted in a shared `--cache` must never make `texplore report` write through it or
//! read through it, a damaged entry costs a render and never the report, and the report's own
//! names cannot clash with a scene's folder.
#![cfg(unix)]

use std::os::unix::fs::symlink;
use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::root;

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// [`crate::common::tiny_report`] of one preset, cached in `cache`.
fn report(preset: &Path, out: &Path, cache: &Path) -> Output {
    crate::common::tiny_report(&[preset], out, Some(cache))
}

fn earth() -> PathBuf {
    root().join("presets/earth.ron")
}

/// The RMSE cells of a report's CSV.
fn rmse(out: &Path) -> Vec<String> {
    let csv = std::fs::read_to_string(out.join("report.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "rmse").unwrap();
    lines
        .map(|l| l.split(',').nth(col).unwrap().to_string())
        .collect()
}

/// The cache's two files for the Earth at this size: (EXR, key), after one run fills it.
fn cache_names(tmp: &Path) -> (PathBuf, PathBuf, Vec<String>) {
    let cache = tmp.join("warm-cache");
    let o = report(&earth(), &tmp.join("warm"), &cache);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut exr = None;
    let mut key = None;
    for e in std::fs::read_dir(&cache).unwrap() {
        let name = e.unwrap().file_name().into_string().unwrap();
        if name.ends_with(".key.txt") {
            key = Some(name);
        } else if Path::new(&name)
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("exr"))
        {
            exr = Some(name);
        }
    }
    (
        PathBuf::from(exr.expect("an EXR in the cache")),
        PathBuf::from(key.expect("a key in the cache")),
        rmse(&tmp.join("warm")),
    )
}

#[test]
fn links_planted_at_the_cache_names_are_neither_written_nor_read_through() {
    let tmp = tempfile::tempdir().unwrap();
    let (exr, key, expected) = cache_names(tmp.path());
    // A user's files, and a cache holding links to them under the names the next run uses.
    let mine = tmp.path().join("mine");
    std::fs::create_dir(&mine).unwrap();
    let (thesis, photo) = (mine.join("thesis.txt"), mine.join("photo.exr"));
    std::fs::write(&thesis, "chapter one").unwrap();
    std::fs::write(&photo, "not really an exr").unwrap();
    let cache = tmp.path().join("shared-cache");
    std::fs::create_dir(&cache).unwrap();
    symlink(&photo, cache.join(&exr)).unwrap();
    symlink(&thesis, cache.join(&key)).unwrap();

    let out = tmp.path().join("out");
    let o = report(&earth(), &out, &cache);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&thesis).unwrap(), "chapter one");
    assert_eq!(
        std::fs::read_to_string(&photo).unwrap(),
        "not really an exr"
    );
    // The links were replaced by the cache's own regular files, and the numbers are right.
    for name in [&exr, &key] {
        let m = std::fs::symlink_metadata(cache.join(name)).unwrap();
        assert!(m.file_type().is_file(), "{} is {m:?}", name.display());
    }
    assert_eq!(rmse(&out), expected);

    // A link to a device that never ends is refused, not read, and replaced.
    std::fs::remove_file(cache.join(&exr)).unwrap();
    std::fs::remove_file(cache.join(&key)).unwrap();
    symlink("/dev/zero", cache.join(&exr)).unwrap();
    std::fs::copy(tmp.path().join("warm-cache").join(&key), cache.join(&key)).unwrap();
    let o = report(&earth(), &tmp.path().join("out2"), &cache);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("symbolic link"),
        "the refused entry is named: {}",
        stderr(&o)
    );
    assert!(
        std::fs::symlink_metadata(cache.join(&exr))
            .unwrap()
            .is_file()
    );
    assert_eq!(rmse(&tmp.path().join("out2")), expected);
}

#[test]
fn a_cached_reference_of_nan_with_a_matching_checksum_is_rendered_again() {
    let tmp = tempfile::tempdir().unwrap();
    let (exr, key, expected) = cache_names(tmp.path());
    let cache = tmp.path().join("warm-cache");
    // The same size, every value NaN, and a key file whose checksum matches it.
    let nan = image::Rgb32FImage::from_pixel(16, 12, image::Rgb([f32::NAN; 3]));
    let mut bytes = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb32F(nan)
        .write_to(&mut bytes, image::ImageFormat::OpenExr)
        .unwrap();
    let bytes = bytes.into_inner();
    std::fs::write(cache.join(&exr), &bytes).unwrap();
    let text = std::fs::read_to_string(cache.join(&key)).unwrap();
    let body = text.trim_end().rsplit_once('\n').unwrap().0;
    let checksum = texplore::report::reference::fnv1a64(&bytes);
    std::fs::write(
        cache.join(&key),
        format!("{body}\nexr {} {checksum:016x}\n", bytes.len()),
    )
    .unwrap();

    let out = tmp.path().join("out");
    let o = report(&earth(), &out, &cache);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(rmse(&out), expected, "{}", stderr(&o));
    assert!(
        stderr(&o).contains("not a radiance"),
        "says why: {}",
        stderr(&o)
    );
}

#[test]
fn a_damaged_entry_costs_a_render_not_the_report() {
    let tmp = tempfile::tempdir().unwrap();
    let (exr, key, expected) = cache_names(tmp.path());
    for (i, make) in [
        // A folder where the EXR goes: it cannot be replaced, so the report goes on unstored.
        (|p: &Path| std::fs::create_dir(p).unwrap()) as fn(&Path),
        // A FIFO: never waited on, replaced by the new file.
        |p: &Path| {
            let c = std::ffi::CString::new(p.to_str().unwrap()).unwrap();
            #[allow(unsafe_code)]
            // SAFETY: mkfifo reads a valid NUL-terminated path.
            let r = unsafe { libc::mkfifo(c.as_ptr(), 0o644) };
            assert_eq!(r, 0);
        },
    ]
    .into_iter()
    .enumerate()
    {
        let cache = tmp.path().join(format!("cache-{i}"));
        std::fs::create_dir(&cache).unwrap();
        std::fs::copy(tmp.path().join("warm-cache").join(&key), cache.join(&key)).unwrap();
        make(&cache.join(&exr));
        let out = tmp.path().join(format!("out-{i}"));
        let o = report(&earth(), &out, &cache);
        assert!(o.status.success(), "case {i}: {}", stderr(&o));
        assert_eq!(rmse(&out), expected, "case {i}");
        if i == 0 {
            assert!(
                stderr(&o).contains("not stored"),
                "the report says the cache could not keep it: {}",
                stderr(&o)
            );
        }
    }
}

#[test]
fn a_cache_that_is_a_file_is_refused_before_any_work() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("notes.txt");
    std::fs::write(&file, "keep me").unwrap();
    let t = std::time::Instant::now();
    let o = report(&earth(), &tmp.path().join("out"), &file);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("notes.txt") && e.contains("not a folder"), "{e}");
    assert!(t.elapsed().as_secs_f64() < 5.0, "refused before rendering");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep me");
    assert!(!tmp.path().join("out").exists(), "nothing was written");
}

#[test]
fn a_preset_named_like_the_reports_files_gets_its_own_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let preset = tmp.path().join("report.csv.ron");
    let text = std::fs::read_to_string(earth())
        .unwrap()
        .replace("../assets/", &format!("{}/assets/", root().display()));
    std::fs::write(&preset, text).unwrap();
    let out = tmp.path().join("out");
    let o = report(&preset, &out, &tmp.path().join("cache"));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("report.csv").is_file());
    assert!(out.join("scene-report.csv").is_dir());
}
