//! Image storage, decoding with explicit limits, texel fetch, nearest, bilinear and bicubic
//! lookups.

use super::{Lookup, Wrap};
use crate::error::{Error, Result};
use crate::math::{Rgb, Vec2, floor_fast, linear_to_srgb8, srgb8_table, unorm8_table};
use std::path::Path;

mod hdr;
mod jpeg;
mod jpeg_other;
#[cfg(not(target_arch = "wasm32"))]
mod openexr;
mod png_decode;
mod storage;
mod tiff;
mod tiff_old;

pub use storage::ImageRequest;
use storage::Storage;

/// The largest width or height an image may have (decoding refuses anything bigger): 2^20, so
/// that an `f32` (u, v) still addresses a sixteenth of a texel. Memory is bounded by
/// [`MAX_IMAGE_BYTES`], not by the sides: a 1 x 100000 strip is fine.
pub const MAX_IMAGE_DIMENSION: u32 = 1 << 20;
/// The texture budget: the most memory one image's texel storage may take (padding to whole
/// tiles included), checked from the header before decoding; also the most one decoder buffer
/// may take. 1 GiB holds a 16384 x 16384 8-bit image as sRGB texels (4 bytes each), the largest
/// texture most GPUs accept and the largest Blue Marble tile, or up to 9459 x 9459 linear RGB
/// (12 bytes each); twice that would not fit beside the renderer on an 8 GiB laptop once the mip
/// pyramid (a third more) and a decoder buffer are added.
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
    /// 8-bit RGB read raw (`v / 255`, an image loaded with `srgb: false`), padded to 4 bytes:
    /// a third of the bytes the same values take as [`Texels::Linear`], so a minified lookup
    /// brings a third of the memory traffic.
    Unorm8(Vec<[u8; 4]>),
    /// Linear RGB.
    Linear(Vec<[f32; 3]>),
}

impl Texels {
    /// 8-bit texels with the table that decodes their bytes to linear values (sRGB or raw), or
    /// `None` for linear floats.
    #[must_use]
    #[inline(always)]
    pub fn bytes(&self) -> Option<(&[[u8; 4]], &'static [f32; 256])> {
        match self {
            Self::Srgb8(v) => Some((v, srgb8_table())),
            Self::Unorm8(v) => Some((v, unorm8_table())),
            Self::Linear(_) => None,
        }
    }
}

/// Side of the square tiles texels are stored in. A 4 x 4 tile of sRGB texels is one 64-byte
/// cache line, so the texels a lookup needs next (the next pixel's, one row up or down when the
/// surface is tilted in the image, as the Earth's axis is) are usually in a line already fetched;
/// in row-major order nearly every pixel of the tilted Earth missed the cache.
pub const TILE: u32 = 4;

/// Index of texel (`column`, `row`) in tiled storage with `tiles_x` tiles per row.
#[inline(always)]
pub(crate) fn tiled_index(tiles_x: u32, column: u32, row: u32) -> usize {
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

/// How the samples of one decoded pixel are laid out in a decoder's output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Layout {
    /// Samples per pixel: 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 (RGBA). Alpha is ignored.
    channels: usize,
    sample: Sample,
}

/// One sample's encoding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sample {
    /// 8 bits.
    U8,
    /// 16 bits, big-endian (as PNG stores them).
    U16Be,
    /// 16 bits, native-endian (as the `image` crate's decoders write them).
    U16Ne,
    /// 32-bit float, native-endian.
    F32Ne,
}

impl Layout {
    /// The layout of an `image` crate colour type (all of them but the non-exhaustive rest).
    fn of(color: image::ColorType) -> Option<Self> {
        use image::ColorType as C;
        let (channels, sample) = match color {
            C::L8 => (1, Sample::U8),
            C::La8 => (2, Sample::U8),
            C::Rgb8 => (3, Sample::U8),
            C::Rgba8 => (4, Sample::U8),
            C::L16 => (1, Sample::U16Ne),
            C::La16 => (2, Sample::U16Ne),
            C::Rgb16 => (3, Sample::U16Ne),
            C::Rgba16 => (4, Sample::U16Ne),
            C::Rgb32F => (3, Sample::F32Ne),
            C::Rgba32F => (4, Sample::F32Ne),
            _ => return None,
        };
        Some(Self { channels, sample })
    }

    /// Bytes one pixel takes.
    const fn bytes_per_pixel(self) -> usize {
        self.channels
            * match self.sample {
                Sample::U8 => 1,
                Sample::U16Be | Sample::U16Ne => 2,
                Sample::F32Ne => 4,
            }
    }
}

