//! A streaming PLY reader (ascii, binary little- and big-endian) and writer.
//!
//! Reads vertex `x y z`, texture coordinates under any of the names in use (`u v`, `s t`,
//! `texture_u texture_v`, `texture_s texture_t`), optional `nx ny nz`, and faces as
//! `list <int type> <int type> vertex_indices` (or `vertex_index`); polygons are triangulated as
//! fans, not truncated. Comments, `obj_info`, other elements and other properties are skipped.
//! The file is read once, element by element: memory is what the mesh needs, and a count in the
//! header is never trusted for an allocation. Errors name the file, the line (ascii) or byte
//! (binary) and the element where reading stopped.

use super::{MAX_POLYGON_CORNERS, MAX_TRIANGLES, MAX_VERTICES};
use crate::error::{Error, Result};
use crate::geometry::MeshData;
use crate::math::{Vec2, Vec3};
use crate::names::Named as _;
use std::io::{BufRead, Read, Write};
use std::path::Path;

mod body;
use body::{AsciiBody, At, BinaryBody, Body};

/// Largest header accepted, in bytes.
pub const MAX_HEADER_BYTES: usize = 1 << 16;
/// The (u, v) property names accepted, in order of preference.
pub const UV_NAMES: [(&str, &str); 4] = [
    ("u", "v"),
    ("s", "t"),
    ("texture_u", "texture_v"),
    ("texture_s", "texture_t"),
];

/// The body encodings a PLY header's `format` line names, spelt as there (`ascii`,
/// `binary_little_endian`, `binary_big_endian`); [`read_ply`] reads all three and
/// [`write_ply`] writes any.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
#[strum(serialize_all = "snake_case")]
pub enum PlyFormat {
    /// Numbers as decimal text, one element per line.
    #[strum(message = "Text: one element per line.")]
    Ascii,
    /// Binary, little-endian.
    #[strum(message = "Binary, little-endian.")]
    BinaryLittleEndian,
    /// Binary, big-endian.
    #[strum(message = "Binary, big-endian.")]
    BinaryBigEndian,
}

impl crate::names::Named for PlyFormat {
    const WHAT: &'static str = "PLY format";
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "char" | "int8" => Self::I8,
            "uchar" | "uint8" => Self::U8,
            "short" | "int16" => Self::I16,
            "ushort" | "uint16" => Self::U16,
            "int" | "int32" => Self::I32,
            "uint" | "uint32" => Self::U32,
            "float" | "float32" => Self::F32,
            "double" | "float64" => Self::F64,
            _ => return None,
        })
    }

    const fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }

    const fn is_int(self) -> bool {
        !matches!(self, Self::F32 | Self::F64)
    }

    /// The values an integer type holds (a binary file cannot hold others; an ASCII one can
    /// write them, and is refused).
    const fn int_range(self) -> (i64, i64) {
        match self {
            Self::I8 => (i8::MIN as i64, i8::MAX as i64),
            Self::U8 => (0, u8::MAX as i64),
            Self::I16 => (i16::MIN as i64, i16::MAX as i64),
            Self::U16 => (0, u16::MAX as i64),
            Self::I32 => (i32::MIN as i64, i32::MAX as i64),
            Self::U32 => (0, u32::MAX as i64),
            Self::F32 | Self::F64 => (i64::MIN, i64::MAX),
        }
    }

    /// The type's name as a header writes it.
    const fn name(self) -> &'static str {
        match self {
            Self::I8 => "char",
            Self::U8 => "uchar",
            Self::I16 => "short",
            Self::U16 => "ushort",
            Self::I32 => "int",
            Self::U32 => "uint",
            Self::F32 => "float",
            Self::F64 => "double",
        }
    }
}

#[derive(Clone, Debug)]
enum Property {
    Scalar {
        name: String,
        ty: Scalar,
    },
    List {
        name: String,
        count: Scalar,
        item: Scalar,
    },
}

impl Property {
    fn name(&self) -> &str {
        match self {
            Self::Scalar { name, .. } | Self::List { name, .. } => name,
        }
    }
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: u64,
    props: Vec<Property>,
    line: usize,
}

/// Where each vertex property goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Slot {
    Pos(usize),
    Uv(usize),
    Normal(usize),
    Skip,
}

