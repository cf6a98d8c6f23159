//! Plots without a plotting crate: a log-log chart laid out once as a list of drawing commands,
//! written as SVG text or rasterised to RGB pixels (anti-aliased lines and discs; text through
//! `ab_glyph` with egui's bundled Ubuntu Light, so no system font library is involved), and
//! error heat maps with a colour bar.

use super::{ErrorMap, SceneReport, table};
use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use std::fmt::Write as _;
use std::sync::LazyLock;

/// An RGB colour as bytes.
pub type Colour = [u8; 3];

/// Line colours, cycled (Tableau 10 and two more).
pub const PALETTE: [Colour; 12] = [
    [31, 119, 180],
    [255, 127, 14],
    [44, 160, 44],
    [214, 39, 40],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [127, 127, 127],
    [188, 189, 34],
    [23, 190, 207],
    [0, 0, 0],
    [255, 215, 0],
];

/// Where text sits relative to its anchor point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// Anchor at the left end of the baseline.
    Start,
    /// Anchor at the middle of the baseline.
    Middle,
    /// Anchor at the right end of the baseline.
    End,
}

/// One drawing command in pixel coordinates (y down).
#[derive(Clone, Debug, PartialEq)]
pub enum Cmd {
    /// A polyline.
    Line {
        /// Vertices.
        points: Vec<(f64, f64)>,
        /// Colour.
        colour: Colour,
        /// Stroke width in pixels.
        width: f64,
    },
    /// A filled disc.
    Disc {
        /// Centre.
        centre: (f64, f64),
        /// Radius in pixels.
        radius: f64,
        /// Colour.
        colour: Colour,
    },
    /// Text; `vertical` turns it 90 degrees counter-clockwise about the anchor.
    Text {
        /// Anchor point on the baseline.
        at: (f64, f64),
        /// The text.
        text: String,
        /// Size in pixels.
        size: f64,
        /// Horizontal alignment.
        anchor: Anchor,
        /// Rotated to read bottom to top.
        vertical: bool,
    },
}

/// A series of (x, y) points with a label.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points, drawn in order.
    pub points: Vec<(f64, f64)>,
}

/// A log-log chart.
#[derive(Clone, Debug, PartialEq)]
pub struct LogLogChart {
    /// Title above the plot.
    pub title: String,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// The lines.
    pub series: Vec<Series>,
    /// Horizontal reference lines: (y, label).
    pub y_marks: Vec<(f64, String)>,
}

/// Width of the rendered chart in pixels (the plot area plus the legend on the right).
pub const CHART_WIDTH: u32 = 1000;
/// Height of the rendered chart in pixels.
pub const CHART_HEIGHT: u32 = 600;

/// Decade bounds [10^lo, 10^hi] covering positive values `v` (at least one decade).
fn decades(v: impl Iterator<Item = f64>) -> (i32, i32) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in v.filter(|x| x.is_finite() && *x > 0.0) {
        lo = lo.min(x);
        hi = hi.max(x);
    }
    if !lo.is_finite() {
        return (-1, 0);
    }
    let (a, b) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    (a, if b > a { b } else { a + 1 })
}

fn decade_label(k: i32) -> String {
    if (-3..=4).contains(&k) {
        let v = 10f64.powi(k);
        if k >= 0 {
            format!("{v:.0}")
        } else {
            format!("{v:.prec$}", prec = (-k) as usize)
        }
    } else {
        format!("1e{k}")
    }
}

