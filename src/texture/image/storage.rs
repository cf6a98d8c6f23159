//! The texel storage an image is decoded into ([`Storage`]), and what a caller asks of the
//! decode ([`ImageRequest`]): the colour or the alpha channel, and how many bytes the texels may
//! take (the scene's texture budget left), checked from the header before any pixel is decoded.

use super::{
    ImageData, Layout, MAX_IMAGE_BYTES, MAX_IMAGE_DIMENSION, Sample, TILE, Texels, approx_bytes,
    sanitize, tiled_index, zeroed,
};
use crate::math::{srgb_to_linear, srgb8_table};

/// What to read of an image file, and how much memory its texels may take.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ImageRequest {
    /// Whether 8- and 16-bit samples are sRGB-encoded (almost always).
    pub srgb: bool,
    /// Read the alpha channel as a grey image (a clip map's `Alpha`: each texel's R, G and B
    /// are its alpha in [0, 1], linear) instead of the colour.
    pub alpha: bool,
    /// The most bytes the texel storage may take: what is left of the scene's texture budget
    /// ([`MAX_IMAGE_BYTES`] for an image on its own).
    pub max_bytes: u64,
    /// Read only the header: check the size against the limits and return a 1 x 1 stand-in
    /// (what `lesson --list` checks a scene with, without decoding its images).
    pub header_only: bool,
}

impl ImageRequest {
    /// The colour of an image on its own (the whole texture budget).
    #[must_use]
    pub const fn colour(srgb: bool) -> Self {
        Self {
            srgb,
            alpha: false,
            max_bytes: MAX_IMAGE_BYTES,
            header_only: false,
        }
    }

    /// The alpha channel of an image on its own.
    #[must_use]
    pub const fn alpha() -> Self {
        Self {
            srgb: false,
            alpha: true,
            max_bytes: MAX_IMAGE_BYTES,
            header_only: false,
        }
    }

    /// Whether samples in `layout` are stored as linear floats (alpha, and all but 8-bit
    /// colour, which keeps its bytes, sRGB or raw).
    fn linear(self, layout: Layout) -> bool {
        self.alpha || layout.sample != Sample::U8
    }
}

/// The final texel storage of an image being decoded. It is sized from the header and checked
/// against [`MAX_IMAGE_BYTES`] before any pixel is decoded, allocated once, and filled in tiled
/// order as the decoder delivers rows, so no row-major copy of the texels ever exists.
pub(super) struct Storage {
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) tiles_x: u32,
    /// 8- and 16-bit samples are sRGB-encoded.
    srgb: bool,
    /// The texels are the alpha channel.
    alpha: bool,
    pub(super) texels: Texels,
    /// The bytes the image's storage takes, checked from its header (a header-only stand-in
    /// keeps the full image's).
    pub(super) bytes: u64,
    /// The full image's width and height (a stand-in's differ from its own).
    full_size: (u32, u32),
}

impl Storage {
    /// Bytes the tiled storage of a `width` x `height` image takes (rows and columns padded to
    /// whole tiles), linear or sRGB.
    fn bytes(width: u32, height: u32, linear: bool) -> u64 {
        let texels = u64::from(width.div_ceil(TILE))
            * u64::from(height.div_ceil(TILE))
            * u64::from(TILE * TILE);
        texels * if linear { 12 } else { 4 }
    }

    /// Checks a `width` x `height` image whose decoder writes `layout` against
    /// [`MAX_IMAGE_DIMENSION`], [`MAX_IMAGE_BYTES`] and what `req` leaves of the budget; the
    /// bytes its storage takes.
    ///
    /// # Errors
    /// An empty image, a side above the limit, storage above the budget, or no alpha channel
    /// when `req` asks for it.
    pub(super) fn check(
        width: u32,
        height: u32,
        layout: Layout,
        req: ImageRequest,
    ) -> std::result::Result<u64, String> {
        if width == 0 || height == 0 {
            return Err("the image is empty (0 pixels)".into());
        }
        if width > MAX_IMAGE_DIMENSION || height > MAX_IMAGE_DIMENSION {
            return Err(format!(
                "{width} x {height} pixels is more than {MAX_IMAGE_DIMENSION} per side"
            ));
        }
        if req.alpha && layout.channels % 2 == 1 {
            return Err(
                "has no alpha channel (a clip map's Alpha channel needs one, e.g. an RGBA PNG)"
                    .into(),
            );
        }
        let linear = req.linear(layout);
        let bytes = Self::bytes(width, height, linear);
        let kind = match (req.alpha, linear) {
            (true, _) => "as a linear alpha channel (12 bytes a texel)",
            (false, true) => "as linear RGB (12 bytes a texel)",
            (false, false) if req.srgb => "as sRGB (4 bytes a texel)",
            (false, false) => "as raw 8-bit RGB (4 bytes a texel)",
        };
        if bytes > MAX_IMAGE_BYTES {
            return Err(format!(
                "{width} x {height} texels need {} {kind}, above the {} texture budget",
                approx_bytes(bytes),
                approx_bytes(MAX_IMAGE_BYTES)
            ));
        }
        if bytes > req.max_bytes {
            let left = req.max_bytes.min(MAX_IMAGE_BYTES);
            return Err(format!(
                "{width} x {height} texels need {} {kind}, above the {} left of the scene's {} \
                 texture budget (its other images take {})",
                approx_bytes(bytes),
                approx_bytes(left),
                approx_bytes(MAX_IMAGE_BYTES),
                approx_bytes(MAX_IMAGE_BYTES - left)
            ));
        }
        Ok(bytes)
    }

