//! The inspector at a mirror: the reflected ray worked, drawn, and followed to what it shows,
//! bounce after bounce.

use super::normals::{Arrow, surface_vectors};
use super::srgb;
use crate::inspect::{Inspection, MirrorRead};
use crate::math::Rgb;
use crate::names::Named as _;

const VIEW: egui::Color32 = egui::Color32::from_rgb(120, 170, 255);
const REFLECTED: egui::Color32 = egui::Color32::from_rgb(255, 200, 60);

fn rgb(c: Rgb) -> String {
    format!("({:.3}, {:.3}, {:.3})", c.0, c.1, c.2)
}

/// A colour swatch and its numbers.
fn swatch(ui: &mut egui::Ui, c: Rgb, words: &str) {
    ui.horizontal(|ui| {
        let (r, _) = ui.allocate_exact_size(egui::vec2(28.0, 14.0), egui::Sense::hover());
        ui.painter().rect_filled(r, 2.0, srgb(c));
        ui.label(format!("{} {words}", rgb(c)));
    });
}

/// The mirror `m` at the inspected hit: the reflection worked and drawn, what it adds, and what
/// the reflected ray hits (and, if that is a mirror too, the next bounce).
pub(super) fn mirror_section(ui: &mut egui::Ui, m: &MirrorRead) {
    ui.separator();
    ui.strong(format!(
        "Mirror: bounce {} (the reflection depth allows {})",
        m.depth, m.limit
    ));
    for l in &m.lines {
        ui.monospace(l);
    }
    surface_vectors(
        ui,
        &format!(
            "the mirror edge-on: v (to the viewer) and r (reflected) make equal angles, {:.1}°, \
             with n",
            m.normal.dot(m.view).clamp(-1.0, 1.0).acos().to_degrees()
        ),
        m.normal,
        "n",
        &[
            Arrow {
                dir: m.view,
                name: "v",
                colour: VIEW,
                marked: true,
            },
            Arrow {
                dir: m.direction,
                name: "r",
                colour: REFLECTED,
                marked: true,
            },
        ],
    );
    egui::Grid::new(("inspect-mirror", m.depth))
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            ui.label("kr cr");
            ui.label(rgb(m.weight))
                .on_hover_text("The share of the light along r the mirror passes on");
            ui.end_row();
            if m.followed() {
                ui.label("along r");
                swatch(ui, m.radiance, "linear");
                ui.end_row();
                ui.label("the mirror adds");
                swatch(ui, m.added(), "= kr cr x (along r)");
                ui.end_row();
            }
            if let Some(s) = &m.seen {
                seen_rows(ui, s);
            } else if m.followed() {
                ui.label("r hits");
                ui.label("nothing: the background");
                ui.end_row();
            }
        });
    if let Some(next) = m.seen.as_ref().and_then(|s| s.mirror.as_ref()) {
        mirror_section(ui, next);
    }
}

/// What a reflected ray hits: the object, its (u, v), the texel read and the footprint there,
/// which the mirrored ray differentials carry.
fn seen_rows(ui: &mut egui::Ui, s: &Inspection) {
    let p = s.world_point;
    ui.label("r hits");
    ui.label(format!(
        "{} ({}) at ({:.3}, {:.3}, {:.3})",
        s.object_name, s.shape, p.x, p.y, p.z
    ));
    ui.end_row();
    if let Some(t) = s.tex {
        ui.label("its (u, v)");
        ui.monospace(format!("({:.5}, {:.5})", t.uv.x, t.uv.y));
        ui.end_row();
    }
    if let Some(read) = &s.image
        && let Some(pick) = s.texels.iter().find(|t| t.lookup == read.lookup)
    {
        ui.label("image");
        ui.label(format!(
            "{} ({} filter, {} lookup)",
            read.image.name,
            read.filter.name(),
            pick.lookup.name()
        ));
        ui.end_row();
        ui.label("texel");
        ui.label(format!(
            "column {}, row {} from the bottom",
            pick.column, pick.row_from_bottom
        ));
        ui.end_row();
    }
    if let Some(f) = s.footprint
        && let (Some((a, b)), Some(level)) = (f.axes_texels, f.mip_level)
    {
        ui.label("footprint there");
        ui.label(format!("{a:.2} x {b:.2} texels, mip level {level:.2}"))
            .on_hover_text(
                "The pixel's footprint carried through the mirror: the ray differentials are \
                 reflected too (a curved mirror spreads them), so the texture seen in a mirror \
                 is filtered over its true area",
            );
        ui.end_row();
    }
    ui.label("texture colour there");
    swatch(ui, s.texture_colour, "linear");
    ui.end_row();
}
