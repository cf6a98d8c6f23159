//! The report's plots: the log-log chart of RMSE against time drawn by `plotters` (its SVG and
//! bitmap backends; text through `ab_glyph` with egui's bundled Ubuntu Light registered as
//! the sans-serif family, so no system font library is involved, and laid out glyph by glyph
//! in the bitmap, see `Bitmap`), and error heat maps with a colour bar.

#[cfg(feature = "flip")]
use super::ErrorMap;
use super::{SceneReport, table};
use ab_glyph::{Font as _, FontRef, PxScale, ScaleFont as _};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters_backend::{BackendColor, BackendCoord, BackendTextStyle, DrawingErrorKind};
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

/// A plot that could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("cannot draw the plot: {0}")]
pub struct PlotError(String);

/// The font family every text of the plots uses.
const FAMILY: &str = "sans-serif";
/// The colour of text and the frame.
const INK: RGBColor = RGBColor(40, 40, 40);

/// Registers the bundled font as [`FAMILY`] once; the error, if the font cannot be read.
fn font() -> Result<(), PlotError> {
    static REGISTERED: LazyLock<Result<(), String>> = LazyLock::new(|| {
        plotters::style::register_font(
            FAMILY,
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        )
        .map_err(|_| "egui's bundled Ubuntu Light font could not be read".to_owned())
    });
    REGISTERED.clone().map_err(PlotError)
}

fn text_style(size: u32) -> TextStyle<'static> {
    TextStyle::from((FAMILY, size).into_font()).color(&INK)
}

fn rgb(c: Colour) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

static UBUNTU: LazyLock<Option<FontRef<'static>>> =
    LazyLock::new(|| FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).ok());

/// plotters' bitmap backend with the text drawn here: plotters 0.3.7's `ab_glyph` text ignores
/// each glyph's side bearing and rounds every glyph's baseline on its own, so letters wander by
/// a pixel (a colon touches the next word, descenders float). Lines, markers and fills are the
/// bitmap backend's own; the SVG's text is the viewer's.
struct Bitmap<'a>(BitMapBackend<'a>);

type BitmapError = DrawingErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>;

/// `text` laid out along a baseline from x = 0 at `size` pixels: the glyphs and the width.
fn layout(font: &FontRef<'static>, size: f32, text: &str) -> (Vec<ab_glyph::Glyph>, f32) {
    let scaled = font.as_scaled(PxScale::from(size));
    let (mut glyphs, mut x, mut prev) = (Vec::new(), 0.0f32, None);
    for ch in text.chars() {
        let id = scaled.glyph_id(ch);
        if let Some(p) = prev {
            x += scaled.kern(p, id);
        }
        glyphs.push(id.with_scale_and_position(scaled.scale(), ab_glyph::point(x, 0.0)));
        x += scaled.h_advance(id);
        prev = Some(id);
    }
    (glyphs, x)
}

impl DrawingBackend for Bitmap<'_> {
    type ErrorType = <BitMapBackend<'static> as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }
    fn ensure_prepared(&mut self) -> Result<(), BitmapError> {
        self.0.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), BitmapError> {
        self.0.present()
    }
    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Result<(), BitmapError> {
        self.0.draw_pixel(point, color)
    }
    fn draw_line<S: plotters_backend::BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), BitmapError> {
        self.0.draw_line(from, to, style)
    }
    fn draw_rect<S: plotters_backend::BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), BitmapError> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }
    fn draw_path<S: plotters_backend::BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), BitmapError> {
        self.0.draw_path(path, style)
    }
    fn draw_circle<S: plotters_backend::BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), BitmapError> {
        self.0.draw_circle(center, radius, style, fill)
    }
    fn fill_polygon<S: plotters_backend::BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), BitmapError> {
        self.0.fill_polygon(vert, style)
    }
    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), BitmapError> {
        self.0.blit_bitmap(pos, size, src)
    }

    /// The advance width and the line height (ascent to descent).
    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        text: &str,
        style: &T,
    ) -> Result<(u32, u32), BitmapError> {
        let Some(font) = UBUNTU.as_ref() else {
            return self.0.estimate_text_size(text, style);
        };
        let size = style.size() as f32;
        let (_, width) = layout(font, size, text);
        Ok((width.ceil() as u32, size.ceil() as u32))
    }

    /// Each glyph at its own bearing on one baseline, anchored and turned as plotters asks.
    fn draw_text<T: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &T,
        pos: BackendCoord,
    ) -> Result<(), BitmapError> {
        let Some(font) = UBUNTU.as_ref() else {
            return self.0.draw_text(text, style, pos);
        };
        let colour = style.color();
        let size = style.size() as f32;
        let (glyphs, width) = layout(font, size, text);
        let ascent = font.as_scaled(PxScale::from(size)).ascent();
        // The box is `width` x `size` with the baseline `ascent` below its top.
        let dx = match style.anchor().h_pos {
            HPos::Left => 0.0,
            HPos::Center => -width / 2.0,
            HPos::Right => -width,
        };
        let dy = ascent
            + match style.anchor().v_pos {
                VPos::Top => 0.0,
                VPos::Center => -size / 2.0,
                VPos::Bottom => -size,
            };
        let turn = style.transform();
        let (w, h) = self.get_size();
        for g in glyphs {
            let Some(outlined) = font.outline_glyph(g) else {
                continue;
            };
            let b = outlined.px_bounds();
            let mut coverage = Vec::new();
            outlined.draw(|gx, gy, a| coverage.push((gx, gy, a)));
            for (gx, gy, a) in coverage {
                let x = (b.min.x + gx as f32 + dx).floor() as i32;
                let y = (b.min.y + gy as f32 + dy).floor() as i32;
                let (x, y) = turn.transform(x, y);
                let (x, y) = (pos.0 + x, pos.1 + y);
                if a > 0.0 && x >= 0 && y >= 0 && x < w as i32 && y < h as i32 {
                    let c = BackendColor {
                        alpha: colour.alpha * f64::from(a.min(1.0)),
                        rgb: colour.rgb,
                    };
                    self.0.draw_pixel((x, y), c)?;
                }
            }
        }
        Ok(())
    }
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
/// Width of the plot area, left of the legend.
const PLOT_WIDTH: u32 = 760;

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