    /// Storage for a `width` x `height` image whose decoder writes `layout`, allocated after
    /// [`Storage::check`]; `None` when `req` asks for the header only (the size passed).
    ///
    /// # Errors
    /// What [`Storage::check`] reports, or the allocation fails.
    pub(super) fn new(
        width: u32,
        height: u32,
        layout: Layout,
        req: ImageRequest,
    ) -> std::result::Result<Option<Self>, String> {
        let bytes = Self::check(width, height, layout, req)?;
        if req.header_only {
            return Ok(None);
        }
        let linear = req.linear(layout);
        let n = usize::try_from(bytes / if linear { 12 } else { 4 })
            .map_err(|_| "the image does not fit in memory".to_string())?;
        let texels = if linear {
            Texels::Linear(zeroed(n, "the texels")?)
        } else if req.srgb {
            Texels::Srgb8(zeroed(n, "the texels")?)
        } else {
            Texels::Unorm8(zeroed(n, "the texels")?)
        };
        Ok(Some(Self {
            width,
            height,
            tiles_x: width.div_ceil(TILE),
            srgb: req.srgb,
            alpha: req.alpha,
            texels,
            bytes,
            full_size: (width, height),
        }))
    }

    /// The 1 x 1 grey stand-in of a `width` x `height` image whose header alone was read
    /// ([`ImageRequest::header_only`]): it keeps the bytes the image would take.
    pub(super) fn stand_in(
        width: u32,
        height: u32,
        layout: Layout,
        req: ImageRequest,
    ) -> std::result::Result<Self, String> {
        let bytes = Self::check(width, height, layout, req)?;
        let tile = (TILE * TILE) as usize;
        Ok(Self {
            width: 1,
            height: 1,
            tiles_x: 1,
            srgb: req.srgb,
            alpha: req.alpha,
            texels: Texels::Linear(vec![[0.5; 3]; tile]),
            bytes,
            full_size: (width, height),
        })
    }

    /// Converts file row `row` of the alpha channel (the last sample of each pixel) into
    /// grey linear texels in [0, 1].
    fn put_alpha_row(&mut self, row: u32, data: &[u8], layout: Layout) {
        let Texels::Linear(v) = &mut self.texels else {
            return;
        };
        let bpp = layout.bytes_per_pixel();
        let a = layout.channels - 1;
        let data = &data[..data.len().min(self.width as usize * bpp)];
        for (column, px) in data.chunks_exact(bpp).enumerate() {
            let alpha = match layout.sample {
                Sample::U8 => f32::from(px[a]) / 255.0,
                Sample::U16Be => {
                    f32::from(u16::from_be_bytes([px[2 * a], px[2 * a + 1]])) / 65_535.0
                }
                Sample::U16Ne => {
                    f32::from(u16::from_ne_bytes([px[2 * a], px[2 * a + 1]])) / 65_535.0
                }
                Sample::F32Ne => {
                    let f = f32::from_ne_bytes([
                        px[4 * a],
                        px[4 * a + 1],
                        px[4 * a + 2],
                        px[4 * a + 3],
                    ]);
                    if f.is_nan() { 0.0 } else { f.clamp(0.0, 1.0) }
                }
            };
            v[tiled_index(self.tiles_x, column as u32, row)] = [alpha; 3];
        }
    }

