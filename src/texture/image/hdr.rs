//! Radiance HDR headers the `image` crate refuses: any `#?` signature (`#?RGBE` as well as
//! `#?RADIANCE`) and all eight orientations of the resolution line (`+Y N +X M`, `+X M -Y N`,
//! ...). The header is rewritten to the form `image` decodes (`#?RADIANCE`, `-Y rows +X
//! columns`), the scanlines are decoded under the same limits as any image, and the pixels are
//! put where the orientation says.

use image::{DynamicImage, ImageDecoder};
use std::io::{BufRead, Read};

/// Most bytes of header (signature, variables and resolution line) read.
const MAX_HEADER_BYTES: u64 = 64 << 10;

/// One axis of the resolution line: `-Y` runs down the image, `+X` to the right.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Axis {
    /// The X axis (else Y).
    x: bool,
    /// `+` (else `-`).
    plus: bool,
}

impl Axis {
    fn parse(tag: &str) -> Option<Self> {
        match tag {
            "+X" => Some(Self {
                x: true,
                plus: true,
            }),
            "-X" => Some(Self {
                x: true,
                plus: false,
            }),
            "+Y" => Some(Self {
                x: false,
                plus: true,
            }),
            "-Y" => Some(Self {
                x: false,
                plus: false,
            }),
            _ => None,
        }
    }

    /// The image coordinate (column for X, row from the top for Y) of index `k` of `n` along
    /// this axis.
    const fn coordinate(self, k: u32, n: u32) -> u32 {
        // +X runs left to right, -Y top to bottom (Y points up in Radiance's pictures).
        if self.plus == self.x { k } else { n - 1 - k }
    }
}

/// Reads one header line (without its newline) within the header's byte budget.
fn line(r: &mut impl BufRead, budget: &mut u64) -> Result<String, String> {
    let mut buf = Vec::new();
    let n = r
        .by_ref()
        .take(*budget)
        .read_until(b'\n', &mut buf)
        .map_err(|e| e.to_string())?;
    *budget -= n as u64;
    if buf.last() != Some(&b'\n') {
        return Err(if *budget == 0 {
            format!("the Radiance header is longer than {MAX_HEADER_BYTES} bytes")
        } else {
            "the Radiance header ends before the resolution line".into()
        });
    }
    buf.pop();
    if buf.last() == Some(&b'\r') {
        buf.pop();
    }
    Ok(String::from_utf8_lossy(&buf).into_owned())
}

/// Decodes a Radiance HDR file whose first bytes are `#?`, once `check` has accepted its width
/// and height (read from the resolution line, before any scanline is decoded); `None` when
/// `check` says to read no further (the header alone was asked for).
///
/// # Errors
/// A malformed header or resolution line, what `check` reports, or what the scanline decoder or
/// the limits report.
pub fn decode_radiance(
    mut r: impl BufRead,
    limits: image::Limits,
    check: &dyn Fn(u32, u32) -> Result<bool, String>,
) -> Result<Option<Radiance>, String> {
    let mut budget = MAX_HEADER_BYTES;
    let signature = line(&mut r, &mut budget)?;
    debug_assert!(signature.starts_with("#?"));
    let mut header = b"#?RADIANCE\n".to_vec();
    loop {
        let l = line(&mut r, &mut budget)?;
        if l.is_empty() {
            break;
        }
        header.extend_from_slice(l.as_bytes());
        header.push(b'\n');
    }
    let resolution = line(&mut r, &mut budget)?;
    let bad = || format!("resolution line '{resolution}' is not like '-Y 512 +X 1024'");
    let words: Vec<&str> = resolution.split_whitespace().collect();
    let [t1, n1, t2, n2] = words[..] else {
        return Err(bad());
    };
    let (Some(a1), Some(a2)) = (Axis::parse(t1), Axis::parse(t2)) else {
        return Err(bad());
    };
    if a1.x == a2.x {
        return Err(bad());
    }
    let (Ok(n1), Ok(n2)) = (n1.parse::<u32>(), n2.parse::<u32>()) else {
        return Err(bad());
    };
    if !check(if a1.x { n1 } else { n2 }, if a1.x { n2 } else { n1 })? {
        return Ok(None);
    }
    header.extend_from_slice(format!("\n-Y {n1} +X {n2}\n").as_bytes());
    let mut decoder = image::codecs::hdr::HdrDecoder::new(std::io::Cursor::new(header).chain(r))
        .map_err(|e| e.to_string())?;
    decoder.set_limits(limits).map_err(|e| e.to_string())?;
    let scan = DynamicImage::from_decoder(decoder)
        .map_err(|e| e.to_string())?
        .into_rgb32f();
    Ok(Some(Radiance {
        scan,
        axes: (a1, a2),
        counts: (n1, n2),
    }))
}

