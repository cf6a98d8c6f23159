//! The texture panel and the iso-lines, driven headless with `egui_kittest` as a user would
//! (View menu, pointer, checkbox) and checked on what the window shows: labels and pixels.

use crate::gui_common::{harness, small_earth, wait_for_label};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use std::time::{Duration, Instant};
use texplore::gui::ExplorerApp;

const IMAGE: &str = "Rendered image";
const CANVAS: &str = "Texture panel image";
/// The footprint's magenta, the highlight's yellow and the u lines' orange (src/gui).
const MAGENTA: [u8; 3] = [255, 60, 255];
const YELLOW: [u8; 3] = [255, 240, 0];
const ORANGE: [u8; 3] = [255, 150, 40];

/// Ticks the View menu's entry `name`.
fn view_menu(h: &mut Harness<'_, ExplorerApp>, name: &str) {
    h.get_all_by_label("View")
        .min_by(|a, b| a.rect().top().total_cmp(&b.rect().top()))
        .expect("a View menu")
        .click();
    h.run_steps(2);
    h.get_by_role_and_label(Role::CheckBox, name).click();
    h.run_steps(3);
    // Close the menu.
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
}

/// Presses and releases the primary button at `at`.
fn click_at(h: &mut Harness<'_, ExplorerApp>, at: egui::Pos2) {
    h.hover_at(at);
    h.step();
    h.drag_at(at);
    h.step();
    h.drop_at(at);
    h.run_steps(2);
}

/// How many pixels of the window's picture inside `rect` (points) are within 12 of `colour`.
fn count_colour(h: &mut Harness<'_, ExplorerApp>, rect: egui::Rect, colour: [u8; 3]) -> usize {
    let shot = h.render().expect("render the window");
    let s = h.ctx.pixels_per_point();
    let (x0, y0) = ((rect.left() * s) as u32, (rect.top() * s) as u32);
    let (x1, y1) = (
        ((rect.right() * s) as u32).min(shot.width()),
        ((rect.bottom() * s) as u32).min(shot.height()),
    );
    let mut n = 0;
    for y in y0..y1 {
        for x in x0..x1 {
            let p = shot.get_pixel(x, y).0;
            if p[..3].iter().zip(colour).all(|(&a, b)| a.abs_diff(b) <= 12) {
                n += 1;
            }
        }
    }
    n
}

/// The screen point of the centre of film pixel (x, y) of the 160 x 120 small Earth.
fn film_point(h: &Harness<'_, ExplorerApp>, x: u32, y: u32) -> egui::Pos2 {
    let r = h.get_by_label(IMAGE).rect();
    r.min
        + egui::vec2(
            (x as f32 + 0.5) / 160.0 * r.width(),
            (y as f32 + 0.5) / 120.0 * r.height(),
        )
}

fn open_panel(h: &mut Harness<'_, ExplorerApp>) -> egui::Rect {
    view_menu(h, "Texture panel");
    let visible = wait_for_label(h, "Visible region (tinted):");
    let texels: usize = visible
        .split_whitespace()
        .nth(3)
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("a count in '{visible}'"));
    assert!(texels > 1000, "{visible}");
    h.get_by_label(CANVAS).rect()
}

#[test]
fn the_panel_opens_with_the_visible_region_and_a_hover_draws_the_footprint() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    assert!(h.query_by_label(CANVAS).is_none(), "closed at first");
    let canvas = open_panel(&mut h);
    assert_eq!(
        count_colour(&mut h, canvas, MAGENTA),
        0,
        "no pixel hovered yet"
    );
    h.hover_at(film_point(&h, 80, 60));
    h.run_steps(3);
    let label = wait_for_label(&mut h, "'s footprint,");
    assert!(
        label.starts_with("magenta: pixel (80, 60)'s footprint, "),
        "{label}"
    );
    let magenta = count_colour(&mut h, canvas, MAGENTA);
    assert!(magenta > 10, "{magenta} magenta pixels on the texture");
}