/// `bytes` to one decimal, as a person reads it: `1.0 GiB`, `3.0 GiB`, `768.0 MiB`.
#[must_use]
pub fn approx_bytes(bytes: u64) -> String {
    let b = bytes as f64;
    if bytes >= 1 << 30 {
        format!("{:.1} GiB", b / f64::from(1u32 << 30))
    } else if bytes >= 1 << 20 {
        format!("{:.1} MiB", b / f64::from(1u32 << 20))
    } else {
        format!("{bytes} bytes")
    }
}

/// A zeroed vector of `n` elements, or an error (never an abort) when memory runs out.
fn zeroed<T: Clone + Default>(n: usize, what: &str) -> std::result::Result<Vec<T>, String> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| {
        let bytes = n as u64 * std::mem::size_of::<T>() as u64;
        format!(
            "out of memory allocating {} for {what}",
            approx_bytes(bytes)
        )
    })?;
    v.resize(n, T::default());
    Ok(v)
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
    /// The table that decodes 8-bit texels' bytes (`Texels::bytes`'s, looked up once here, not
    /// at every texel).
    table: &'static [f32; 256],
    /// The size of the image a header-only read's 1 x 1 stand-in stands for (its own size
    /// otherwise): what a checked scene counts the image's summed-area tables by.
    full_size: (u32, u32),
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
            Texels::Srgb8(v) | Texels::Unorm8(v) => v.len(),
            Texels::Linear(v) => v.len(),
        };
        assert!(
            width > 0 && height > 0 && n == width as usize * height as usize,
            "bad image size"
        );
        let texels = match texels {
            Texels::Srgb8(v) => Texels::Srgb8(to_tiles(width, height, &v)),
            Texels::Unorm8(v) => Texels::Unorm8(to_tiles(width, height, &v)),
            Texels::Linear(v) => Texels::Linear(to_tiles(width, height, &v)),
        };
        Self {
            width,
            height,
            tiles_x: width.div_ceil(TILE),
            table: texels.bytes().map_or(srgb8_table(), |b| b.1),
            texels,
            full_size: (width, height),
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

    /// The size of the image this one stands for: a header-only read's 1 x 1 stand-in keeps its
    /// file's width and height (see [`ImageRequest::header_only`]); any other image its own.
    #[must_use]
    pub const fn full_size(&self) -> (u32, u32) {
        self.full_size
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

    /// Tiles per row of tiles (for [`tiled_index`]).
    #[must_use]
    pub(crate) const fn tiles_x(&self) -> u32 {
        self.tiles_x
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
            Texels::Srgb8(_) | Texels::Unorm8(_) => 4,
            Texels::Linear(_) => 12,
        }
    }

    /// Bytes the texel storage takes (padding to whole tiles included).
    #[must_use]
    pub fn texels_bytes(&self) -> u64 {
        let n = match &self.texels {
            Texels::Srgb8(v) | Texels::Unorm8(v) => v.len(),
            Texels::Linear(v) => v.len(),
        };
        n as u64 * self.bytes_per_texel() as u64
    }

    /// Bytes the texel storage takes (whole tiles): [`ImageData::texels_bytes`] as a `usize`.
    #[must_use]
    pub fn storage_bytes(&self) -> usize {
        usize::try_from(self.texels_bytes()).unwrap_or(usize::MAX)
    }

    /// Whether the image holds linear floats (HDR, 16-bit and float files, alpha channels, mip
    /// levels of raw 8-bit images), not bytes.
    #[must_use]
    pub const fn is_linear(&self) -> bool {
        matches!(self.texels, Texels::Linear(_))
    }

    /// The texel at `column` and `row_from_bottom` (the lecture's row, v up), linear RGB.
    #[must_use]
    #[inline(always)]
    pub fn texel(&self, column: u32, row_from_bottom: u32) -> Rgb {
        let row = self.height - 1 - row_from_bottom;
        self.texel_top(column, row)
    }

    /// The texel at `column` and file row `row` (0 = top), linear RGB.
    #[must_use]
    #[inline(always)]
    pub fn texel_top(&self, column: u32, row: u32) -> Rgb {
        let i = tiled_index(self.tiles_x, column, row);
        match &self.texels {
            Texels::Srgb8(v) | Texels::Unorm8(v) => {
                let ([r, g, b, _], t) = (v[i], self.table);
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

    /// Bilinear interpolation between the four nearest texel centres, (i + 0.5) / w: the
    /// width-1 instance of [`ImageData::bilinear_lanes`].
    #[must_use]
    #[inline]
    pub fn bilinear(&self, uv: Vec2, wu: Wrap, wv: Wrap) -> Rgb {
        let mut on = [false; crate::math::lanes::MAX_LANES];
        on[0] = true;
        let [r, g, b] = self.bilinear_lanes(pulp::Scalar, uv.x, uv.y, wu, wv, &on);
        Rgb(r, g, b)
    }

    /// Bicubic (Catmull-Rom) interpolation over the 4 x 4 nearest texel centres: sharper than
    /// bilinear when magnified and interpolating (it passes through texel values). Catmull-Rom
    /// can overshoot next to an edge; negative results are clipped to 0.
    #[must_use]
    #[inline]
    pub fn bicubic(&self, uv: Vec2, wu: Wrap, wv: Wrap) -> Rgb {
        let uv = Wrap::reduce_uv(wu, wv, uv);
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        if !(x.is_finite() && y.is_finite()) {
            return self.nearest(uv, Lookup::Centred, wu, wv);
        }
        let (x0, y0) = (floor_fast(x), floor_fast(y));
        let (wx, wy) = (catmull_rom(x - x0), catmull_rom(y - y0));
        let (x0, y0) = (x0 as i64 - 1, y0 as i64 - 1);
        // The four columns wrapped once, not once per row.
        // (A loop, not `std::array::from_fn`, whose body is out of line: see `lanes::map3`.)
        let mut cols = [None; 4];
        for (i, c) in cols.iter_mut().enumerate() {
            *c = wu.index(x0 + i as i64, self.width);
        }
        let mut sum = Rgb::BLACK;
        for (j, wyj) in wy.iter().enumerate() {
            let Some(r) = wv.index(y0 + j as i64, self.height) else {
                continue;
            };
            let mut row = Rgb::BLACK;
            for (c, wxi) in cols.iter().zip(&wx) {
                if let Some(c) = *c {
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
/// `OpenEXR`) under [`MAX_IMAGE_DIMENSION`] and [`MAX_IMAGE_BYTES`].
///
/// The texel storage is sized from the header and refused above [`MAX_IMAGE_BYTES`] before any
/// pixel is decoded; rows are converted straight into it (PNG row by row, other formats from
/// one decoder buffer), so the peak is the storage plus at most one decoder buffer.
///
/// 8-bit images are taken as sRGB-encoded unless `srgb` is false; 16-bit ones are decoded to
/// linear floats through the same curve; float formats are linear already.
///
/// # Errors
/// A missing, truncated, corrupt or oversized file, naming the file.
pub fn load_image(path: &Path, srgb: bool) -> Result<ImageData> {
    let file = crate::input::open_input(path)?;
    Ok(load_opened(file, path, ImageRequest::colour(srgb))?.0)
}

/// Reads the alpha channel of an image file (a PNG with transparency, say) as a grey image:
/// each texel's R, G and B are its alpha in [0, 1] (linear: alpha is a coverage, not a
/// colour). Read as colour images are, under the same budget checked from the header, with
/// the alpha samples converted straight into the storage.
///
/// # Errors
/// The file cannot be read or decoded, or it has no alpha channel.
pub fn load_alpha(path: &Path) -> Result<ImageData> {
    let file = crate::input::open_input(path)?;
    Ok(load_opened(file, path, ImageRequest::alpha())?.0)
}

/// Decodes the opened image `file` (read from `path`) as `req` asks: the image (a 1 x 1
/// stand-in for [`ImageRequest::header_only`]) and the bytes its full storage takes.
///
/// # Errors
/// As [`load_image`]; the storage above `req.max_bytes`.
pub fn load_opened(
    file: crate::input::Input,
    path: &Path,
    req: ImageRequest,
) -> Result<(ImageData, u64)> {
    let storage = decode(std::io::BufReader::new(file), path, req)?;
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let name = if req.alpha {
        format!("{name} (alpha)")
    } else {
        name
    };
    let bytes = storage.bytes;
    Ok((storage.finish(name), bytes))
}

/// The decode limits every image is read under.
fn limits() -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_DIMENSION);
    limits.max_image_height = Some(MAX_IMAGE_DIMENSION);
    limits.max_alloc = Some(MAX_IMAGE_BYTES);
    limits
}

/// Decodes an opened image file into its storage: the format from its first bytes (else from
/// `path`'s extension), Radiance HDR in any of its eight orientations and with any `#?`
/// signature.
fn decode(
    mut file: std::io::BufReader<crate::input::Input>,
    path: &Path,
    req: ImageRequest,
) -> Result<Storage> {
    use std::io::BufRead;
    let err = |message: String| Error::Image {
        path: path.to_path_buf(),
        message,
    };
    let head = file.fill_buf().map_err(|e| Error::io(path, e))?;
    if head.starts_with(b"#?") {
        let size = std::cell::Cell::new((0, 0));
        let check = |w: u32, h: u32| {
            Storage::check(w, h, F32_RGB, req)?;
            size.set((w, h));
            Ok(!req.header_only)
        };
        let Some(img) = hdr::decode_radiance(file, limits(), &check).map_err(err)? else {
            let (w, h) = size.get();
            return Storage::stand_in(w, h, F32_RGB, req).map_err(err);
        };
        return from_radiance(&img, req).map_err(err);
    }
    let mut reader = image::ImageReader::new(file)
        .with_guessed_format()
        .map_err(|e| Error::io(path, e))?;
    if reader.format().is_none()
        && let Ok(format) = image::ImageFormat::from_path(path)
    {
        reader.set_format(format);
    }
    match reader.format() {
        Some(image::ImageFormat::Png) => {
            return png_decode::decode_png(reader.into_inner(), req).map_err(err);
        }
        Some(image::ImageFormat::Jpeg) => {
            return jpeg::decode_jpeg(reader.into_inner(), req).map_err(err);
        }
        Some(image::ImageFormat::Tiff) => {
            return tiff::decode_tiff(reader.into_inner(), req).map_err(err);
        }
        #[cfg(not(target_arch = "wasm32"))]
        Some(image::ImageFormat::OpenExr) => {
            return openexr::decode_exr(reader.into_inner(), req).map_err(err);
        }
        // The page's module leaves OpenEXR out (Cargo.toml: its crate needs relaxed SIMD).
        #[cfg(target_arch = "wasm32")]
        Some(image::ImageFormat::OpenExr) => {
            return Err(err(
                "OpenEXR images are not read in the page (the desktop window reads them)".into(),
            ));
        }
        _ => {}
    }
    reader.limits(limits());
    let decoder = reader.into_decoder().map_err(|e| err(e.to_string()))?;
    from_decoder(decoder, req).map_err(err)
}

/// Linear RGB floats, as Radiance HDR decodes.
const F32_RGB: Layout = Layout {
    channels: 3,
    sample: Sample::F32Ne,
};

/// Storage from an `image` crate decoder: the budget checked from its header, then one decoder
/// buffer converted into the storage.
fn from_decoder(
    decoder: impl image::ImageDecoder,
    req: ImageRequest,
) -> std::result::Result<Storage, String> {
    let (w, h) = decoder.dimensions();
    let color = decoder.color_type();
    let layout = Layout::of(color).ok_or_else(|| format!("unsupported colour type {color:?}"))?;
    let Some(mut storage) = Storage::new(w, h, layout, req)? else {
        return Storage::stand_in(w, h, layout, req);
    };
    let total = decoder.total_bytes();
    if total > MAX_IMAGE_BYTES {
        return Err(format!(
            "the decoder needs {}, above the {} limit",
            approx_bytes(total),
            approx_bytes(MAX_IMAGE_BYTES)
        ));
    }
    let mut buf = zeroed::<u8>(total as usize, "the decoder")?;
    decoder.read_image(&mut buf).map_err(|e| e.to_string())?;
    storage.put_rows(&buf, layout)?;
    Ok(storage)
}

/// Storage from a decoded Radiance file: its scanlines are the rows, or each pixel goes where
/// the file's orientation puts it (no turned copy of the image is made).
fn from_radiance(img: &hdr::Radiance, req: ImageRequest) -> std::result::Result<Storage, String> {
    let (w, h) = img.size();
    let Some(mut storage) = Storage::new(w, h, F32_RGB, req)? else {
        return Storage::stand_in(w, h, F32_RGB, req);
    };
    let Texels::Linear(v) = &mut storage.texels else {
        return Err("Radiance texels are linear".into());
    };
    for (j, i, p) in img.scan.enumerate_pixels() {
        let (x, y) = img.place(j, i);
        v[tiled_index(storage.tiles_x, x, y)] = sanitize(p.0);
    }
    Ok(storage)
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