/// A tick's label: plain decimals with one significant digit's precision for the usual range
/// (`0.003`, `20`, `1000`), `1e-7` style beyond it.
fn tick_label(v: f64) -> String {
    if !(v.is_finite() && v > 0.0) {
        return String::new();
    }
    let k = v.log10().floor() as i32;
    if (-4..=5).contains(&k) {
        let prec = (-k).max(0) as usize;
        format!("{v:.prec$}")
    } else {
        let mantissa = v / 10f64.powi(k);
        if (mantissa - 1.0).abs() < 1e-9 {
            format!("1e{k}")
        } else {
            format!("{mantissa:.0}e{k}")
        }
    }
}

impl LogLogChart {
    /// The points of a series that a log-log plot can show.
    fn visible(s: &Series) -> Vec<(f64, f64)> {
        s.points
            .iter()
            .copied()
            .filter(|p| p.0 > 0.0 && p.1 > 0.0 && p.0.is_finite() && p.1.is_finite())
            .collect()
    }

    /// Draws the chart on `root` ([`CHART_WIDTH`] x [`CHART_HEIGHT`]): the log-log plot on
    /// the left, the legend on the right.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        root.fill(&WHITE)?;
        let (plot_area, legend) = root.split_horizontally(PLOT_WIDTH);
        let all = || self.series.iter().flat_map(Self::visible);
        let (x0, x1) = decades(all().map(|p| p.0));
        let (y0, y1) = decades(all().map(|p| p.1).chain(self.y_marks.iter().map(|m| m.0)));
        // A hair below the lowest decade, so rounding cannot drop its tick and label.
        let (xr, yr) = (
            10f64.powi(x0) * (1.0 - 1e-9)..10f64.powi(x1),
            10f64.powi(y0) * (1.0 - 1e-9)..10f64.powi(y1),
        );
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(
                &self.title,
                text_style(16).pos(Pos::new(HPos::Center, VPos::Top)),
            )
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(xr.clone().log_scale(), yr.log_scale())?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&|v| tick_label(*v))
            .y_label_formatter(&|v| tick_label(*v))
            .label_style(text_style(13))
            .axis_desc_style(text_style(14))
            .bold_line_style(RGBColor(215, 215, 215))
            .light_line_style(RGBColor(242, 242, 242))
            .axis_style(INK)
            .draw()?;
        // The equal-quality targets: grey lines, labelled at the right end.
        let grey = RGBColor(150, 150, 150);
        for (y, label) in &self.y_marks {
            chart.draw_series(LineSeries::new([(xr.start, *y), (xr.end, *y)], grey))?;
            chart.draw_series(std::iter::once(Text::new(
                label.clone(),
                (xr.end, *y),
                text_style(12).pos(Pos::new(HPos::Right, VPos::Bottom)),
            )))?;
        }
        for (i, s) in self.series.iter().enumerate() {
            let colour = rgb(PALETTE[i % PALETTE.len()]);
            let pts = Self::visible(s);
            chart.draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))?;
            chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 4, colour.filled())))?;
        }
        // The legend: a stroke with a dot in the series' colour, then its label.
        let top = 40;
        for (i, s) in self.series.iter().enumerate() {
            let colour = rgb(PALETTE[i % PALETTE.len()]);
            let y = top + 20 * i as i32;
            legend.draw(&PathElement::new(
                [(12, y), (36, y)],
                colour.stroke_width(2),
            ))?;
            legend.draw(&Circle::new((24, y), 4, colour.filled()))?;
            legend.draw(&Text::new(
                s.label.clone(),
                (42, y),
                text_style(13).pos(Pos::new(HPos::Left, VPos::Center)),
            ))?;
        }
        root.present()
    }

    /// The chart as an SVG document.
    ///
    /// # Errors
    /// The bundled font cannot be read, or plotters fails.
    pub fn to_svg(&self) -> Result<String, PlotError> {
        font()?;
        let mut s = String::new();
        {
            let root =
                SVGBackend::with_string(&mut s, (CHART_WIDTH, CHART_HEIGHT)).into_drawing_area();
            self.draw(&root).map_err(|e| PlotError(e.to_string()))?;
        }
        Ok(s)
    }

    /// The chart as RGB pixels, row-major.
    ///
    /// # Errors
    /// The bundled font cannot be read, or plotters fails.
    pub fn to_rgb(&self) -> Result<Vec<u8>, PlotError> {
        font()?;
        let mut rgb = vec![255u8; CHART_WIDTH as usize * CHART_HEIGHT as usize * 3];
        {
            let root = Bitmap(BitMapBackend::with_buffer(
                &mut rgb,
                (CHART_WIDTH, CHART_HEIGHT),
            ))
            .into_drawing_area();
            self.draw(&root).map_err(|e| PlotError(e.to_string()))?;
        }
        Ok(rgb)
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
#[cfg(feature = "flip")]
#[must_use]
pub fn magma() -> Vec<Colour> {
    nv_flip::magma_lut()
        .to_vec()
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect()
}

/// An error map colour-mapped with magma over [0, 1], with a labelled colour bar underneath:
/// (width, height, RGB bytes). The map and the bar are copied texel for texel (a chart
/// library would only resample them); plotters writes the labels.
///
/// # Errors
/// The bundled font cannot be read, or plotters fails.
#[cfg(feature = "flip")]
pub fn heat_map(map: &ErrorMap) -> Result<(u32, u32, Vec<u8>), PlotError> {
    font()?;
    let lut = magma();
    let width = map.width.max(200);
    let height = map.height + LEGEND_HEIGHT;
    let mut rgb = vec![255u8; width as usize * height as usize * 3];
    let mut set = |x: u32, y: u32, c: Colour| {
        let i = (y as usize * width as usize + x as usize) * 3;
        rgb[i..i + 3].copy_from_slice(&c);
    };
    let colour = |e: f32| lut[((e.clamp(0.0, 1.0) * 255.0).round() as usize).min(lut.len() - 1)];
    for y in 0..map.height {
        for x in 0..map.width {
            set(x, y, colour(map.error[(y * map.width + x) as usize]));
        }
    }
    // The bar: 8 pixels from 0 to 1 across the width, labelled 0, 0.5 and 1.
    let (bar_top, bar_h, margin) = (map.height + 4, 8, 10u32);
    let span = width - 2 * margin;
    for x in 0..span {
        let e = x as f32 / (span - 1).max(1) as f32;
        for y in bar_top..bar_top + bar_h {
            set(margin + x, y, colour(e));
        }
    }
    {
        let root =
            Bitmap(BitMapBackend::with_buffer(&mut rgb, (width, height))).into_drawing_area();
        let ty = (bar_top + bar_h + 3) as i32;
        let label = |text: &str, x: u32, h: HPos| {
            root.draw(&Text::new(
                text.to_owned(),
                (x as i32, ty),
                text_style(12).pos(Pos::new(h, VPos::Top)),
            ))
        };
        label("FLIP 0", margin, HPos::Left)
            .and_then(|()| label("0.5", width / 2, HPos::Center))
            .and_then(|()| label("1", width - margin, HPos::Right))
            .and_then(|()| root.present())
            .map_err(|e| PlotError(e.to_string()))?;
    }
    Ok((width, height, rgb))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_series() -> LogLogChart {
        LogLogChart {
            title: "a <b> & c".into(),
            x_label: "time".into(),
            y_label: "error".into(),
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
            y_marks: vec![(0.03, "RMSE 0.03".into())],
        }
    }

    #[test]
    fn decades_cover_the_data_and_ticks_read_plainly() {
        assert_eq!(decades([3.0, 250.0].into_iter()), (0, 3));
        assert_eq!(decades([0.02, 0.05].into_iter()), (-2, -1));
        assert_eq!(decades([10.0].into_iter()), (1, 2));
        assert_eq!(tick_label(0.01), "0.01");
        assert_eq!(tick_label(0.003), "0.003");
        assert_eq!(tick_label(20.0), "20");
        assert_eq!(tick_label(1000.0), "1000");
        assert_eq!(tick_label(1e-7), "1e-7");
        assert_eq!(tick_label(2e-7), "2e-7");
    }

    fn pixel(rgb: &[u8], width: u32, x: u32, y: u32) -> Colour {
        let i = (y as usize * width as usize + x as usize) * 3;
        [rgb[i], rgb[i + 1], rgb[i + 2]]
    }

    #[test]
    fn the_raster_chart_has_a_title_and_a_legend_in_the_series_colours() {
        let rgb = two_series().to_rgb().unwrap();
        assert_eq!(rgb.len(), (CHART_WIDTH * CHART_HEIGHT * 3) as usize);
        let count = |x0: u32, x1: u32, y0: u32, y1: u32, c: Colour| {
            (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| pixel(&rgb, CHART_WIDTH, x, y) == c)
                .count()
        };
        // Each legend entry's stroke is drawn in its series' colour.
        for (i, c) in PALETTE[..2].iter().enumerate() {
            let y = 40 + 20 * i as u32;
            assert!(
                count(PLOT_WIDTH + 12, PLOT_WIDTH + 37, y - 2, y + 3, *c) >= 20,
                "legend entry {i}"
            );
        }
        // Both lines cross the plot area.
        for c in &PALETTE[..2] {
            assert!(count(0, PLOT_WIDTH, 0, CHART_HEIGHT, *c) > 200);
        }
        // The title: dark text in the top band, centred over the plot.
        let dark = (0..30)
            .flat_map(|y| (200..560).map(move |x| (x, y)))
            .filter(|&(x, y)| pixel(&rgb, CHART_WIDTH, x, y).iter().all(|v| *v < 160))
            .count();
        assert!(dark > 50, "{dark} dark pixels in the title band");
    }

    #[test]
    fn the_svg_chart_escapes_text_and_names_every_series() {
        let s = two_series().to_svg().unwrap();
        assert!(s.starts_with("<svg"), "{}", &s[..80.min(s.len())]);
        assert!(s.contains("a &lt;b&gt; &amp; c"), "the title, escaped");
        for text in ["one", "two", "RMSE 0.03", "time", "error", "0.01"] {
            assert!(s.contains(&format!(">\n{text}\n</text>")), "{text}");
        }
        // The lines and legend markers in the first two palette colours.
        for c in &PALETTE[..2] {
            let hex = format!("#{:02X}{:02X}{:02X}", c[0], c[1], c[2]);
            assert!(s.matches(&hex).count() >= 3, "{hex}");
        }
    }

    #[cfg(feature = "flip")]
    #[test]
    fn a_heat_map_is_the_error_in_magma_over_a_labelled_bar() {
        let map = ErrorMap {
            mode: crate::report::Mode::new(
                crate::texture::Filter::Bilinear,
                crate::sampler::PixelSampler::Jittered,
            ),
            spp: 1,
            width: 4,
            height: 2,
            error: vec![0.0, 0.5, 1.0, 2.0, 0.0, 0.0, 0.0, -1.0],
        };
        let (w, h, rgb) = heat_map(&map).unwrap();
        assert_eq!((w, h), (200, 2 + LEGEND_HEIGHT));
        let lut = magma();
        assert_eq!(pixel(&rgb, w, 0, 0), lut[0]);
        assert_eq!(pixel(&rgb, w, 1, 0), lut[128]);
        assert_eq!(pixel(&rgb, w, 2, 0), lut[255]);
        assert_eq!(pixel(&rgb, w, 3, 0), lut[255], "clamped to 1");
        assert_eq!(pixel(&rgb, w, 3, 1), lut[0], "clamped to 0");
        assert_eq!(
            pixel(&rgb, w, 5, 0),
            [255, 255, 255],
            "white beside the map"
        );
        // The bar runs from magma(0) to magma(1).
        assert_eq!(pixel(&rgb, w, 10, 8), lut[0]);
        assert_eq!(pixel(&rgb, w, 189, 8), lut[255]);
        // Its labels are drawn beneath it.
        let dark = (16..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| pixel(&rgb, w, x, y).iter().all(|v| *v < 160))
            .count();
        assert!(dark > 20, "{dark} dark pixels of label text");
    }
}