impl LogLogChart {
    /// The chart as drawing commands on a [`CHART_WIDTH`] x [`CHART_HEIGHT`] canvas.
    #[must_use]
    pub fn layout(&self) -> Vec<Cmd> {
        let (left, top, right, bottom) = (80.0, 40.0, 740.0, 540.0);
        let all = || self.series.iter().flat_map(|s| s.points.iter().copied());
        let (x0, x1) = decades(all().map(|p| p.0));
        let (y0, y1) = decades(all().map(|p| p.1).chain(self.y_marks.iter().map(|m| m.0)));
        let sx = |x: f64| left + (x.log10() - f64::from(x0)) / f64::from(x1 - x0) * (right - left);
        let sy =
            |y: f64| bottom - (y.log10() - f64::from(y0)) / f64::from(y1 - y0) * (bottom - top);
        let grid = [225, 225, 225];
        let minor = [242, 242, 242];
        let ink = [40, 40, 40];
        let text = |at, text: &str, size, anchor, vertical| Cmd::Text {
            at,
            text: text.to_string(),
            size,
            anchor,
            vertical,
        };
        let mut c = Vec::new();
        // Grid: minor lines at 2..9 x 10^k, major at decades with labels.
        for k in x0..x1 {
            for m in 2..10 {
                let x = sx(f64::from(m) * 10f64.powi(k));
                c.push(line(vec![(x, top), (x, bottom)], minor, 1.0));
            }
        }
        for k in y0..y1 {
            for m in 2..10 {
                let y = sy(f64::from(m) * 10f64.powi(k));
                c.push(line(vec![(left, y), (right, y)], minor, 1.0));
            }
        }
        for k in x0..=x1 {
            let x = sx(10f64.powi(k));
            c.push(line(vec![(x, top), (x, bottom)], grid, 1.0));
            c.push(text(
                (x, bottom + 18.0),
                &decade_label(k),
                13.0,
                Anchor::Middle,
                false,
            ));
        }
        for k in y0..=y1 {
            let y = sy(10f64.powi(k));
            c.push(line(vec![(left, y), (right, y)], grid, 1.0));
            c.push(text(
                (left - 6.0, y + 4.0),
                &decade_label(k),
                13.0,
                Anchor::End,
                false,
            ));
        }
        for (y, label) in &self.y_marks {
            let py = sy(*y);
            c.push(line(vec![(left, py), (right, py)], [150, 150, 150], 1.0));
            c.push(text(
                (right - 4.0, py - 4.0),
                label,
                12.0,
                Anchor::End,
                false,
            ));
        }
        // Frame, title and axis labels.
        c.push(line(
            vec![
                (left, top),
                (right, top),
                (right, bottom),
                (left, bottom),
                (left, top),
            ],
            ink,
            1.0,
        ));
        c.push(text(
            ((left + right) / 2.0, 24.0),
            &self.title,
            16.0,
            Anchor::Middle,
            false,
        ));
        c.push(text(
            ((left + right) / 2.0, bottom + 44.0),
            &self.x_label,
            14.0,
            Anchor::Middle,
            false,
        ));
        c.push(text(
            (24.0, (top + bottom) / 2.0),
            &self.y_label,
            14.0,
            Anchor::Middle,
            true,
        ));
        // Series and legend.
        let (lx, mut ly) = (right + 20.0, top + 10.0);
        for (i, s) in self.series.iter().enumerate() {
            let colour = PALETTE[i % PALETTE.len()];
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter(|p| p.0 > 0.0 && p.1 > 0.0 && p.0.is_finite() && p.1.is_finite())
                .map(|p| (sx(p.0), sy(p.1)))
                .collect();
            if pts.len() > 1 {
                c.push(line(pts.clone(), colour, 2.0));
            }
            for p in pts {
                c.push(Cmd::Disc {
                    centre: p,
                    radius: 3.5,
                    colour,
                });
            }
            c.push(line(
                vec![(lx, ly - 4.0), (lx + 24.0, ly - 4.0)],
                colour,
                2.0,
            ));
            c.push(Cmd::Disc {
                centre: (lx + 12.0, ly - 4.0),
                radius: 3.5,
                colour,
            });
            c.push(text((lx + 30.0, ly), &s.label, 13.0, Anchor::Start, false));
            ly += 20.0;
        }
        c
    }

    /// The chart as an SVG document.
    #[must_use]
    pub fn to_svg(&self) -> String {
        svg(&self.layout(), CHART_WIDTH, CHART_HEIGHT)
    }

    /// The chart as RGB pixels, row-major.
    #[must_use]
    pub fn to_rgb(&self) -> Vec<u8> {
        let mut canvas = Canvas::new(CHART_WIDTH, CHART_HEIGHT, [255, 255, 255]);
        for cmd in &self.layout() {
            canvas.draw(cmd);
        }
        canvas.rgb
    }
}

fn line(points: Vec<(f64, f64)>, colour: Colour, width: f64) -> Cmd {
    Cmd::Line {
        points,
        colour,
        width,
    }
}