    /// Converts file row `row` (0 = top), in `layout`, into its texels. Grey becomes RGB, alpha
    /// is dropped (or is all that is kept, see [`ImageRequest::alpha`]), 8-bit samples keep their
    /// bytes (sRGB-encoded, or raw `v / 255` when not sRGB),
    /// 16-bit ones become linear through the sRGB curve (unless not sRGB), floats are
    /// [sanitized](sanitize). Bytes past the row's width are ignored.
    pub(super) fn put_row(&mut self, row: u32, data: &[u8], layout: Layout) {
        /// Writes `f` of each pixel of the row into its tiles, four texels (one tile's row) at
        /// a time.
        fn fill<T>(
            v: &mut [T],
            tiles_x: u32,
            width: u32,
            row: u32,
            data: &[u8],
            bpp: usize,
            f: impl Fn(&[u8]) -> T,
        ) {
            let data = &data[..data.len().min(width as usize * bpp)];
            let tile = (TILE * TILE) as usize;
            let first = tiled_index(tiles_x, 0, row);
            let tiles = v[first..].chunks_mut(tile);
            for (texels, pixels) in tiles.zip(data.chunks(TILE as usize * bpp)) {
                for (t, px) in texels.iter_mut().zip(pixels.chunks_exact(bpp)) {
                    *t = f(px);
                }
            }
        }
        if self.alpha {
            self.put_alpha_row(row, data, layout);
            return;
        }
        let (tiles_x, width, srgb) = (self.tiles_x, self.width, self.srgb);
        let bpp = layout.bytes_per_pixel();
        let grey = layout.channels < 3;
        let u8_linear = |v: u8| f32::from(v) / 255.0;
        let u16_linear = |v: u16| {
            let x = f32::from(v) / 65_535.0;
            if srgb { srgb_to_linear(x) } else { x }
        };
        let be = |p: &[u8], c: usize| u16::from_be_bytes([p[2 * c], p[2 * c + 1]]);
        let ne = |p: &[u8], c: usize| u16::from_ne_bytes([p[2 * c], p[2 * c + 1]]);
        let f32_at = |p: &[u8], c: usize| {
            f32::from_ne_bytes([p[4 * c], p[4 * c + 1], p[4 * c + 2], p[4 * c + 3]])
        };
        match (&mut self.texels, layout.sample, grey) {
            (Texels::Srgb8(v) | Texels::Unorm8(v), _, true) => {
                fill(v, tiles_x, width, row, data, bpp, |p| {
                    [p[0], p[0], p[0], 255]
                });
            }
            (Texels::Srgb8(v) | Texels::Unorm8(v), _, false) => {
                fill(v, tiles_x, width, row, data, bpp, |p| {
                    [p[0], p[1], p[2], 255]
                });
            }
            (Texels::Linear(v), Sample::U8, true) => {
                fill(v, tiles_x, width, row, data, bpp, |p| [u8_linear(p[0]); 3]);
            }
            (Texels::Linear(v), Sample::U8, false) => {
                fill(v, tiles_x, width, row, data, bpp, |p| {
                    [u8_linear(p[0]), u8_linear(p[1]), u8_linear(p[2])]
                });
            }
            (Texels::Linear(v), Sample::U16Be, true) => {
                fill(v, tiles_x, width, row, data, bpp, |p| {
                    [u16_linear(be(p, 0)); 3]
                });
            }
            (Texels::Linear(v), Sample::U16Be, false) => {
                fill(v, tiles_x, width, row, data, bpp, |p| {
                    [0, 1, 2].map(|c| u16_linear(be(p, c)))
                });
            }
            (Texels::Linear(v), Sample::U16Ne, true) => {
                fill(v, tiles_x, width, row, data, bpp, |p| {
                    [u16_linear(ne(p, 0)); 3]
                });
            }
            (Texels::Linear(v), Sample::U16Ne, false) => {
                fill(v, tiles_x, width, row, data, bpp, |p| {
                    [0, 1, 2].map(|c| u16_linear(ne(p, c)))
                });
            }
            (Texels::Linear(v), Sample::F32Ne, true) => {
                fill(v, tiles_x, width, row, data, bpp, |p| {
                    sanitize([f32_at(p, 0); 3])
                });
            }
            (Texels::Linear(v), Sample::F32Ne, false) => {
                fill(v, tiles_x, width, row, data, bpp, |p| {
                    sanitize([0, 1, 2].map(|c| f32_at(p, c)))
                });
            }
        }
    }

    /// Converts a whole decoded image (rows top to bottom, in `layout`).
    ///
    /// # Errors
    /// `data` holds fewer rows than the image has.
    pub(super) fn put_rows(
        &mut self,
        data: &[u8],
        layout: Layout,
    ) -> std::result::Result<(), String> {
        let stride = self.width as usize * layout.bytes_per_pixel();
        if data.len() < stride * self.height as usize {
            return Err("truncated image data".into());
        }
        for (row, line) in data
            .chunks_exact(stride)
            .take(self.height as usize)
            .enumerate()
        {
            self.put_row(row as u32, line, layout);
        }
        Ok(())
    }

    /// The image, named `name`.
    pub(super) fn finish(self, name: String) -> ImageData {
        ImageData {
            width: self.width,
            height: self.height,
            tiles_x: self.tiles_x,
            table: self.texels.bytes().map_or(srgb8_table(), |b| b.1),
            texels: self.texels,
            full_size: self.full_size,
            name,
        }
    }
}
