//! How long the window's frames take while a displaced mesh is edited (issue 23: "editing a
//! displaced mesh at 4 levels leaves the window responsive"). A measurement, not a check of
//! this machine's speed: run it by hand and read what it prints.
//!
//! `cargo test --test window gui_frame_time:: -- --ignored --nocapture`

use egui_kittest::Harness;
use std::path::Path;
use std::time::{Duration, Instant};
use texplore::gui::ExplorerApp;
use texplore::scene::{load_preset, save_preset};

/// Subdivision levels of the displaced knot.
const LEVELS: u32 = 4;
/// Edits measured.
const EDITS: usize = 3;

#[test]
#[ignore = "a measurement: run by hand with --ignored --nocapture"]
fn frame_times_while_a_displaced_mesh_is_edited() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut desc = load_preset(&root.join("presets/displaced.ron")).expect("displaced preset");
    let knot = desc
        .objects
        .iter()
        .position(|o| o.displace.is_some())
        .expect("a displaced object");
    desc.objects[knot]
        .displace
        .as_mut()
        .expect("displacement")
        .subdivide = LEVELS;
    desc.render.width = 320;
    desc.render.height = 240;
    // In the presets folder, so its asset paths hold.
    let path = root.join("presets/.frame-time-displaced.ron");
    save_preset(&desc, &path).expect("write preset");
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(|_cc| ExplorerApp::open(path.clone()));
    let _ = std::fs::remove_file(&path);
    // The first build (the mesh file, the height image, the displacement).
    let start = Instant::now();
    while h.state().image().is_none() {
        assert!(start.elapsed() < Duration::from_mins(5), "the scene opens");
        h.step();
        std::thread::sleep(Duration::from_millis(10));
    }
    assert_eq!(h.state().error(), None);
    let mut all = Vec::new();
    for edit in 0..EDITS {
        let width = 328 + 8 * edit as u32;
        let edited = Instant::now();
        // The edit, as a panel makes it during a frame: the time the UI thread spends in it
        // (the whole build, when builds ran on it) counts toward the first frame.
        h.state_mut().edit_scene(|d| {
            let displace = d.objects[knot].displace.as_mut().expect("displacement");
            displace.scale += 0.01;
            // The new scene's image is told apart from the old one's by its width.
            d.render.width = width;
        });
        let mut in_edit = Some(edited.elapsed());
        let mut frames = Vec::new();
        // Frames until the edited scene's image shows, as a user would see them: the window
        // repaints about every 33 ms while it renders or builds.
        loop {
            let t = Instant::now();
            h.step();
            frames.push(t.elapsed() + in_edit.take().unwrap_or_default());
            if h.state().image().is_some_and(|i| i.width == width) {
                break;
            }
            assert!(h.state().error().is_none(), "{:?}", h.state().error());
            assert!(edited.elapsed() < Duration::from_mins(5), "the edit builds");
            std::thread::sleep(Duration::from_millis(33));
        }
        let landed = edited.elapsed();
        let longest = frames.iter().max().copied().unwrap_or_default();
        let mean = frames.iter().sum::<Duration>() / frames.len().max(1) as u32;
        println!(
            "edit {edit}: built and shown after {:.0} ms over {} frames; longest frame {:.1} ms, \
             mean {:.1} ms",
            landed.as_secs_f64() * 1e3,
            frames.len(),
            longest.as_secs_f64() * 1e3,
            mean.as_secs_f64() * 1e3
        );
        all.extend(frames);
        // Let the render of the new scene run a little, as between a user's edits.
        for _ in 0..10 {
            h.step();
            std::thread::sleep(Duration::from_millis(33));
        }
    }
    all.sort();
    let pick = |q: f64| all[((all.len() - 1) as f64 * q) as usize].as_secs_f64() * 1e3;
    println!(
        "{} frames during {EDITS} edits at {LEVELS} levels: median {:.1} ms, 90th percentile \
         {:.1} ms, longest {:.1} ms",
        all.len(),
        pick(0.5),
        pick(0.9),
        pick(1.0)
    );
}
