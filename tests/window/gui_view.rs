//! The viewport, the A/B divider and the speed panel's legend, driven headless with
//! `egui_kittest` as a user would (pointer, wheel, menus) and checked on what the window shows.

use crate::gui_common::{WINDOW, small_earth};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};
use texplore::gui::{AppOptions, ExplorerApp};
use texplore::report::Mode;
use texplore::scene::CameraDesc;

/// The accessible names the viewport gives its image and the A/B divider.
const IMAGE: &str = "Rendered image";
const DIVIDER: &str = "A/B divider";

fn harness(path: PathBuf) -> Harness<'static, ExplorerApp> {
    let mut h = Harness::builder()
        .with_size(WINDOW)
        .build_eframe(move |_cc| ExplorerApp::with_options(path, AppOptions::default()));
    h.state()
        .wait_for_render(Duration::from_mins(2))
        .expect("the render ends");
    h.run_steps(3);
    h
}

fn camera(h: &Harness<'_, ExplorerApp>) -> CameraDesc {
    h.state().desc().expect("a scene").camera
}

/// Ticks the View menu's entry `name`.
fn view_menu(h: &mut Harness<'_, ExplorerApp>, name: &str) {
    // The menu (topmost), not the viewport's View combo box.
    h.get_all_by_label("View")
        .min_by(|a, b| a.rect().top().total_cmp(&b.rect().top()))
        .expect("a View menu")
        .click();
    h.run_steps(2);
    h.get_by_role_and_label(Role::CheckBox, name).click();
    h.run_steps(3);
}

/// Presses the primary button at `from`, moves to `to` in a few steps and releases it there,
/// after hovering `from` for a few frames (as a hand does).
fn drag(h: &mut Harness<'_, ExplorerApp>, from: egui::Pos2, to: egui::Pos2) {
    h.hover_at(from);
    h.run_steps(3);
    h.drag_at(from);
    h.step();
    for i in 1..=5 {
        h.hover_at(from + (to - from) * (i as f32 / 5.0));
        h.step();
    }
    h.drop_at(to);
    h.run_steps(2);
}

#[test]
fn the_ab_divider_follows_a_drag_and_leaves_the_camera_alone() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    view_menu(&mut h, "A/B split");
    let image = h.get_by_label(IMAGE).rect();
    let start = camera(&h);
    let divider_x = |h: &Harness<'_, ExplorerApp>| h.get_by_label(DIVIDER).rect().center().x;
    assert!(
        (divider_x(&h) - image.center().x).abs() < 1.0,
        "the divider starts at half the image"
    );
    // Mid-height, near the top and near the bottom, as the issue tried.
    for (y, fraction) in [
        (image.center().y, 0.25),
        (image.top() + 4.0, 0.7),
        (image.bottom() - 4.0, 0.4),
    ] {
        let from = egui::pos2(divider_x(&h), y);
        let to = egui::pos2(image.left() + image.width() * fraction, y);
        drag(&mut h, from, to);
        assert!(
            (divider_x(&h) - to.x).abs() < 1.5,
            "dragged to x = {}, the divider is at {}",
            to.x,
            divider_x(&h)
        );
        assert_eq!(camera(&h), start, "dragging the divider moved the camera");
    }
    // A drag on the image away from the divider still orbits.
    let x = divider_x(&h);
    let from = egui::pos2(x - 40.0, image.center().y);
    drag(&mut h, from, from + egui::vec2(-30.0, 0.0));
    assert_ne!(camera(&h).eye, start.eye, "a drag on the image orbits");
    assert!((divider_x(&h) - x).abs() < 0.5, "the divider stayed put");
}

/// Turns the wheel `clicks` notches toward the scene over the image, one event per frame, and
/// lets egui's smooth scrolling run out.
fn wheel_in(h: &mut Harness<'_, ExplorerApp>, clicks: usize) {
    // The image is there once the first build and preview have landed (a loaded machine can
    // take a few frames more than the harness's settling).
    for _ in 0..2000 {
        if h.query_by_label(IMAGE).is_some() {
            break;
        }
        h.step();
    }
    let centre = h.get_by_label(IMAGE).rect().center();
    h.hover_at(centre);
    h.step();
    for _ in 0..clicks {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Line,
            delta: egui::vec2(0.0, 1.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Wheel,
            modifiers: egui::Modifiers::NONE,
        });
        h.step();
    }
    let mut still = 0;
    let mut eye = camera(h).eye;
    for _ in 0..2000 {
        h.step();
        let e = camera(h).eye;
        still = if e == eye { still + 1 } else { 0 };
        eye = e;
        if still == 10 {
            return;
        }
    }
    panic!("the zoom never settled");
}

