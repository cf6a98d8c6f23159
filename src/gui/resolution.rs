//! The resolution the window renders at: by default the image's own size in screen pixels (at
//! the preset's aspect ratio), so a larger pane, a projector or a higher UI scale gets a
//! sharper image instead of a 640x480 film drawn large; or the preset's resolution, except in
//! presentation mode, which always follows the image (the page renders at the preset's
//! resolution otherwise). A scale renders a fraction of either (a view setting, never saved in
//! the scene).
//!
//! A new size is taken at once (presentation mode, a panel opened or closed, the window
//! resized, the UI scale), except while a pointer button is held: a divider being dragged
//! restarts the render once the size has held for a quarter of a second, or when it is let go.

use crate::math::Vec2;
use std::time::Duration;
use web_time::Instant;

/// How long the image's size must hold, while a pointer button is held, before the render
/// follows it (a drag of a divider does not restart the render on every frame).
const SETTLE: Duration = Duration::from_millis(250);

/// The smallest film side the viewport asks for.
const MIN_SIDE: u32 = 16;

/// The view's resolution setting and the size the image pane asks for.
#[derive(Clone, Debug)]
pub struct ViewResolution {
    /// Render at the pane's size (else at the preset's resolution).
    pub follow_viewport: bool,
    /// The fraction of that size rendered (0.125 to 2).
    pub scale: f32,
    /// Presentation mode: the render follows the image whatever `follow_viewport` says.
    pub presenting: bool,
    /// The pane's size in pixels, once it has held for [`SETTLE`].
    settled: Option<(u32, u32)>,
    /// A new pane size and when it was first seen.
    pending: Option<((u32, u32), Instant)>,
}

impl Default for ViewResolution {
    /// The preset's resolution (tests render small presets at their own size; the window
    /// turns [`ViewResolution::follow_viewport`] on).
    fn default() -> Self {
        Self {
            follow_viewport: false,
            scale: 1.0,
            presenting: false,
            settled: None,
            pending: None,
        }
    }
}

impl ViewResolution {
    /// The preset's resolution, or the image pane's size when `follow_viewport`.
    #[must_use]
    pub fn new(follow_viewport: bool) -> Self {
        Self {
            follow_viewport,
            ..Self::default()
        }
    }

    /// The image's space this frame: `avail` in points, the scene's `aspect` (its preset
    /// width and height), `ppp` screen pixels per point; `held` whether a pointer button is
    /// down (a drag: the size is taken once it holds or the button is let go).
    pub fn viewport(
        &mut self,
        avail: egui::Rect,
        aspect: Vec2,
        ppp: f32,
        held: bool,
        ctx: &egui::Context,
    ) {
        let Some(size) = pane_pixels(avail, aspect, ppp) else {
            return;
        };
        if self.settled == Some(size) {
            self.pending = None;
            return;
        }
        let now = Instant::now();
        match self.pending {
            _ if self.settled.is_none() || !held => {
                self.settled = Some(size);
                self.pending = None;
            }
            Some((s, since)) if s == size => {
                let held = now.duration_since(since);
                if held >= SETTLE {
                    self.settled = Some(size);
                    self.pending = None;
                } else {
                    ctx.request_repaint_after(SETTLE.saturating_sub(held));
                }
            }
            _ => {
                self.pending = Some((size, now));
                ctx.request_repaint_after(SETTLE);
            }
        }
    }

    /// The film size to render for a preset of `preset` pixels.
    #[must_use]
    pub fn film(&self, preset: (u32, u32)) -> (u32, u32) {
        let base = match self.settled {
            Some(s) if self.follow_viewport || self.presenting => s,
            _ => preset,
        };
        let side = |v: u32| ((v as f32 * self.scale).round() as u32).max(1);
        (side(base.0), side(base.1))
    }

    /// What the slider's tooltip says the scale is a fraction of.
    #[must_use]
    pub fn of_what(&self) -> &'static str {
        if self.follow_viewport || self.presenting {
            "the image pane's size in screen pixels"
        } else {
            "the preset's resolution"
        }
    }
}

/// The pixels of the largest rectangle of `aspect` that fits in `avail` (`None` for an empty
/// pane or a degenerate aspect).
fn pane_pixels(avail: egui::Rect, aspect: Vec2, ppp: f32) -> Option<(u32, u32)> {
    if !(aspect.x > 0.0 && aspect.y > 0.0 && avail.width() > 1.0 && avail.height() > 1.0) {
        return None;
    }
    let fit = (avail.width() / aspect.x).min(avail.height() / aspect.y) * ppp;
    let side = |v: f32| ((v * fit).round() as u32).max(MIN_SIDE);
    Some((side(aspect.x), side(aspect.y)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(w: f32, h: f32) -> egui::Rect {
        egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(w, h))
    }

    #[test]
    fn the_film_fills_the_pane_at_the_presets_aspect() {
        // A 4:3 preset in a 900x500-point pane at 2 pixels per point: 500 points high.
        assert_eq!(
            pane_pixels(rect(900.0, 500.0), Vec2::new(640.0, 480.0), 2.0),
            Some((1333, 1000))
        );
        assert_eq!(
            pane_pixels(rect(0.0, 500.0), Vec2::new(640.0, 480.0), 1.0),
            None
        );
    }

    #[test]
    fn a_new_size_is_taken_at_once_but_while_dragging_once_it_holds() {
        let ctx = egui::Context::default();
        let mut r = ViewResolution {
            follow_viewport: true,
            ..ViewResolution::default()
        };
        let aspect = Vec2::new(4.0, 3.0);
        r.viewport(rect(400.0, 300.0), aspect, 1.0, false, &ctx);
        assert_eq!(r.film((640, 480)), (400, 300));
        // Presentation mode, a panel closed: at once.
        r.viewport(rect(600.0, 450.0), aspect, 1.0, false, &ctx);
        assert_eq!(r.film((640, 480)), (600, 450));
        // A divider dragged: once it holds.
        r.viewport(rect(400.0, 300.0), aspect, 1.0, true, &ctx);
        r.viewport(rect(800.0, 600.0), aspect, 1.0, true, &ctx);
        assert_eq!(r.film((640, 480)), (600, 450), "not before it holds");
        r.pending = r.pending.map(|(s, t)| {
            (
                s,
                t.checked_sub(SETTLE)
                    .expect("the clock runs longer than that"),
            )
        });
        r.viewport(rect(800.0, 600.0), aspect, 1.0, true, &ctx);
        assert_eq!(r.film((640, 480)), (800, 600));
        r.viewport(rect(700.0, 525.0), aspect, 1.0, true, &ctx);
        r.viewport(rect(700.0, 525.0), aspect, 1.0, false, &ctx);
        assert_eq!(r.film((640, 480)), (700, 525), "let go: at once");
        r.scale = 0.5;
        assert_eq!(r.film((640, 480)), (350, 263));
        r.follow_viewport = false;
        assert_eq!(r.film((640, 480)), (320, 240));
        r.presenting = true;
        assert_eq!(
            r.film((640, 480)),
            (350, 263),
            "presentation mode follows the image"
        );
    }
}