fn hex(c: Colour) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Drawing commands as an SVG document of `width` x `height`.
#[must_use]
pub fn svg(cmds: &[Cmd], width: u32, height: u32) -> String {
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" font-family=\"Ubuntu, DejaVu Sans, Arial, sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    for c in cmds {
        match c {
            Cmd::Line {
                points,
                colour,
                width,
            } => {
                let pts: Vec<String> = points
                    .iter()
                    .map(|(x, y)| format!("{x:.2},{y:.2}"))
                    .collect();
                let _ = writeln!(
                    s,
                    "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{width}\" stroke-linejoin=\"round\"/>",
                    pts.join(" "),
                    hex(*colour)
                );
            }
            Cmd::Disc {
                centre,
                radius,
                colour,
            } => {
                let _ = writeln!(
                    s,
                    "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"{radius}\" fill=\"{}\"/>",
                    centre.0,
                    centre.1,
                    hex(*colour)
                );
            }
            Cmd::Text {
                at,
                text,
                size,
                anchor,
                vertical,
            } => {
                let a = match anchor {
                    Anchor::Start => "start",
                    Anchor::Middle => "middle",
                    Anchor::End => "end",
                };
                let rot = if *vertical {
                    format!(" transform=\"rotate(-90 {:.2} {:.2})\"", at.0, at.1)
                } else {
                    String::new()
                };
                let _ = writeln!(
                    s,
                    "<text x=\"{:.2}\" y=\"{:.2}\" font-size=\"{size}\" text-anchor=\"{a}\" fill=\"#282828\"{rot}>{}</text>",
                    at.0,
                    at.1,
                    xml_escape(text)
                );
            }
        }
    }
    s.push_str("</svg>\n");
    s
}

static FONT: LazyLock<Option<FontRef<'static>>> =
    LazyLock::new(|| FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).ok());

/// An RGB raster that draws [`Cmd`]s with anti-aliasing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Canvas {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGB bytes, row-major.
    pub rgb: Vec<u8>,
}

impl Canvas {
    /// A canvas filled with `background`.
    #[must_use]
    pub fn new(width: u32, height: u32, background: Colour) -> Self {
        Self {
            width,
            height,
            rgb: background
                .iter()
                .copied()
                .cycle()
                .take(width as usize * height as usize * 3)
                .collect(),
        }
    }