#[test]
fn clicking_a_texel_highlights_the_pixels_that_read_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let canvas = open_panel(&mut h);
    let image = h.get_by_label(IMAGE).rect();
    h.hover_at(film_point(&h, 80, 60));
    h.run_steps(3);
    let i = h.state().inspection().expect("an inspection").clone();
    let read = i.image.as_ref().expect("the Earth's image");
    let pick = i
        .texels
        .iter()
        .find(|t| t.lookup == read.lookup)
        .expect("the lookup in use");
    let (w, hh) = (read.image.width() as f32, read.image.height() as f32);
    // The canvas fits the whole texture, centred.
    let fit = (canvas.width() / w).min(canvas.height() / hh);
    let at = canvas.center()
        + egui::vec2(
            (pick.column as f32 + 0.5 - w * 0.5) * fit,
            (pick.file_row as f32 + 0.5 - hh * 0.5) * fit,
        );
    assert_eq!(
        count_colour(&mut h, image, YELLOW),
        0,
        "nothing highlighted yet"
    );
    h.hover_at(at);
    h.run_steps(2);
    click_at(&mut h, at);
    h.run_steps(2);
    let label = wait_for_label(&mut h, "1 texel chosen: ");
    let label = if label.ends_with('…') {
        wait_for_label(&mut h, "read")
    } else {
        label
    };
    assert!(
        label.contains("1 pixel reads it") || label.contains("pixels read it"),
        "{label}"
    );
    h.hover_at(canvas.center() + egui::vec2(0.0, canvas.height() * 0.45));
    h.run_steps(4);
    let yellow = count_colour(&mut h, image, YELLOW);
    assert!(yellow > 10, "{yellow} highlighted points in the viewport");
    // A second click on the same texel forgets it: the highlight goes.
    click_at(&mut h, at);
    h.run_steps(4);
    assert_eq!(count_colour(&mut h, image, YELLOW), 0);
}

#[test]
fn the_iso_lines_checkbox_draws_lines_over_the_shaded_image() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let image = h.get_by_label(IMAGE).rect();
    h.remove_cursor();
    h.run_steps(2);
    let before = count_colour(&mut h, image, ORANGE);
    h.get_by_role_and_label(Role::CheckBox, "Iso-lines").click();
    let started = Instant::now();
    let mut after = 0;
    while started.elapsed() < Duration::from_mins(1) {
        h.run_steps(3);
        after = count_colour(&mut h, image, ORANGE);
        if after > before + 100 {
            break;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    assert!(
        after > before + 100,
        "orange u lines: {before} before, {after} after"
    );
    // Lines over the image, not a picture instead of it: a few percent of its area.
    let s = h.ctx.pixels_per_point();
    let area = image.area() * s * s;
    assert!((after as f32) < area * 0.05, "{after} orange of {area}");
    h.get_by_role_and_label(Role::CheckBox, "Iso-lines").click();
    h.run_steps(3);
    assert!(
        count_colour(&mut h, image, ORANGE) <= before + 5,
        "the lines go"
    );
}

#[test]
fn the_pole_and_the_seam_are_drawn_large_enough_to_see_from_afar() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    // Straight above the north pole, the seam running from it toward the camera's bottom.
    h.state_mut().edit_scene(|d| {
        d.camera.eye = [0.0, 3.6, 0.01].into();
        d.objects[0].transform = texplore::scene::TransformDesc::default();
    });
    crate::gui_common::settle(&mut h);
    let image = h.get_by_label(IMAGE).rect();
    h.remove_cursor();
    h.get_by_role_and_label(Role::CheckBox, "Iso-lines").click();
    let pole_yellow = [255, 255, 0];
    let started = Instant::now();
    let (mut ring, mut seam) = (0, 0);
    while started.elapsed() < Duration::from_mins(1) {
        h.run_steps(3);
        ring = count_colour(&mut h, image, pole_yellow);
        seam = count_colour(&mut h, image, MAGENTA);
        if ring > 150 && seam > 150 {
            break;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    if let Ok(shot) = h.render() {
        let _ = shot.save(std::env::temp_dir().join("texplore-pole-seam.png"));
    }
    // A ring of radius 12 points, 3.5 wide, around the pole: hundreds of yellow pixels (a
    // pixel-sized marker is a handful); the seam 4 points wide over half the sphere's height.
    assert!(ring > 150, "{ring} yellow pixels at the pole");
    assert!(seam > 150, "{seam} magenta pixels on the seam");
}