struct Header {
    format: PlyFormat,
    elements: Vec<Element>,
    /// Header lines (ascii line numbers continue from here).
    lines: usize,
    /// Header bytes (binary offsets count from the file's start).
    bytes: u64,
}

/// Reads a PLY file.
///
/// # Errors
/// The file cannot be read, or is not a PLY this reader understands; the message names the
/// file, the line or byte, and the element.
pub fn read_ply(path: &Path) -> Result<MeshData> {
    let file = crate::input::open_input(path)?;
    let mut r = std::io::BufReader::with_capacity(1 << 16, file);
    read_ply_from(&mut r, path)
}

/// Reads a PLY from `r`; `path` names it in errors.
///
/// # Errors
/// See [`read_ply`].
pub fn read_ply_from(r: &mut impl BufRead, path: &Path) -> Result<MeshData> {
    let header = read_header(r, path)?;
    let layout = Layout::new(&header, path)?;
    match header.format {
        PlyFormat::Ascii => read_body(r, &header, &layout, AsciiBody::new(header.lines), path),
        PlyFormat::BinaryLittleEndian => read_body(
            r,
            &header,
            &layout,
            BinaryBody::<false>::new(header.bytes),
            path,
        ),
        PlyFormat::BinaryBigEndian => read_body(
            r,
            &header,
            &layout,
            BinaryBody::<true>::new(header.bytes),
            path,
        ),
    }
}

/// What the reader takes from the header: the vertex and face elements, where each vertex
/// property goes and which list holds the face's vertex indices.
struct Layout {
    /// Index of the vertex element in `Header::elements`.
    vertex: usize,
    /// Per vertex property, where its value goes.
    slots: Vec<Slot>,
    /// The (u, v) property names found, if any.
    uv_names: Option<(&'static str, &'static str)>,
    has_normals: bool,
    n_vertices: u64,
    /// Index of the face element in `Header::elements`.
    face: usize,
    /// Index of the face's vertex index list among its properties.
    face_list: usize,
}

impl Layout {
    fn new(header: &Header, path: &Path) -> Result<Self> {
        let fail = |at: String, message: String| Error::Mesh {
            path: path.to_path_buf(),
            at,
            message,
        };
        let find_element = |name: &str| header.elements.iter().position(|e| e.name == name);
        let vertex = find_element("vertex")
            .ok_or_else(|| fail("header".into(), "no 'vertex' element".into()))?;
        let vertex_el = &header.elements[vertex];
        let find = |name: &str| {
            vertex_el
                .props
                .iter()
                .position(|p| matches!(p, Property::Scalar { name: n, .. } if n == name))
        };
        let mut slots = vec![Slot::Skip; vertex_el.props.len()];
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let i = find(axis).ok_or_else(|| {
                fail(
                    format!("header line {}", vertex_el.line),
                    format!("the vertex element has no '{axis}' property"),
                )
            })?;
            slots[i] = Slot::Pos(k);
        }
        let uv = UV_NAMES
            .iter()
            .find_map(|&(u, v)| Some(((find(u)?, find(v)?), (u, v))));
        if let Some(((iu, iv), _)) = uv {
            slots[iu] = Slot::Uv(0);
            slots[iv] = Slot::Uv(1);
        }
        let normal_idx = [find("nx"), find("ny"), find("nz")];
        let has_normals = normal_idx.iter().all(Option::is_some);
        if has_normals {
            for (k, i) in normal_idx.iter().flatten().enumerate() {
                slots[*i] = Slot::Normal(k);
            }
        }
        let n_vertices = vertex_el.count;
        if n_vertices > MAX_VERTICES as u64 {
            return Err(fail(
                format!("header line {}", vertex_el.line),
                format!("{n_vertices} vertices is more than texplore reads ({MAX_VERTICES})"),
            ));
        }
        let face = find_element("face")
            .ok_or_else(|| fail("header".into(), "no 'face' element (a point cloud?)".into()))?;
        let face_el = &header.elements[face];
        let face_list = face_el
            .props
            .iter()
            .position(|p| {
                matches!(p, Property::List { name, .. } if name == "vertex_indices" || name == "vertex_index")
            })
            .ok_or_else(|| {
                fail(
                    format!("header line {}", face_el.line),
                    "the face element has no 'vertex_indices' (or 'vertex_index') list".into(),
                )
            })?;
        if let Property::List { item, .. } = &face_el.props[face_list]
            && !item.is_int()
        {
            return Err(fail(
                format!("header line {}", face_el.line),
                "vertex indices must be an integer type".into(),
            ));
        }
        if face_el.count > MAX_TRIANGLES as u64 {
            return Err(fail(
                format!("header line {}", face_el.line),
                format!(
                    "{} faces is more than texplore reads ({MAX_TRIANGLES})",
                    face_el.count
                ),
            ));
        }
        Ok(Self {
            vertex,
            slots,
            uv_names: uv.map(|(_, names)| names),
            has_normals,
            n_vertices,
            face,
            face_list,
        })
    }
}