    /// Mixes `colour` into pixel (x, y) with coverage `a` in [0, 1].
    pub fn blend(&mut self, x: i64, y: i64, colour: Colour, a: f64) {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) || a <= 0.0 {
            return;
        }
        let a = a.min(1.0);
        let i = (y as usize * self.width as usize + x as usize) * 3;
        for (k, c) in colour.iter().enumerate() {
            let old = f64::from(self.rgb[i + k]);
            self.rgb[i + k] = (old + (f64::from(*c) - old) * a).round() as u8;
        }
    }

    /// Sets pixel (x, y).
    pub fn set(&mut self, x: u32, y: u32, colour: Colour) {
        if x < self.width && y < self.height {
            let i = (y as usize * self.width as usize + x as usize) * 3;
            self.rgb[i..i + 3].copy_from_slice(&colour);
        }
    }

    /// Coverage of a shape given by its signed distance `d` (pixels, negative inside).
    fn cover_by_distance(&mut self, bbox: [f64; 4], colour: Colour, d: impl Fn(f64, f64) -> f64) {
        let [x0, y0, x1, y1] = bbox;
        for y in (y0.floor() as i64).max(0)..=(y1.ceil() as i64).min(i64::from(self.height) - 1) {
            for x in (x0.floor() as i64).max(0)..=(x1.ceil() as i64).min(i64::from(self.width) - 1)
            {
                let a = 0.5 - d(x as f64 + 0.5, y as f64 + 0.5);
                self.blend(x, y, colour, a.clamp(0.0, 1.0));
            }
        }
    }

    /// Draws one command.
    pub fn draw(&mut self, cmd: &Cmd) {
        match cmd {
            Cmd::Line {
                points,
                colour,
                width,
            } => {
                // Each segment as a capsule; joins overlap a little, which at these widths
                // only darkens the corner pixel slightly.
                let r = width / 2.0;
                for seg in points.windows(2) {
                    let ((ax, ay), (bx, by)) = (seg[0], seg[1]);
                    let bbox = [
                        ax.min(bx) - r - 1.0,
                        ay.min(by) - r - 1.0,
                        ax.max(bx) + r + 1.0,
                        ay.max(by) + r + 1.0,
                    ];
                    let (dx, dy) = (bx - ax, by - ay);
                    let len2 = (dx * dx + dy * dy).max(1e-12);
                    self.cover_by_distance(bbox, *colour, |px, py| {
                        let t = (((px - ax) * dx + (py - ay) * dy) / len2).clamp(0.0, 1.0);
                        let (qx, qy) = (ax + t * dx - px, ay + t * dy - py);
                        (qx * qx + qy * qy).sqrt() - r
                    });
                }
            }
            Cmd::Disc {
                centre,
                radius,
                colour,
            } => {
                let (cx, cy) = *centre;
                let bbox = [
                    cx - radius - 1.0,
                    cy - radius - 1.0,
                    cx + radius + 1.0,
                    cy + radius + 1.0,
                ];
                self.cover_by_distance(bbox, *colour, |px, py| {
                    ((px - cx).powi(2) + (py - cy).powi(2)).sqrt() - radius
                });
            }
            Cmd::Text {
                at,
                text,
                size,
                anchor,
                vertical,
            } => self.text(*at, text, *size, *anchor, *vertical, [40, 40, 40]),
        }
    }

    /// Draws text with its baseline through `at`.
    pub fn text(
        &mut self,
        at: (f64, f64),
        text: &str,
        size: f64,
        anchor: Anchor,
        vertical: bool,
        colour: Colour,
    ) {
        let Some(font) = FONT.as_ref() else {
            return;
        };
        let scaled = font.as_scaled(PxScale::from(size as f32));
        // Lay out along the baseline from x = 0.
        let mut glyphs = Vec::new();
        let mut x = 0.0f32;
        let mut prev = None;
        for ch in text.chars() {
            let id = scaled.glyph_id(ch);
            if let Some(p) = prev {
                x += scaled.kern(p, id);
            }
            glyphs.push(id.with_scale_and_position(scaled.scale(), ab_glyph::point(x, 0.0)));
            x += scaled.h_advance(id);
            prev = Some(id);
        }
        let shift = f64::from(match anchor {
            Anchor::Start => 0.0,
            Anchor::Middle => x / 2.0,
            Anchor::End => x,
        });
        for g in glyphs {
            let Some(outlined) = font.outline_glyph(g) else {
                continue;
            };
            let b = outlined.px_bounds();
            outlined.draw(|gx, gy, a| {
                // (u, v): position along and across the baseline.
                let u = f64::from(b.min.x) + f64::from(gx) - shift;
                let v = f64::from(b.min.y) + f64::from(gy);
                let (px, py) = if vertical {
                    (at.0 + v, at.1 - u)
                } else {
                    (at.0 + u, at.1 + v)
                };
                self.blend(px.floor() as i64, py.floor() as i64, colour, f64::from(a));
            });
        }
    }
}

/// The (time in ms, RMSE) chart of one scene, one line per mode in order of spp.
#[must_use]
pub fn error_vs_time(rep: &SceneReport) -> LogLogChart {
    let series = table::modes(&rep.rows)
        .into_iter()
        .map(|mode| Series {
            label: mode.name(),
            points: table::curve(&rep.rows, mode)
                .into_iter()
                .map(|(t, e)| (t.as_secs_f64() * 1e3, e))
                .collect(),
        })
        .collect();
    let threads = rep.rows.first().map_or(0, |r| r.threads);
    LogLogChart {
        title: format!(
            "{}: RMSE against render time ({} threads; points at each spp)",
            rep.scene, threads
        ),
        x_label: "render time (ms), median".into(),
        y_label: "RMSE (sRGB) against the reference".into(),
        series,
        y_marks: table::RMSE_TARGETS
            .iter()
            .map(|t| (*t, format!("RMSE {t}")))
            .collect(),
    }
}

/// Height of the colour bar under a heat map, with its labels.
pub const LEGEND_HEIGHT: u32 = 34;

