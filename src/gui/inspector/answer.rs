//! The inspector's answer, first (issue 37 §3): the texel the pixel reads and its colour (or,
//! for a texture that is not an image, the texture's colour there), and (u, v); the working
//! follows below it.

use super::srgb;
use crate::inspect::Inspection;
use crate::math::Rgb;
use crate::names::Named as _;
use crate::texture::Filter;

/// A colour's swatch and its linear values, after `what`.
fn swatch(ui: &mut egui::Ui, what: &str, c: Rgb) {
    ui.horizontal_wrapped(|ui| {
        ui.label(what);
        let side = ui.text_style_height(&egui::TextStyle::Body);
        let (r, _) = ui.allocate_exact_size(egui::vec2(2.0 * side, side), egui::Sense::hover());
        ui.painter().rect_filled(r, 2.0, srgb(c));
        ui.monospace(format!("({:.3}, {:.3}, {:.3}) linear", c.0, c.1, c.2));
    });
}

/// The answer for the pixel `i`, in a frame of its own above the working.
pub(super) fn answer(ui: &mut egui::Ui, i: &Inspection) {
    egui::Frame::group(ui.style()).show(ui, |ui| {
        ui.set_width(ui.available_width());
        let read = i
            .image
            .as_ref()
            .and_then(|r| Some((r, i.texels.iter().find(|p| p.lookup == r.lookup)?)));
        if let Some((read, pick)) = read {
            ui.strong(format!(
                "Texel: column {}, row {} from the bottom of {}",
                pick.column, pick.row_from_bottom, read.image.name
            ))
            .on_hover_text(format!(
                "The {} lookup's texel (file row {}); the working below shows both lookups",
                pick.lookup.name(),
                pick.file_row
            ));
            swatch(
                ui,
                "its colour",
                read.image.texel(pick.column, pick.row_from_bottom),
            );
            if read.filter != Filter::Nearest {
                swatch(
                    ui,
                    &format!("the {} filter gives", read.filter.name()),
                    i.texture_colour,
                );
            }
        } else {
            ui.strong(format!("Texture: {}", i.texture_kind));
            swatch(ui, "its colour here", i.texture_colour);
        }
        if let Some(t) = i.tex {
            ui.label(format!(
                "at (u, v) = ({:.4}, {:.4}) on {}",
                t.uv.x, t.uv.y, i.object_name
            ));
        }
    });
    ui.label(egui::RichText::new("The working, step by step:").strong());
}