/// A decoded Radiance file: its scanlines as stored, and where each pixel belongs.
#[derive(Debug)]
pub struct Radiance {
    /// The scanlines in file order: row `i` is scanline `i`, column `j` its pixel `j`.
    pub scan: image::Rgb32FImage,
    /// The resolution line's axes, first (along which scanlines follow) and second.
    axes: (Axis, Axis),
    /// The resolution line's counts along the first and second axis.
    counts: (u32, u32),
}

impl Radiance {
    /// Width and height of the image.
    pub const fn size(&self) -> (u32, u32) {
        let ((a1, _), (n1, n2)) = (self.axes, self.counts);
        if a1.x { (n1, n2) } else { (n2, n1) }
    }

    /// Image column and row (from the top) of pixel `j` of scanline `i`.
    pub const fn place(&self, j: u32, i: u32) -> (u32, u32) {
        let ((a1, a2), (n1, n2)) = (self.axes, self.counts);
        let (c1, c2) = (a1.coordinate(i, n1), a2.coordinate(j, n2));
        if a1.x { (c1, c2) } else { (c2, c1) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat (uncompressed) RGBE file of `w` x `h` whose pixel `k` in file order has red `k`.
    fn file(signature: &str, resolution: &str, count: u32) -> Vec<u8> {
        let mut v = format!("{signature}\nFORMAT=32-bit_rle_rgbe\n\n{resolution}\n").into_bytes();
        for k in 0..count {
            // RGBE: mantissa k with exponent 136 (2^(136-136)) is k, exactly.
            v.extend_from_slice(&[k as u8, 0, 0, 136]);
        }
        v
    }

    /// Red of the pixel the file puts at (`x`, `y`).
    fn red(img: &Radiance, x: u32, y: u32) -> f32 {
        let (w, h) = img.size();
        let mut at = None;
        for (j, i, p) in img.scan.enumerate_pixels() {
            if img.place(j, i) == (x, y) {
                assert!(at.is_none(), "two pixels at ({x}, {y})");
                at = Some(p.0[0]);
            }
        }
        assert!(x < w && y < h);
        at.expect("a pixel at every place")
    }

    #[test]
    fn every_orientation_puts_the_first_pixel_where_it_says() {
        // 3 columns x 2 rows. The first pixel in the file sits at the corner the two signs
        // name; the second is one step along the second axis.
        let cases = [
            ("-Y 2 +X 3", (0, 0), (1, 0)),
            ("+Y 2 +X 3", (0, 1), (1, 1)),
            ("-Y 2 -X 3", (2, 0), (1, 0)),
            ("+Y 2 -X 3", (2, 1), (1, 1)),
            ("+X 3 -Y 2", (0, 0), (0, 1)),
            ("+X 3 +Y 2", (0, 1), (0, 0)),
            ("-X 3 -Y 2", (2, 0), (2, 1)),
            ("-X 3 +Y 2", (2, 1), (2, 0)),
        ];
        for (res, first, second) in cases {
            let img = decode_radiance(
                &file("#?RADIANCE", res, 6)[..],
                image::Limits::default(),
                &|_, _| Ok(true),
            )
            .unwrap()
            .expect("decoded");
            assert_eq!(img.size(), (3, 2), "{res}");
            assert_eq!(red(&img, first.0, first.1), 0.0, "{res}");
            assert_eq!(red(&img, second.0, second.1), 1.0, "{res}");
        }
    }

    #[test]
    fn any_signature_is_read() {
        let img = decode_radiance(
            &file("#?RGBE", "-Y 1 +X 2", 2)[..],
            image::Limits::default(),
            &|_, _| Ok(true),
        )
        .unwrap()
        .expect("decoded");
        assert_eq!(red(&img, 1, 0), 1.0);
    }

    #[test]
    fn bad_resolution_lines_are_named() {
        for res in ["-Y 2 -Y 3", "-Y 2", "+Z 2 +X 3", "-Y two +X 3"] {
            let e = decode_radiance(
                &file("#?RADIANCE", res, 6)[..],
                image::Limits::default(),
                &|_, _| Ok(true),
            )
            .unwrap_err();
            assert!(e.contains(res), "{e}");
        }
    }
}