/// The magma colour map as 256 RGB entries (FLIP's own, from `nv-flip`).
#[must_use]
pub fn magma() -> Vec<Colour> {
    nv_flip::magma_lut()
        .to_vec()
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect()
}

/// An error map colour-mapped with magma over [0, 1], with a labelled colour bar underneath:
/// (width, height, RGB bytes).
#[must_use]
pub fn heat_map(map: &ErrorMap) -> (u32, u32, Vec<u8>) {
    let lut = magma();
    let width = map.width.max(200);
    let height = map.height + LEGEND_HEIGHT;
    let mut c = Canvas::new(width, height, [255, 255, 255]);
    let colour = |e: f32| lut[((e.clamp(0.0, 1.0) * 255.0).round() as usize).min(lut.len() - 1)];
    for y in 0..map.height {
        for x in 0..map.width {
            let e = map.error[(y * map.width + x) as usize];
            c.set(x, y, colour(e));
        }
    }
    // The bar: 8 pixels from 0 to 1 across the width, labelled 0, 0.5 and 1.
    let (bar_top, bar_h, margin) = (map.height + 4, 8, 10u32);
    let span = width - 2 * margin;
    for x in 0..span {
        let e = x as f32 / (span - 1).max(1) as f32;
        for y in bar_top..bar_top + bar_h {
            c.set(margin + x, y, colour(e));
        }
    }
    let ty = f64::from(bar_top + bar_h + 14);
    let ink = [40, 40, 40];
    c.text(
        (f64::from(margin), ty),
        "FLIP 0",
        12.0,
        Anchor::Start,
        false,
        ink,
    );
    c.text(
        (f64::from(width) / 2.0, ty),
        "0.5",
        12.0,
        Anchor::Middle,
        false,
        ink,
    );
    c.text(
        (f64::from(width - margin), ty),
        "1",
        12.0,
        Anchor::End,
        false,
        ink,
    );
    (width, height, c.rgb)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decades_cover_the_data() {
        assert_eq!(decades([3.0, 250.0].into_iter()), (0, 3));
        assert_eq!(decades([0.02, 0.05].into_iter()), (-2, -1));
        assert_eq!(decades([10.0].into_iter()), (1, 2));
        assert_eq!(decade_label(-2), "0.01");
        assert_eq!(decade_label(3), "1000");
        assert_eq!(decade_label(-7), "1e-7");
    }

    #[test]
    fn raster_draws_lines_discs_and_text() {
        let mut c = Canvas::new(60, 40, [255, 255, 255]);
        c.draw(&line(vec![(5.0, 10.5), (55.0, 10.5)], [255, 0, 0], 2.0));
        let px = |c: &Canvas, x: usize, y: usize| {
            let i = (y * 60 + x) * 3;
            [c.rgb[i], c.rgb[i + 1], c.rgb[i + 2]]
        };
        assert_eq!(px(&c, 30, 10), [255, 0, 0]);
        assert_eq!(px(&c, 30, 20), [255, 255, 255]);
        c.draw(&Cmd::Disc {
            centre: (30.0, 30.0),
            radius: 3.0,
            colour: [0, 0, 255],
        });
        assert_eq!(px(&c, 30, 30), [0, 0, 255]);
        let before = c.rgb.clone();
        c.text((2.0, 38.0), "Ag", 12.0, Anchor::Start, false, [0, 0, 0]);
        assert_ne!(c.rgb, before, "the font must draw something");
    }

    #[test]
    fn svg_escapes_text_and_draws_every_series() {
        let chart = LogLogChart {
            title: "a <b> & c".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![
                Series {
                    label: "one".into(),
                    points: vec![(1.0, 0.1), (10.0, 0.01)],
                },
                Series {
                    label: "two".into(),
                    points: vec![(2.0, 0.2), (20.0, 0.02)],
                },
            ],
            y_marks: vec![],
        };
        let s = chart.to_svg();
        assert!(s.contains("a &lt;b&gt; &amp; c"));
        assert!(s.contains(">one</text>") && s.contains(">two</text>"));
        assert!(s.contains(&hex(PALETTE[0])) && s.contains(&hex(PALETTE[1])));
        assert_eq!(
            chart.to_rgb().len(),
            (CHART_WIDTH * CHART_HEIGHT * 3) as usize
        );
    }
}
