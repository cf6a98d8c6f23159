//! Presentation mode's captions: the experiment tried with its *Look for*, and the lesson's
//! question, in type a room can read, placed where they cover as little of the image as the
//! window allows (issue 37 §3):
//!
//! 1. **Beside** the image, in a column right of it, when the image (fitted to the pane's
//!    height) leaves room there: a 4:3 lesson scene on a 16:9 screen does. Nothing of the
//!    image is covered.
//! 2. **Above and below** it, the image shrunk to make room, when it still keeps the width
//!    it must (60% of the window).
//! 3. **Over its top**, when neither fits (a panel open beside the image): in the upper third
//!    of the image, never its lower third.
//!
//! In each, the type shrinks step by step (down to [`MIN_PX`]) before the next is tried.

use super::Caption;

/// The *Look for* caption's size, in screen pixels of a 720-row window (larger windows scale
/// it with their height).
const LOOK_FOR_PX: f32 = 26.0;
/// The question's size, likewise.
const QUESTION_PX: f32 = 22.0;
/// The smallest the captions shrink to (the *Look for*'s; the question keeps its proportion).
const MIN_PX: f32 = 16.0;
/// The narrowest column beside the image that takes the captions.
const MIN_COLUMN_PX: f32 = 240.0;
/// The space around a caption's text inside its dark box, and between boxes.
const PAD_PX: f32 = 8.0;

/// Where the captions went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Placing {
    /// In a column right of the image.
    Beside,
    /// The *Look for* above the image, the question below.
    AboveBelow,
    /// Over the image's upper third.
    OverTop,
}

/// One caption: its text, its size (points) and its dark box (points).
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    /// The text drawn (and its accessible label).
    pub text: String,
    /// The font size, in points.
    pub size: f32,
    /// The box the text sits in, padding included.
    pub rect: egui::Rect,
    /// The padding round the text inside the box.
    pad: f32,
    /// Its id's salt.
    key: &'static str,
}

/// The image's place and the captions'.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// The space the image is fitted into.
    pub image: egui::Rect,
    /// The captions, in the order they are read.
    pub bands: Vec<Band>,
    /// Which of the three placings was taken.
    pub placing: Placing,
}

/// The sizes of the captions a window of this shape draws: `unit` is the points of one pixel
/// of a 720-row window (its height over 720, at least 1, over the pixels per point), and
/// `min_width` the narrowest the image may get (points).
#[derive(Clone, Copy, Debug)]
pub struct Scale {
    /// Points per pixel of a 720-row window.
    pub unit: f32,
    /// The image's least width (60% of the window), in points.
    pub min_width: f32,
}

impl Scale {
    /// The scale of the window `ctx` draws: its height in pixels over 720 (at least 1) and its
    /// pixels per point; the image keeps 60% of its width.
    #[must_use]
    pub fn of(ctx: &egui::Context) -> Self {
        let ppp = ctx.pixels_per_point();
        let window = ctx.content_rect();
        let rows = window.height() * ppp;
        Self {
            unit: (rows / 720.0).max(1.0) / ppp,
            min_width: 0.6 * window.width(),
        }
    }
}

/// The rectangle an image of `size` takes, fitted in `avail` at its centre.
fn fit(avail: egui::Rect, size: egui::Vec2) -> egui::Rect {
    let s = (avail.width() / size.x)
        .min(avail.height() / size.y)
        .max(1e-3);
    egui::Rect::from_center_size(avail.center(), size * s)
}

