//! Image storage, decoding with explicit limits, texel fetch, nearest, bilinear and bicubic
//! lookups.

use super::{Lookup, Wrap};
use crate::error::{Error, Result};
use crate::math::{Rgb, Vec2, linear_to_srgb8, srgb_to_linear, srgb8_table};
use std::path::Path;

mod float_tiff;
mod hdr;
mod png_decode;

/// The largest width or height an image may have (decoding refuses anything bigger).
pub const MAX_IMAGE_DIMENSION: u32 = 32_768;
/// The most memory one decoded image may take.
pub const MAX_IMAGE_BYTES: u64 = 1 << 30;

/// Texel storage: 8-bit sRGB images stay compact (4 bytes per texel, decoded through a 256-entry
/// table on lookup); HDR and 16-bit images are kept as linear `f32` (12 bytes per texel).
///
/// [`ImageData::new`] takes texels in file order (row-major, top row first) and stores them in
/// [`TILE`] x [`TILE`] tiles (rows padded to whole tiles), so [`ImageData::texels`] returns the
/// tiled order.
#[derive(Clone, Debug)]
pub enum Texels {
    /// 8-bit sRGB-encoded RGB, padded to 4 bytes for aligned loads.
    Srgb8(Vec<[u8; 4]>),
    /// Linear RGB.
    Linear(Vec<[f32; 3]>),
}

/// Side of the square tiles texels are stored in. A 4 x 4 tile of sRGB texels is one 64-byte
/// cache line, so the texels a lookup needs next (the next pixel's, one row up or down when the
/// surface is tilted in the image, as the Earth's axis is) are usually in a line already fetched;
/// in row-major order nearly every pixel of the tilted Earth missed the cache.
pub const TILE: u32 = 4;

/// Index of texel (`column`, `row`) in tiled storage with `tiles_x` tiles per row.
#[inline]
fn tiled_index(tiles_x: u32, column: u32, row: u32) -> usize {
    let tile = (row / TILE) as usize * tiles_x as usize + (column / TILE) as usize;
    tile * (TILE * TILE) as usize + ((row % TILE) * TILE + column % TILE) as usize
}

/// Row-major texels rearranged into tiles (padding texels are `T::default()`, never read).
fn to_tiles<T: Copy + Default>(width: u32, height: u32, v: &[T]) -> Vec<T> {
    let tiles_x = width.div_ceil(TILE);
    let tiles_y = height.div_ceil(TILE);
    let mut out = vec![T::default(); (tiles_x * tiles_y * TILE * TILE) as usize];
    for (row, line) in v.chunks_exact(width as usize).enumerate() {
        for (column, &t) in line.iter().enumerate() {
            out[tiled_index(tiles_x, column as u32, row as u32)] = t;
        }
    }
    out
}

/// An image in memory. Row 0 is the top row of the file; the lecture's `v` runs up, so
/// `row_from_bottom` is converted once, in [`ImageData::texel`].
#[derive(Clone, Debug)]
pub struct ImageData {
    width: u32,
    height: u32,
    /// Tiles per row of tiles.
    tiles_x: u32,
    texels: Texels,
    /// Where it came from, for the inspector and messages.
    pub name: String,
}

impl ImageData {
    /// An image from texels in file order (top row first).
    ///
    /// # Panics
    /// If the texel count is not `width * height` or a side is zero (a programming error).
    #[must_use]
    pub fn new(width: u32, height: u32, texels: Texels, name: impl Into<String>) -> Self {
        let n = match &texels {
            Texels::Srgb8(v) => v.len(),
            Texels::Linear(v) => v.len(),
        };
        assert!(
            width > 0 && height > 0 && n == width as usize * height as usize,
            "bad image size"
        );
        let texels = match texels {
            Texels::Srgb8(v) => Texels::Srgb8(to_tiles(width, height, &v)),
            Texels::Linear(v) => Texels::Linear(to_tiles(width, height, &v)),
        };
        Self {
            width,
            height,
            tiles_x: width.div_ceil(TILE),
            texels,
            name: name.into(),
        }
    }