/// Reads every element of the body, in the header's order, through `body`'s encoding (one
/// copy of this function per encoding, so the per-value read is not a dispatch).
fn read_body<B: Body, R: BufRead>(
    r: &mut R,
    header: &Header,
    layout: &Layout,
    mut body: B,
    path: &Path,
) -> Result<MeshData> {
    let fail = |at: String, message: String| Error::Mesh {
        path: path.to_path_buf(),
        at,
        message,
    };
    let mut data = MeshData {
        format: format!("ply {}", header.format.name()),
        uv_names: layout.uv_names.map(|(u, v)| (u.to_string(), v.to_string())),
        ..MeshData::default()
    };
    let n_vertices = layout.n_vertices;
    // Never reserve from the header's word alone: a lying count must not allocate.
    let reserve = |n: u64| (n as usize).min(1 << 20);
    data.positions.reserve(reserve(n_vertices));
    if layout.uv_names.is_some() {
        data.uvs.reserve(reserve(n_vertices));
    }
    if layout.has_normals {
        data.normals.reserve(reserve(n_vertices));
    }
    data.triangles
        .reserve(reserve(header.elements[layout.face].count));

    let mut corners: Vec<u32> = Vec::with_capacity(16);
    for (e, el) in header.elements.iter().enumerate() {
        let is_vertex = e == layout.vertex;
        let is_face = e == layout.face;
        if el.props.is_empty() {
            // Its items take no bytes: nothing to read, however many the header claims (a loop
            // over them would read nothing per item and, for a count of 2^64 - 1, never end).
            // Every other item reads at least one value, so each pass below makes progress.
            continue;
        }
        for i in 0..el.count {
            // Built only on the error paths: where reading stopped, and in which element.
            let at = |pos: At| format!("{pos} ({} {i})", el.name);
            let mut pos = [0.0f64; 3];
            let mut uv = [0.0f64; 2];
            let mut nrm = [0.0f64; 3];
            for (k, prop) in el.props.iter().enumerate() {
                match prop {
                    Property::Scalar { ty, .. } => {
                        let x = body.read(r, *ty).map_err(|m| fail(at(body.at()), m))?;
                        if is_vertex {
                            match layout.slots[k] {
                                Slot::Pos(a) => pos[a] = x,
                                Slot::Uv(a) => uv[a] = x,
                                Slot::Normal(a) => nrm[a] = x,
                                Slot::Skip => {}
                            }
                        }
                    }
                    Property::List { count, item, .. } => {
                        let before = body.at();
                        let n = body.read(r, *count).map_err(|m| fail(at(body.at()), m))?;
                        if !(0.0..=MAX_POLYGON_CORNERS as f64).contains(&n) {
                            return Err(fail(
                                at(before),
                                format!(
                                    "a list of {n} items (at most {MAX_POLYGON_CORNERS} are read)"
                                ),
                            ));
                        }
                        let take = is_face && k == layout.face_list;
                        corners.clear();
                        for _ in 0..n as usize {
                            let x = body.read(r, *item).map_err(|m| fail(at(body.at()), m))?;
                            if take {
                                let index = vertex_index(x, n_vertices)
                                    .map_err(|m| fail(at(body.at()), m))?;
                                corners.push(index);
                            }
                        }
                        if take {
                            push_polygon(&mut data.triangles, &corners)
                                .map_err(|m| fail(at(body.at()), m))?;
                        }
                    }
                }
            }
            if is_vertex {
                push_vertex(&mut data, layout, pos, uv, nrm).map_err(|m| fail(at(body.at()), m))?;
            }
            if is_face {
                data.faces += 1;
            }
        }
    }
    Ok(data)
}