#[test]
fn zooming_slows_down_near_the_earth_and_stops_outside_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let start = camera(&h).eye;
    assert!((start.length() - 3.6).abs() < 1e-6, "{start}");
    // The nine clicks from the preset's camera: closer, still well outside.
    wheel_in(&mut h, 9);
    let nine = camera(&h).eye;
    assert!(
        nine.length() < start.length() - 0.5 && nine.length() > 1.5,
        "{nine}"
    );
    // Many more: the eye stops 5 % of its distance to the centre above the unit sphere.
    wheel_in(&mut h, 150);
    let end = camera(&h).eye;
    let stop = 1.0 / 0.95;
    assert!(
        (end.length() - stop).abs() < 1e-3,
        "the eye is {} from the centre, not {stop}",
        end.length()
    );
    assert!(end.x.abs() < 1e-6 && end.y.abs() < 1e-6, "{end}");
    // The rendered view is all Earth: every pixel of the image is lit surface, no background.
    h.state()
        .wait_for_render(Duration::from_mins(2))
        .expect("the render ends");
    let image = h.state().image().expect("an image");
    let background = image
        .rgba
        .chunks(4)
        .filter(|p| p[0] == 0 && p[1] == 0 && p[2] == 0)
        .count();
    assert_eq!(
        background, 0,
        "{background} black pixels: the view left the Earth"
    );
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
}

fn same_color(a: image::Rgba<u8>, b: egui::Color32) -> bool {
    a.0[..3]
        .iter()
        .zip([b.r(), b.g(), b.b()])
        .all(|(&x, y)| x.abs_diff(y) <= 3)
}

#[test]
fn the_speed_legend_shows_each_curves_colour() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    view_menu(&mut h, "Speed and error");
    h.get_by_label("Measure").click();
    h.run_steps(3);
    assert!(h.query_by_label("Stop").is_some(), "the measurement runs");
    let started = Instant::now();
    while h.query_by_label("Stop").is_some() {
        assert!(
            started.elapsed() < Duration::from_mins(10),
            "the measurement never finished"
        );
        std::thread::sleep(Duration::from_millis(100));
        h.step();
    }
    h.run_steps(3);
    h.remove_cursor();
    h.run_steps(2);
    let shot = h.render().expect("render the window");
    let scale = h.ctx.pixels_per_point();
    let pixel = |p: egui::Pos2| *shot.get_pixel((p.x * scale) as u32, (p.y * scale) as u32);
    let modes = Mode::default_set();
    let mut entries = Vec::new();
    for mode in &modes {
        let rect = h.get_by_role_and_label(Role::CheckBox, &mode.name()).rect();
        // egui_plot draws the entry's dot, a circle as tall as the text, left of its name.
        let dot = pixel(egui::pos2(
            rect.left() + rect.height() / 2.0,
            rect.center().y,
        ));
        let [r, g, b, _] = dot.0;
        let spread = r.max(g).max(b) - r.min(g).min(b);
        assert!(spread > 40, "{}: its dot is grey ({dot:?})", mode.name());
        entries.push((mode.name(), rect, egui::Color32::from_rgb(r, g, b)));
    }
    for (i, (name, _, color)) in entries.iter().enumerate() {
        for (other, _, c) in &entries[i + 1..] {
            assert_ne!(color, c, "{name} and {other} share a colour");
        }
    }
    // Each dot's colour is its curve's: pixels of it lie in the plot outside the legend.
    let legend = entries
        .iter()
        .fold(egui::Rect::NOTHING, |r, (_, e, _)| r.union(*e))
        .expand(12.0);
    // The plot: under the caption, as wide as it, and above the viewport the window covers.
    let caption = h.get_by_label_contains("log-log").rect();
    let plot = egui::Rect::from_min_max(
        caption.left_bottom(),
        egui::pos2(caption.right(), caption.bottom() + 250.0),
    );
    for (name, _, color) in &entries {
        let on_curve = shot
            .enumerate_pixels()
            .filter(|(x, y, p)| {
                let pos = egui::pos2(*x as f32 / scale, *y as f32 / scale);
                plot.contains(pos) && !legend.contains(pos) && same_color(**p, *color)
            })
            .count();
        assert!(
            on_curve >= 5,
            "{name}: only {on_curve} pixels of its legend colour {color:?} in the plot"
        );
    }
}