/// Lays out `caption` and an image of aspect `image` in `pane` (points); `measure(text, size,
/// width)` is the size of `text` at font `size` wrapped at `width` (egui's fonts in the window,
/// a stand-in in the tests).
pub fn place(
    pane: egui::Rect,
    image: egui::Vec2,
    caption: &Caption,
    scale: Scale,
    measure: &dyn Fn(&str, f32, f32) -> egui::Vec2,
) -> Layout {
    let full = fit(pane, image);
    let mut texts: Vec<(String, f32, &'static str)> = Vec::new();
    if let Some((label, look_for)) = &caption.experiment {
        texts.push((
            format!("{label}\nLook for: {look_for}"),
            LOOK_FOR_PX,
            "caption-look-for",
        ));
    }
    if !caption.question.is_empty() {
        texts.push((caption.question.clone(), QUESTION_PX, "caption-question"));
    }
    if texts.is_empty() {
        return Layout {
            image: full,
            bands: Vec::new(),
            placing: Placing::Beside,
        };
    }
    let u = scale.unit;
    let pad = PAD_PX * u;
    // Each step 10% smaller, down to MIN_PX for the Look for.
    let shrinks: Vec<f32> = std::iter::successors(Some(1.0_f32), |s| Some(s * 0.9))
        .take_while(|s| LOOK_FOR_PX * s >= MIN_PX - 1e-3)
        .collect();
    // The boxes' heights at a shrink, the text wrapped at `width` (box included).
    let heights = |shrink: f32, width: f32| -> Vec<(f32, f32)> {
        texts
            .iter()
            .map(|(t, px, _)| {
                let size = px * shrink * u;
                (size, measure(t, size, width - 2.0 * pad).y + 2.0 * pad)
            })
            .collect()
    };
    let band = |i: usize, size: f32, rect: egui::Rect| Band {
        text: texts[i].0.clone(),
        size,
        rect,
        pad,
        key: texts[i].2,
    };

    // 1. Beside: the image at the pane's left, the captions in the column right of it.
    let column = pane.width() - full.width() - pad;
    if column >= MIN_COLUMN_PX * u {
        let image = full.translate(egui::vec2(pane.left() - full.left(), 0.0));
        let x = image.right() + pad;
        for &s in &shrinks {
            let h = heights(s, column);
            let total: f32 = h.iter().map(|(_, h)| h).sum::<f32>() + pad * (h.len() - 1) as f32;
            if total <= pane.height() {
                // The Look for level with the image's top, the question with its bottom.
                let mut bands = Vec::new();
                let mut top = image.top().max(pane.top());
                for (i, &(size, height)) in h.iter().enumerate() {
                    let y = if texts[i].2 == "caption-question" {
                        (image.bottom().min(pane.bottom()) - height).max(top)
                    } else {
                        top
                    };
                    let rect =
                        egui::Rect::from_min_size(egui::pos2(x, y), egui::vec2(column, height));
                    top = rect.bottom() + pad;
                    bands.push(band(i, size, rect));
                }
                return Layout {
                    image,
                    bands,
                    placing: Placing::Beside,
                };
            }
        }
    }

    // 2. Above and below: the image shrinks into what the captions leave, keeping its width.
    let least = scale.min_width.min(full.width());
    for &s in &shrinks {
        let h = heights(s, pane.width());
        let (mut above, mut below) = (0.0, 0.0);
        for (i, (_, height)) in h.iter().enumerate() {
            if texts[i].2 == "caption-question" {
                below += height + pad;
            } else {
                above += height + pad;
            }
        }
        let space = egui::Rect::from_min_max(
            pane.min + egui::vec2(0.0, above),
            pane.max - egui::vec2(0.0, below),
        );
        if space.height() <= 0.0 {
            continue;
        }
        let image = fit(space, image);
        if image.width() + 0.5 >= least {
            let bands = h
                .iter()
                .enumerate()
                .map(|(i, &(size, height))| {
                    let y = if texts[i].2 == "caption-question" {
                        image.bottom() + pad
                    } else {
                        image.top() - pad - height
                    };
                    let rect = egui::Rect::from_min_size(
                        egui::pos2(pane.left(), y),
                        egui::vec2(pane.width(), height),
                    );
                    band(i, size, rect)
                })
                .collect();
            return Layout {
                image: space,
                bands,
                placing: Placing::AboveBelow,
            };
        }
    }

    // 3. Over the image's top: the upper third, the smallest type if need be (the painter
    // clips at two thirds, so the lower third is never covered).
    let width = full.width() - 2.0 * pad;
    let third = full.height() / 3.0;
    let fits = |s: f32| {
        let h = heights(s, width);
        let total: f32 = h.iter().map(|(_, h)| h).sum::<f32>() + pad * (h.len() + 1) as f32;
        (total <= third).then_some(h)
    };
    let h = shrinks
        .iter()
        .find_map(|&s| fits(s))
        .unwrap_or_else(|| heights(*shrinks.last().unwrap_or(&1.0), width));
    let mut top = full.top() + pad;
    let bands = h
        .iter()
        .enumerate()
        .map(|(i, &(size, height))| {
            let rect = egui::Rect::from_min_size(
                egui::pos2(full.left() + pad, top),
                egui::vec2(width, height),
            );
            top = rect.bottom() + pad;
            band(i, size, rect)
        })
        .collect();
    Layout {
        image: full,
        bands,
        placing: Placing::OverTop,
    }
}

/// The upper two thirds of the image `image` would take in `layout`: where an over-the-top
/// caption may be drawn.
fn upper_two_thirds(layout: &Layout, aspect: egui::Vec2) -> egui::Rect {
    let r = fit(layout.image, aspect);
    egui::Rect::from_min_max(
        r.min,
        egui::pos2(r.right(), r.top() + r.height() * 2.0 / 3.0),
    )
}

/// Draws `layout`'s captions (each an accessible label), inside `clip`; over the image they
/// stay in its upper two thirds.
pub fn draw(ui: &egui::Ui, layout: &Layout, aspect: egui::Vec2, clip: egui::Rect) {
    let clip = if layout.placing == Placing::OverTop {
        clip.intersect(upper_two_thirds(layout, aspect))
    } else {
        clip
    };
    let painter = ui.painter().with_clip_rect(clip);
    for b in &layout.bands {
        let galley = painter.layout(
            b.text.clone(),
            egui::FontId::proportional(b.size),
            egui::Color32::WHITE,
            b.rect.width() - 2.0 * b.pad,
        );
        painter.rect_filled(b.rect, 6.0, egui::Color32::from_black_alpha(200));
        painter.galley(
            b.rect.min + egui::vec2(b.pad, b.pad),
            galley,
            egui::Color32::WHITE,
        );
        let response = ui.interact(b.rect, ui.scope_id().with(b.key), egui::Sense::hover());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Label, true, &b.text));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stand-in for egui's fonts: characters half the size wide, lines 1.2 sizes high.
    fn measure(text: &str, size: f32, width: f32) -> egui::Vec2 {
        let per_line = ((width / (0.5 * size)).floor() as usize).max(1);
        let lines: usize = text
            .split('\n')
            .map(|l| l.chars().count().div_ceil(per_line).max(1))
            .sum();
        egui::vec2(width, lines as f32 * 1.2 * size)
    }

    fn caption(look_for: usize, question: usize) -> Caption {
        Caption {
            experiment: Some(("The lecture's lookup".to_owned(), "x".repeat(look_for))),
            question: "q".repeat(question),
        }
    }

    fn rect(x: f32, y: f32, w: f32, h: f32) -> egui::Rect {
        egui::Rect::from_min_size(egui::pos2(x, y), egui::vec2(w, h))
    }

    const SCALE: Scale = Scale {
        unit: 1.0,
        min_width: 0.6 * 1280.0,
    };

    fn assert_clear_of_lower_third(l: &Layout, aspect: egui::Vec2) {
        let image = fit(l.image, aspect);
        let lower = rect(
            image.left(),
            image.top() + image.height() * 2.0 / 3.0,
            image.width(),
            image.height() / 3.0,
        );
        for b in &l.bands {
            let drawn = if l.placing == Placing::OverTop {
                b.rect.intersect(upper_two_thirds(l, aspect))
            } else {
                b.rect
            };
            assert!(
                !drawn.intersects(lower.shrink(0.5)),
                "{:?}: {drawn:?} covers the lower third {lower:?}",
                l.placing
            );
        }
    }

    #[test]
    fn a_4_3_scene_at_720p_gets_its_captions_beside_it_uncovered_and_full_size() {
        // The image pane of presentation mode at 1280x720: right of the strip, below the
        // toolbar.
        let pane = rect(90.0, 80.0, 1180.0, 610.0);
        let aspect = egui::vec2(640.0, 480.0);
        let l = place(pane, aspect, &caption(200, 130), SCALE, &measure);
        assert_eq!(l.placing, Placing::Beside);
        let image = fit(l.image, aspect);
        assert!(image.width() >= 0.6 * 1280.0, "{image:?}");
        assert!(
            (image.height() - 610.0).abs() < 0.5,
            "the image keeps the height"
        );
        for b in &l.bands {
            assert!(!b.rect.intersects(image.shrink(0.5)), "{b:?}");
            assert!(pane.contains_rect(b.rect), "{b:?}");
        }
        assert_eq!(l.bands[0].size, LOOK_FOR_PX);
        assert_eq!(l.bands[1].size, QUESTION_PX);
        assert!(l.bands[0].rect.bottom() < l.bands[1].rect.top());
    }

    #[test]
    fn without_room_beside_the_captions_go_above_and_below_or_over_the_upper_third() {
        let aspect = egui::vec2(800.0, 400.0);
        // A wide scene in a tall pane: room above and below.
        let pane = rect(0.0, 0.0, 1180.0, 900.0);
        let l = place(pane, aspect, &caption(200, 130), SCALE, &measure);
        assert_eq!(l.placing, Placing::AboveBelow);
        let image = fit(l.image, aspect);
        assert!(image.width() >= 0.6 * 1280.0 - 0.5, "{image:?}");
        for b in &l.bands {
            assert!(!b.rect.intersects(image.shrink(0.5)), "{b:?}");
        }
        assert_clear_of_lower_third(&l, aspect);

        // A panel open beside the image: the pane is the image's own shape; over the top.
        let aspect = egui::vec2(640.0, 480.0);
        let pane = rect(0.0, 0.0, 800.0, 600.0);
        let l = place(pane, aspect, &caption(200, 130), SCALE, &measure);
        assert_eq!(l.placing, Placing::OverTop);
        assert_eq!(
            fit(l.image, aspect),
            fit(pane, aspect),
            "the image keeps its size"
        );
        assert!(l.bands[0].size < LOOK_FOR_PX, "the type shrank");
        assert_clear_of_lower_third(&l, aspect);
        // A short caption fits the upper third at full size.
        let l = place(pane, aspect, &caption(20, 0), SCALE, &measure);
        assert_eq!(l.bands.len(), 1);
        assert_eq!(l.bands[0].size, LOOK_FOR_PX);
        assert!(l.bands[0].rect.bottom() <= 200.0, "{:?}", l.bands[0]);
    }

    #[test]
    fn a_larger_window_gets_larger_captions_and_no_caption_leaves_the_image_whole() {
        let pane = rect(130.0, 120.0, 1770.0, 915.0);
        let aspect = egui::vec2(640.0, 480.0);
        let scale = Scale {
            unit: 1.5,
            min_width: 0.6 * 1920.0,
        };
        let l = place(pane, aspect, &caption(200, 130), scale, &measure);
        assert_eq!(l.placing, Placing::Beside);
        assert_eq!(l.bands[0].size, LOOK_FOR_PX * 1.5);
        let none = Caption::default();
        let l = place(pane, aspect, &none, scale, &measure);
        assert!(l.bands.is_empty());
        assert_eq!(fit(l.image, aspect), fit(pane, aspect));
    }
}