/// A face's vertex index, checked against the vertex count.
fn vertex_index(x: f64, n_vertices: u64) -> std::result::Result<u32, String> {
    if x < 0.0 {
        return Err(format!("vertex index {x} is negative"));
    }
    if x >= n_vertices as f64 {
        return Err(format!(
            "vertex index {x} is out of range ({n_vertices} vertices)"
        ));
    }
    Ok(x as u32)
}

/// Triangulates a polygon as a fan from its first corner.
fn push_polygon(triangles: &mut Vec<[u32; 3]>, corners: &[u32]) -> std::result::Result<(), String> {
    if corners.len() < 3 {
        return Err(format!(
            "a face needs at least 3 vertices, this one has {}",
            corners.len()
        ));
    }
    for k in 1..corners.len() - 1 {
        triangles.push([corners[0], corners[k], corners[k + 1]]);
    }
    if triangles.len() > MAX_TRIANGLES {
        return Err(format!(
            "more than {MAX_TRIANGLES} triangles after triangulation"
        ));
    }
    Ok(())
}

/// Stores one vertex's position, and its (u, v) and normal when the file has them; each must be
/// finite.
fn push_vertex(
    data: &mut MeshData,
    layout: &Layout,
    pos: [f64; 3],
    uv: [f64; 2],
    nrm: [f64; 3],
) -> std::result::Result<(), String> {
    let p = Vec3::new(pos[0] as f32, pos[1] as f32, pos[2] as f32);
    if !p.is_finite() {
        return Err(format!("position {p} is not finite"));
    }
    data.positions.push(p);
    if layout.uv_names.is_some() {
        let t = Vec2::new(uv[0] as f32, uv[1] as f32);
        if !t.is_finite() {
            return Err(format!("(u, v) {t} is not finite"));
        }
        data.uvs.push(t);
    }
    if layout.has_normals {
        let n = Vec3::new(nrm[0] as f32, nrm[1] as f32, nrm[2] as f32);
        if !n.is_finite() {
            return Err(format!("normal {n} is not finite"));
        }
        data.normals.push(n);
    }
    Ok(())
}

fn read_header(r: &mut impl BufRead, path: &Path) -> Result<Header> {
    let mut line = Vec::new();
    let mut total = 0usize;
    let mut line_no = 0usize;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    let fail = |line_no: usize, message: String| Error::Mesh {
        path: path.to_path_buf(),
        at: format!("header line {line_no}"),
        message,
    };
    loop {
        line.clear();
        let n = r
            .by_ref()
            .take((MAX_HEADER_BYTES - total) as u64 + 1)
            .read_until(b'\n', &mut line)
            .map_err(|e| Error::io(path, e))?;
        line_no += 1;
        total += n;
        if n == 0 {
            return Err(fail(
                line_no,
                "the file ends inside the header (no 'end_header')".into(),
            ));
        }
        if total > MAX_HEADER_BYTES {
            return Err(fail(
                line_no,
                format!("the header is longer than {MAX_HEADER_BYTES} bytes"),
            ));
        }
        let text = std::str::from_utf8(&line)
            .map_err(|_| fail(line_no, "the header is not text".into()))?
            .trim_end_matches(['\n', '\r']);
        let words: Vec<&str> = text.split_ascii_whitespace().collect();
        if line_no == 1 {
            if words != ["ply"] {
                return Err(fail(
                    1,
                    format!(
                        "not a PLY file (it starts with '{}')",
                        text.chars().take(20).collect::<String>()
                    ),
                ));
            }
            continue;
        }
        match words.as_slice() {
            [] | ["comment" | "obj_info", ..] => {}
            ["format", f, _version] => {
                format = Some(PlyFormat::from_name(f).map_err(|e| fail(line_no, e))?);
            }
            ["element", name, count] => {
                let count = count.parse::<u64>().map_err(|_| {
                    fail(line_no, format!("element count '{count}' is not a number"))
                })?;
                if elements.len() >= 256 {
                    return Err(fail(line_no, "more than 256 elements".into()));
                }
                elements.push(Element {
                    name: (*name).to_string(),
                    count,
                    props: Vec::new(),
                    line: line_no,
                });
            }
            ["property", "list", count, item, name] => {
                let el = elements
                    .last_mut()
                    .ok_or_else(|| fail(line_no, "a property before any element".into()))?;
                let (Some(count), Some(item)) = (Scalar::parse(count), Scalar::parse(item)) else {
                    return Err(fail(line_no, format!("unknown type in '{text}'")));
                };
                if !count.is_int() {
                    return Err(fail(line_no, "a list count must be an integer type".into()));
                }
                el.props.push(Property::List {
                    name: (*name).to_string(),
                    count,
                    item,
                });
            }
            ["property", ty, name] => {
                let el = elements
                    .last_mut()
                    .ok_or_else(|| fail(line_no, "a property before any element".into()))?;
                let ty = Scalar::parse(ty)
                    .ok_or_else(|| fail(line_no, format!("unknown property type '{ty}'")))?;
                if el.props.len() >= 256 {
                    return Err(fail(line_no, "more than 256 properties".into()));
                }
                if el.props.iter().any(|p| p.name() == *name) {
                    return Err(fail(line_no, format!("property '{name}' appears twice")));
                }
                el.props.push(Property::Scalar {
                    name: (*name).to_string(),
                    ty,
                });
            }
            ["end_header"] => {
                let format = format
                    .ok_or_else(|| fail(line_no, "no 'format' line before end_header".into()))?;
                return Ok(Header {
                    format,
                    elements,
                    lines: line_no,
                    bytes: total as u64,
                });
            }
            _ => {
                return Err(fail(
                    line_no,
                    format!(
                        "cannot read '{}'",
                        text.chars().take(60).collect::<String>()
                    ),
                ));
            }
        }
    }
}