    /// A linear-colour image from a closure of (column, row from the top).
    #[must_use]
    pub fn from_fn(width: u32, height: u32, name: &str, f: impl Fn(u32, u32) -> Rgb) -> Self {
        let mut v = Vec::with_capacity(width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                v.push(f(x, y).to_array());
            }
        }
        Self::new(width, height, Texels::Linear(v), name)
    }

    /// Width in texels (the lecture's `hres`).
    #[must_use]
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels (the lecture's `vres`).
    #[must_use]
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// The storage, in tiles (see [`Texels`]).
    #[must_use]
    pub const fn texels(&self) -> &Texels {
        &self.texels
    }

    /// Bytes per texel of the storage.
    #[must_use]
    pub const fn bytes_per_texel(&self) -> usize {
        match self.texels {
            Texels::Srgb8(_) => 4,
            Texels::Linear(_) => 12,
        }
    }

    /// Whether the image holds linear (HDR or 16-bit) values.
    #[must_use]
    pub const fn is_linear(&self) -> bool {
        matches!(self.texels, Texels::Linear(_))
    }

    /// The texel at `column` and `row_from_bottom` (the lecture's row, v up), linear RGB.
    #[must_use]
    #[inline]
    pub fn texel(&self, column: u32, row_from_bottom: u32) -> Rgb {
        let row = self.height - 1 - row_from_bottom;
        self.texel_top(column, row)
    }

    /// The texel at `column` and file row `row` (0 = top), linear RGB.
    #[must_use]
    #[inline]
    pub fn texel_top(&self, column: u32, row: u32) -> Rgb {
        let i = tiled_index(self.tiles_x, column, row);
        match &self.texels {
            Texels::Srgb8(v) => {
                let t = srgb8_table();
                let [r, g, b, _] = v[i];
                Rgb(t[r as usize], t[g as usize], t[b as usize])
            }
            Texels::Linear(v) => Rgb::from_array(v[i]),
        }
    }

    /// The texel (column, row from bottom) a nearest lookup picks, or `None` outside under
    /// [`Wrap::Black`].
    #[must_use]
    #[inline]
    pub fn nearest_index(
        &self,
        uv: Vec2,
        lookup: Lookup,
        wu: Wrap,
        wv: Wrap,
    ) -> Option<(u32, u32)> {
        let u = wu.coord(uv.x)?;
        let v = wv.coord(uv.y)?;
        Some((lookup.index(u, self.width), lookup.index(v, self.height)))
    }

    /// Nearest-texel lookup.
    #[must_use]
    #[inline]
    pub fn nearest(&self, uv: Vec2, lookup: Lookup, wu: Wrap, wv: Wrap) -> Rgb {
        match self.nearest_index(uv, lookup, wu, wv) {
            Some((c, r)) => self.texel(c, r),
            None => Rgb::BLACK,
        }
    }

    /// Bilinear interpolation between the four nearest texel centres, (i + 0.5) / w.
    #[must_use]
    #[inline]
    pub fn bilinear(&self, uv: Vec2, wu: Wrap, wv: Wrap) -> Rgb {
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        if !(x.is_finite() && y.is_finite()) {
            return self.nearest(uv, Lookup::Centred, wu, wv);
        }
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        if x0 >= 0 && y0 >= 0 && x0 + 1 < w && y0 + 1 < h {
            // All four texels inside the image (nearly every lookup): no wrapping.
            let (c, r) = (x0 as u32, y0 as u32);
            let top = self.texel(c, r + 1) * (1.0 - fx) + self.texel(c + 1, r + 1) * fx;
            let bottom = self.texel(c, r) * (1.0 - fx) + self.texel(c + 1, r) * fx;
            return bottom * (1.0 - fy) + top * fy;
        }
        let fetch = |i: i64, j: i64| match (wu.index(i, self.width), wv.index(j, self.height)) {
            (Some(c), Some(r)) => self.texel(c, r),
            _ => Rgb::BLACK,
        };
        let top = fetch(x0, y0 + 1) * (1.0 - fx) + fetch(x0 + 1, y0 + 1) * fx;
        let bottom = fetch(x0, y0) * (1.0 - fx) + fetch(x0 + 1, y0) * fx;
        bottom * (1.0 - fy) + top * fy
    }

    /// Bicubic (Catmull-Rom) interpolation over the 4 x 4 nearest texel centres: sharper than
    /// bilinear when magnified and interpolating (it passes through texel values). Catmull-Rom
    /// can overshoot next to an edge; negative results are clipped to 0.
    #[must_use]
    #[inline]
    pub fn bicubic(&self, uv: Vec2, wu: Wrap, wv: Wrap) -> Rgb {
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        if !(x.is_finite() && y.is_finite()) {
            return self.nearest(uv, Lookup::Centred, wu, wv);
        }
        let (x0, y0) = (x.floor(), y.floor());
        let (wx, wy) = (catmull_rom(x - x0), catmull_rom(y - y0));
        let (x0, y0) = (x0 as i64 - 1, y0 as i64 - 1);
        let mut sum = Rgb::BLACK;
        for (j, wyj) in wy.iter().enumerate() {
            let Some(r) = wv.index(y0 + j as i64, self.height) else {
                continue;
            };
            let mut row = Rgb::BLACK;
            for (i, wxi) in wx.iter().enumerate() {
                if let Some(c) = wu.index(x0 + i as i64, self.width) {
                    row += self.texel(c, r) * *wxi;
                }
            }
            sum += row * *wyj;
        }
        Rgb(sum.0.max(0.0), sum.1.max(0.0), sum.2.max(0.0))
    }

    /// The image encoded as 8-bit sRGB RGB bytes (top row first), for display and PNG.
    #[must_use]
    pub fn to_srgb8(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.width as usize * self.height as usize * 3);
        for row in 0..self.height {
            for col in 0..self.width {
                let c = self.texel_top(col, row);
                for ch in c.to_array() {
                    out.push(linear_to_srgb8(ch));
                }
            }
        }
        out
    }
}

