//! The window's memory file (eframe's `app.ron`) as a hostile user leaves it: a FIFO, a link
//! to `/dev/zero` or to one of the user's files, a UI zoom of 0, NaN or 1e30, a window size of
//! 1e30. Checked before eframe reads it: moved aside or repaired, never hanging, never
//! panicking, never writing through a link (issue 26).

use std::collections::HashMap;
use std::path::Path;
use std::time::{Duration, Instant};
use texplore::gui::{Guarded, guard_storage};

/// Writes eframe's key-value file at `path`.
fn write_kv(path: &Path, kv: &HashMap<String, String>) {
    std::fs::write(path, ron::to_string(kv).expect("ron")).expect("write app.ron");
}

fn read_kv(path: &Path) -> HashMap<String, String> {
    ron::from_str(&std::fs::read_to_string(path).expect("read app.ron")).expect("eframe's format")
}

/// egui's memory with the UI zoom at `zoom`.
fn memory_with_zoom(zoom: f32) -> String {
    let mut m = egui::Memory::default();
    m.options.zoom_factor = zoom;
    ron::to_string(&m).expect("ron")
}

#[test]
fn a_remembered_zoom_of_zero_nan_or_1e30_is_set_back_to_one_and_the_rest_kept() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("app.ron");
    for zoom in [0.0, f32::NAN, 1e30, -1.0, f32::INFINITY] {
        let prefs = "(last_scene: None, camera_is_unsaved: true, ui_scale: 1.5)".to_owned();
        let kv = HashMap::from([
            ("egui".to_owned(), memory_with_zoom(zoom)),
            ("texplore-prefs".to_owned(), prefs.clone()),
        ]);
        write_kv(&path, &kv);
        match guard_storage(&path).expect("guarded") {
            Guarded::Repaired(notes) => assert!(notes[0].contains("zoom"), "{notes:?}"),
            other => panic!("zoom {zoom}: {other:?}"),
        }
        let kv = read_kv(&path);
        let m: egui::Memory = ron::from_str(&kv["egui"]).expect("egui's memory");
        assert_eq!(m.options.zoom_factor, 1.0, "zoom {zoom}");
        assert_eq!(kv["texplore-prefs"], prefs, "texplore's own entry is kept");
        assert_eq!(guard_storage(&path).expect("guarded"), Guarded::Fine);
    }
}

#[test]
fn an_absurd_window_geometry_is_forgotten_and_a_sane_file_left_byte_for_byte() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("app.ron");
    let sane = "(normal_geometry: (inner_size: Some((1440.0, 900.0)), outer_position: Some((10.0, 20.0))), fullscreen: false, maximized: false)";
    let kv = HashMap::from([
        ("window".to_owned(), sane.to_owned()),
        ("egui".to_owned(), memory_with_zoom(1.2)),
    ]);
    write_kv(&path, &kv);
    let before = std::fs::read(&path).expect("read");
    assert_eq!(guard_storage(&path).expect("guarded"), Guarded::Fine);
    assert_eq!(std::fs::read(&path).expect("read"), before, "untouched");

    for bad in ["1e30", "NaN", "inf"] {
        let window = sane.replace("1440.0", bad);
        write_kv(
            &path,
            &HashMap::from([("window".to_owned(), window.clone())]),
        );
        assert!(
            matches!(guard_storage(&path), Ok(Guarded::Repaired(_))),
            "{window}"
        );
        assert!(!read_kv(&path).contains_key("window"), "{window}");
    }
}

/// The entries of `dir` whose name starts with `app.ron.refused-`.
fn refused(dir: &Path) -> Vec<std::path::PathBuf> {
    std::fs::read_dir(dir)
        .expect("list")
        .map(|e| e.expect("entry").path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("app.ron.refused-"))
        })
        .collect()
}

#[cfg(unix)]
#[test]
fn a_fifo_a_link_or_garbage_is_moved_aside_without_reading_through_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("app.ron");
    // A link to one of the user's files: renamed, the file itself untouched.
    let users = dir.path().join("thesis.txt");
    std::fs::write(&users, "my thesis").expect("write");
    std::os::unix::fs::symlink(&users, &path).expect("link");
    let Ok(Guarded::MovedAside(aside, why)) = guard_storage(&path) else {
        panic!("a link is moved aside");
    };
    assert!(why.contains("symbolic link"), "{why}");
    assert!(aside.is_symlink() && !path.exists());
    assert_eq!(std::fs::read_to_string(&users).expect("read"), "my thesis");
    std::fs::remove_file(&aside).expect("clean");

    // /dev/zero behind a link, a FIFO with no writer, a folder, garbage: each at once.
    std::os::unix::fs::symlink("/dev/zero", &path).expect("link");
    let start = Instant::now();
    assert!(matches!(guard_storage(&path), Ok(Guarded::MovedAside(..))));
    std::fs::remove_file(refused(dir.path())[0].clone()).expect("clean");
    let fifo = std::process::Command::new("mkfifo")
        .arg(&path)
        .status()
        .expect("mkfifo");
    assert!(fifo.success());
    assert!(matches!(guard_storage(&path), Ok(Guarded::MovedAside(..))));
    assert!(start.elapsed() < Duration::from_secs(5), "no hang");
    std::fs::remove_file(refused(dir.path())[0].clone()).expect("clean");
    std::fs::write(&path, "this is { not ron").expect("write");
    let Ok(Guarded::MovedAside(aside, why)) = guard_storage(&path) else {
        panic!("garbage is moved aside");
    };
    assert!(why.contains("not eframe's format"), "{why}");
    assert_eq!(
        std::fs::read_to_string(aside).expect("kept"),
        "this is { not ron",
        "kept, not deleted"
    );
}

#[cfg(unix)]
#[test]
fn the_window_never_hangs_on_a_fifo_where_its_memory_was() {
    // No display: the window cannot open, but the memory file is checked first.
    let home = tempfile::tempdir().expect("temp dir");
    let data = home.path().join("data");
    std::fs::create_dir_all(data.join("texplore")).expect("folder");
    let path = data.join("texplore/app.ron");
    let fifo = std::process::Command::new("mkfifo")
        .arg(&path)
        .status()
        .expect("mkfifo");
    assert!(fifo.success());
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_DATA_HOME", &data)
        .env("HOME", home.path())
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run texplore");
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break s;
        }
        if start.elapsed() > Duration::from_mins(1) {
            child.kill().expect("kill");
            panic!("texplore hung on a FIFO at {}", path.display());
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().expect("stderr"), &mut stderr)
        .expect("read stderr");
    assert!(!status.success(), "no display: {stderr}");
    assert!(stderr.contains("not a regular file"), "{stderr}");
    assert!(stderr.contains("moved aside"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(refused(&data.join("texplore")).len(), 1);
}