/// Writes `data` as PLY: `float x y z`, then `float nx ny nz` and `float u v` when present, and
/// faces as `list uchar int vertex_indices`.
///
/// # Errors
/// `w` fails to take the bytes.
pub fn write_ply(w: &mut impl Write, data: &MeshData, format: PlyFormat) -> std::io::Result<()> {
    let has_n = !data.normals.is_empty();
    let has_uv = !data.uvs.is_empty();
    writeln!(w, "ply\nformat {} 1.0", format.name())?;
    writeln!(w, "comment written by texplore")?;
    writeln!(w, "element vertex {}", data.positions.len())?;
    writeln!(w, "property float x\nproperty float y\nproperty float z")?;
    if has_n {
        writeln!(w, "property float nx\nproperty float ny\nproperty float nz")?;
    }
    if has_uv {
        writeln!(w, "property float u\nproperty float v")?;
    }
    writeln!(w, "element face {}", data.triangles.len())?;
    writeln!(w, "property list uchar int vertex_indices\nend_header")?;
    let mut floats = Vec::with_capacity(8);
    for (i, p) in data.positions.iter().enumerate() {
        floats.clear();
        floats.extend_from_slice(&p.to_array());
        if has_n {
            floats.extend_from_slice(&data.normals[i].to_array());
        }
        if has_uv {
            floats.extend_from_slice(&data.uvs[i].to_array());
        }
        match format {
            PlyFormat::Ascii => {
                let words: Vec<String> = floats.iter().map(f32::to_string).collect();
                writeln!(w, "{}", words.join(" "))?;
            }
            PlyFormat::BinaryLittleEndian => {
                for f in &floats {
                    w.write_all(&f.to_le_bytes())?;
                }
            }
            PlyFormat::BinaryBigEndian => {
                for f in &floats {
                    w.write_all(&f.to_be_bytes())?;
                }
            }
        }
    }
    for t in &data.triangles {
        match format {
            PlyFormat::Ascii => writeln!(w, "3 {} {} {}", t[0], t[1], t[2])?,
            PlyFormat::BinaryLittleEndian => {
                w.write_all(&[3])?;
                for i in t {
                    w.write_all(&(*i as i32).to_le_bytes())?;
                }
            }
            PlyFormat::BinaryBigEndian => {
                w.write_all(&[3])?;
                for i in t {
                    w.write_all(&(*i as i32).to_be_bytes())?;
                }
            }
        }
    }
    Ok(())
}