/// Catmull-Rom weights of the four texels around a point at fraction `t` past the second.
#[inline]
fn catmull_rom(t: f32) -> [f32; 4] {
    let t2 = t * t;
    let t3 = t2 * t;
    [
        0.5 * (-t3 + 2.0 * t2 - t),
        0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
        0.5 * (-3.0 * t3 + 4.0 * t2 + t),
        0.5 * (t3 - t2),
    ]
}

/// Decodes an image file (PNG, JPEG, TIFF, PPM/PGM P2/P3/P5/P6 8- and 16-bit, Radiance HDR,
/// OpenEXR) under [`MAX_IMAGE_DIMENSION`] and [`MAX_IMAGE_BYTES`].
///
/// 8-bit images are taken as sRGB-encoded unless `srgb` is false; 16-bit ones are decoded to
/// linear floats through the same curve; float formats are linear already.
///
/// # Errors
/// A missing, truncated, corrupt or oversized file, naming the file.
pub fn load_image(path: &Path, srgb: bool) -> Result<ImageData> {
    let err = |message: String| Error::Image {
        path: path.to_path_buf(),
        message,
    };
    let file = crate::input::open_input(path)?;
    let decoded = decode(std::io::BufReader::new(file), path)?;
    let (w, h) = (decoded.width(), decoded.height());
    if w == 0 || h == 0 {
        return Err(err("the image is empty (0 pixels)".into()));
    }
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    use image::DynamicImage as D;
    let texels = match decoded {
        D::ImageRgb32F(_) | D::ImageRgba32F(_) => {
            let rgb = decoded.to_rgb32f();
            Texels::Linear(rgb.pixels().map(|p| sanitize(p.0)).collect())
        }
        D::ImageLuma16(_) | D::ImageLumaA16(_) | D::ImageRgb16(_) | D::ImageRgba16(_) => {
            let rgb = decoded.to_rgb16();
            let dec = |v: u16| {
                let x = f32::from(v) / 65_535.0;
                if srgb { srgb_to_linear(x) } else { x }
            };
            Texels::Linear(
                rgb.pixels()
                    .map(|p| [dec(p.0[0]), dec(p.0[1]), dec(p.0[2])])
                    .collect(),
            )
        }
        _ => {
            let rgb = decoded.to_rgb8();
            if srgb {
                Texels::Srgb8(
                    rgb.pixels()
                        .map(|p| [p.0[0], p.0[1], p.0[2], 255])
                        .collect(),
                )
            } else {
                let f = |v: u8| f32::from(v) / 255.0;
                Texels::Linear(
                    rgb.pixels()
                        .map(|p| [f(p.0[0]), f(p.0[1]), f(p.0[2])])
                        .collect(),
                )
            }
        }
    };
    Ok(ImageData::new(w, h, texels, name))
}

