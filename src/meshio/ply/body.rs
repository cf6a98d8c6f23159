//! The PLY body's two encodings, read one value at a time: whitespace-separated text and packed
//! binary in either byte order, each saying where it is for error messages.

use super::Scalar;
use std::io::BufRead;

/// Where reading is in the body: a line of an ascii file, a byte of a binary one (from the
/// file's start).
#[derive(Clone, Copy, Debug)]
pub(super) enum At {
    Line(usize),
    Byte(u64),
}

impl std::fmt::Display for At {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Line(n) => write!(f, "line {n}"),
            Self::Byte(n) => write!(f, "byte {n}"),
        }
    }
}

/// A body encoding: values one at a time.
pub(super) trait Body {
    /// Where the next value starts (after a failed read: where it failed).
    fn at(&self) -> At;
    /// One value of type `ty` (integers are exact in f64).
    fn read(&mut self, r: &mut impl BufRead, ty: Scalar) -> std::result::Result<f64, String>;
}

const TRUNCATED: &str = "the file ends early (truncated?)";

/// Whitespace-separated text, any number of values per line.
pub(super) struct AsciiBody {
    line: String,
    pos: usize,
    line_no: usize,
}

impl AsciiBody {
    /// A body whose first line follows `header_lines` header lines.
    pub(super) const fn new(header_lines: usize) -> Self {
        Self {
            line: String::new(),
            pos: 0,
            line_no: header_lines,
        }
    }

    /// The next whitespace-separated token, as a range of `self.line`.
    fn token(&mut self, r: &mut impl BufRead) -> std::result::Result<(usize, usize), String> {
        loop {
            let bytes = self.line.as_bytes();
            let mut s = self.pos;
            while s < bytes.len() && bytes[s].is_ascii_whitespace() {
                s += 1;
            }
            if s < bytes.len() {
                let mut e = s;
                while e < bytes.len() && !bytes[e].is_ascii_whitespace() {
                    e += 1;
                }
                self.pos = e;
                return Ok((s, e));
            }
            self.line.clear();
            self.pos = 0;
            let n = r.read_line(&mut self.line).map_err(|e| {
                if e.kind() == std::io::ErrorKind::InvalidData {
                    "the line is not text".to_string()
                } else {
                    e.to_string()
                }
            })?;
            if n == 0 {
                return Err(TRUNCATED.into());
            }
            self.line_no += 1;
        }
    }
}

impl Body for AsciiBody {
    fn at(&self) -> At {
        At::Line(self.line_no)
    }

    #[inline]
    fn read(&mut self, r: &mut impl BufRead, ty: Scalar) -> std::result::Result<f64, String> {
        let (s, e) = self.token(r)?;
        let tok = &self.line[s..e];
        if ty.is_int() {
            let v = tok
                .parse::<i64>()
                .map_err(|_| format!("expected an integer, found '{tok}'"))?;
            let (lo, hi) = ty.int_range();
            if !(lo..=hi).contains(&v) {
                return Err(format!(
                    "{v} does not fit the header's {} ({lo} to {hi})",
                    ty.name()
                ));
            }
            Ok(v as f64)
        } else {
            tok.parse::<f64>()
                .map_err(|_| format!("expected a number, found '{tok}'"))
        }
    }
}

/// Packed binary values, big-endian when `BIG`.
pub(super) struct BinaryBody<const BIG: bool> {
    offset: u64,
}

impl<const BIG: bool> BinaryBody<BIG> {
    /// A body that starts `header_bytes` into the file.
    pub(super) const fn new(header_bytes: u64) -> Self {
        Self {
            offset: header_bytes,
        }
    }
}

/// `from_be_bytes` or `from_le_bytes` of a scalar type, chosen at compile time.
macro_rules! from_bytes {
    ($t:ty, $big:expr, $b:expr) => {{
        let a = $b[..size_of::<$t>()]
            .try_into()
            .expect("a slice of the type's size");
        if $big {
            <$t>::from_be_bytes(a)
        } else {
            <$t>::from_le_bytes(a)
        }
    }};
}

impl<const BIG: bool> Body for BinaryBody<BIG> {
    fn at(&self) -> At {
        At::Byte(self.offset)
    }

    #[inline]
    fn read(&mut self, r: &mut impl BufRead, ty: Scalar) -> std::result::Result<f64, String> {
        let mut b = [0u8; 8];
        let n = ty.size();
        r.read_exact(&mut b[..n]).map_err(|e| {
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                TRUNCATED.to_string()
            } else {
                e.to_string()
            }
        })?;
        self.offset += n as u64;
        Ok(match ty {
            Scalar::I8 => f64::from(b[0] as i8),
            Scalar::U8 => f64::from(b[0]),
            Scalar::I16 => f64::from(from_bytes!(i16, BIG, b)),
            Scalar::U16 => f64::from(from_bytes!(u16, BIG, b)),
            Scalar::I32 => f64::from(from_bytes!(i32, BIG, b)),
            Scalar::U32 => f64::from(from_bytes!(u32, BIG, b)),
            Scalar::F32 => f64::from(from_bytes!(f32, BIG, b)),
            Scalar::F64 => from_bytes!(f64, BIG, b),
        })
    }
}