/// The decode limits every image is read under.
fn limits() -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_DIMENSION);
    limits.max_image_height = Some(MAX_IMAGE_DIMENSION);
    limits.max_alloc = Some(MAX_IMAGE_BYTES);
    limits
}

/// Decodes an opened image file: the format from its first bytes (else from `path`'s
/// extension), Radiance HDR in any of its eight orientations and with any `#?` signature.
fn decode(mut file: std::io::BufReader<std::fs::File>, path: &Path) -> Result<image::DynamicImage> {
    use std::io::BufRead;
    let err = |message: String| Error::Image {
        path: path.to_path_buf(),
        message,
    };
    let head = file.fill_buf().map_err(|e| Error::io(path, e))?;
    if head.starts_with(b"#?") {
        return hdr::decode_radiance(file, limits()).map_err(err);
    }
    let mut reader = image::ImageReader::new(file)
        .with_guessed_format()
        .map_err(|e| Error::io(path, e))?;
    if reader.format().is_none()
        && let Ok(format) = image::ImageFormat::from_path(path)
    {
        reader.set_format(format);
    }
    if reader.format() == Some(image::ImageFormat::Png) {
        return png_decode::decode_png(reader.into_inner(), MAX_IMAGE_DIMENSION, MAX_IMAGE_BYTES)
            .map_err(err);
    }
    if reader.format() == Some(image::ImageFormat::Tiff) {
        let mut file = reader.into_inner();
        if let Some(image) =
            float_tiff::decode_gray_f32(&mut file, MAX_IMAGE_DIMENSION, MAX_IMAGE_BYTES)
                .map_err(err)?
        {
            return Ok(image);
        }
        reader = image::ImageReader::with_format(file, image::ImageFormat::Tiff);
    }
    reader.limits(limits());
    reader.decode().map_err(|e| err(e.to_string()))
}

/// HDR files may hold NaN or Inf (a corrupt RGBE exponent, an EXR with holes): such texels are
/// zeroed so they can never reach the film.
fn sanitize(p: [f32; 3]) -> [f32; 3] {
    p.map(|v| if v.is_finite() && v >= 0.0 { v } else { 0.0 })
}

/// Writes RGB8 pixels as a PNG, with optional text chunks (keyword, text), atomically through
/// [`crate::output::write_atomically`]: a failed save never leaves half a file.
///
/// # Errors
/// The file is refused or cannot be written: "cannot write FILE: reason".
pub fn save_png(
    path: &Path,
    width: u32,
    height: u32,
    rgb: &[u8],
    text: &[(&str, &str)],
) -> Result<()> {
    save_png_checked(path, &[], width, height, rgb, text)
}

/// [`save_png`] that also refuses to write over any of `inputs` (the files the image was made
/// from).
///
/// # Errors
/// The file is refused or cannot be written: "cannot write FILE: reason".
pub fn save_png_checked(
    path: &Path,
    inputs: &[&Path],
    width: u32,
    height: u32,
    rgb: &[u8],
    text: &[(&str, &str)],
) -> Result<()> {
    crate::output::write_atomically(path, inputs, |out| {
        let mut enc = png::Encoder::new(out, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        for (k, t) in text {
            enc.add_itxt_chunk((*k).to_string(), (*t).to_string())
                .map_err(std::io::Error::other)?;
        }
        let mut w = enc.write_header().map_err(std::io::Error::other)?;
        w.write_image_data(rgb).map_err(std::io::Error::other)?;
        w.finish().map_err(std::io::Error::other)
    })
}
