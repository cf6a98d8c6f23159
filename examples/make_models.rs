//! Writes the procedural models shipped in `assets/` (run from the repository root):
//!
//! ```sh
//! cargo run --release --example make_models
//! ```
//!
//! - `soup-can.obj` + `soup-can.mtl` + `soup-can-label.png`: a UV-unwrapped soup can (label
//!   around the wall with its seam at u = 0, the two lids as disc islands in the lower half of the
//!   image), with normals; the .mtl's `map_Kd` names the label.
//! - `torus-knot.ply` (binary little-endian): a (2, 3) torus knot tube with normals and (u, v)
//!   (u along the knot, v around the tube: two seams).

use std::fmt::Write as _;
use std::path::Path;
use texplore::geometry::MeshData;
use texplore::math::{TAU, Vec2, Vec3};
use texplore::meshio::{PlyFormat, write_ply};

/// A surface of revolution about y from a profile of (radius, height) points, oriented so
/// (dy, -dr) points outside, with (u, v) from `uv(i / segments, k)`. Appended to `d`.
fn revolve(
    d: &mut MeshData,
    segments: u32,
    profile: &[(f32, f32)],
    uv: impl Fn(f32, usize, f32) -> Vec2,
) {
    let base = d.positions.len() as u32;
    let n = profile.len();
    for (k, &(r, y)) in profile.iter().enumerate() {
        // The normal at a profile point: the average of its segments' normals.
        let seg = |a: usize, b: usize| {
            let (dr, dy) = (profile[b].0 - profile[a].0, profile[b].1 - profile[a].1);
            Vec2::new(dy, -dr).normalize_or_zero()
        };
        let mut nrm = Vec2::ZERO;
        if k > 0 {
            nrm += seg(k - 1, k);
        }
        if k + 1 < n {
            nrm += seg(k, k + 1);
        }
        let nrm = nrm.normalize_or(Vec2::Y);
        for i in 0..=segments {
            let phi = TAU * (i % segments) as f32 / segments as f32;
            let (s, c) = phi.sin_cos();
            d.positions.push(Vec3::new(r * s, y, r * c));
            d.normals.push(Vec3::new(nrm.x * s, nrm.y, nrm.x * c));
            d.uvs.push(uv(i as f32 / segments as f32, k, phi));
        }
    }
    let at = |i: u32, k: u32| base + k * (segments + 1) + i;
    for k in 0..n as u32 - 1 {
        for i in 0..segments {
            let (a, b, c, e) = (at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1));
            if profile[k as usize].0 > 0.0 {
                d.triangles.push([a, b, c]);
            }
            if profile[k as usize + 1].0 > 0.0 {
                d.triangles.push([a, c, e]);
            }
        }
    }
}

/// Makes every triangle counter-clockwise seen from where its vertex normals point.
fn orient(d: &mut MeshData) {
    for t in &mut d.triangles {
        let p = t.map(|i| d.positions[i as usize]);
        let n: Vec3 = t.iter().map(|&i| d.normals[i as usize]).sum();
        if (p[1] - p[0]).cross(p[2] - p[0]).dot(n) < 0.0 {
            t.swap(1, 2);
        }
    }
}

const H: f32 = 1.3; // half height of the can
const LID_UV_RADIUS: f32 = 0.23;

fn soup_can() -> MeshData {
    let mut d = MeshData::default();
    let segments = 64;
    // The wall: slight ridges near both ends, label in the upper half of the image (v 0.5 to 1).
    let mut wall = Vec::new();
    let rows = 14;
    for k in 0..=rows {
        let t = k as f32 / rows as f32;
        let y = -H + 2.0 * H * t;
        let ridge = if (0.1..=0.9).contains(&t) {
            0.0
        } else {
            0.012 * (t * 80.0).sin()
        };
        wall.push((1.0 + ridge, y));
    }
    revolve(&mut d, segments, &wall, |u, k, _| {
        Vec2::new(u, 0.5 + 0.5 * k as f32 / rows as f32)
    });
    // The lids, from the wall's edge inward: bevel up to the rim, down into the lid, a groove,
    // then flat to the centre. (u, v): a disc island, radius proportional to the distance
    // from the axis.
    let lid = |top: bool| {
        let s = if top { 1.0 } else { -1.0 };
        let pts = [
            (1.0, H),
            (0.975, H + 0.07),
            (0.94, H + 0.075),
            (0.91, H + 0.02),
            (0.8, H + 0.015),
            (0.74, H + 0.035),
            (0.68, H + 0.015),
            (0.4, H + 0.015),
            (0.0, H + 0.015),
        ];
        let mut p: Vec<(f32, f32)> = pts.iter().map(|&(r, y)| (r, s * y)).collect();
        if !top {
            // The outside is below: walk the profile the other way round.
            p.reverse();
        }
        p
    };
    for top in [true, false] {
        let profile = lid(top);
        let centre = if top {
            Vec2::new(0.25, 0.25)
        } else {
            Vec2::new(0.75, 0.25)
        };
        let radii: Vec<f32> = profile.iter().map(|p| p.0).collect();
        revolve(&mut d, segments, &profile, |_, k, phi| {
            let rho = LID_UV_RADIUS * radii[k];
            // Seen from outside each lid reads the right way round.
            let sx = if top { 1.0 } else { -1.0 };
            centre + Vec2::new(sx * rho * phi.sin(), -rho * phi.cos())
        });
    }
    orient(&mut d);
    d.faces = d.triangles.len();
    d
}

fn torus_knot() -> MeshData {
    let (p, q) = (2.0f32, 3.0f32);
    let (n_u, n_v) = (192u32, 16u32);
    let tube = 0.16;
    let curve = |t: f32| {
        let r = 0.55 * (2.0 + (q * t).cos());
        Vec3::new(r * (p * t).cos(), 0.55 * (q * t).sin(), r * (p * t).sin())
    };
    let mut d = MeshData::default();
    for i in 0..=n_u {
        let t = TAU * (i % n_u) as f32 / n_u as f32;
        let h = 1e-3;
        let c = curve(t);
        let tangent = (curve(t + h) - curve(t - h)).normalize();
        let accel = curve(t + h) - 2.0 * c + curve(t - h);
        let normal = (accel - tangent * accel.dot(tangent)).normalize();
        let binormal = tangent.cross(normal);
        for j in 0..=n_v {
            let a = TAU * (j % n_v) as f32 / n_v as f32;
            let radial = normal * a.cos() + binormal * a.sin();
            d.positions.push(c + radial * tube);
            d.normals.push(radial);
            d.uvs
                .push(Vec2::new(i as f32 / n_u as f32, j as f32 / n_v as f32));
        }
    }
    let at = |i: u32, j: u32| i * (n_v + 1) + j;
    for i in 0..n_u {
        for j in 0..n_v {
            let (a, b, c, e) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            d.triangles.push([a, b, c]);
            d.triangles.push([a, c, e]);
        }
    }
    orient(&mut d);
    d.faces = d.triangles.len();
    d
}

fn write_obj(d: &MeshData, obj: &Path, mtl_name: &str) -> std::io::Result<()> {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# A procedural soup can with a UV-unwrapped label, written by texplore's"
    );
    let _ = writeln!(
        s,
        "# examples/make_models.rs. CC0.\nmtllib {mtl_name}\no can"
    );
    let f = |x: f32| {
        let t = format!("{x:.5}");
        let t = t.trim_end_matches('0').trim_end_matches('.').to_string();
        if t == "-0" { "0".to_string() } else { t }
    };
    for p in &d.positions {
        let _ = writeln!(s, "v {} {} {}", f(p.x), f(p.y), f(p.z));
    }
    for t in &d.uvs {
        let _ = writeln!(s, "vt {} {}", f(t.x), f(t.y));
    }
    for n in &d.normals {
        let _ = writeln!(s, "vn {} {} {}", f(n.x), f(n.y), f(n.z));
    }
    let _ = writeln!(s, "usemtl label");
    for t in &d.triangles {
        let [a, b, c] = t.map(|i| i + 1);
        let _ = writeln!(s, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}");
    }
    std::fs::write(obj, s)
}

/// 5 x 7 glyphs for the label's letters.
fn glyph(c: char) -> [u8; 7] {
    match c {
        'T' => [0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04],
        'E' => [0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x1f],
        'X' => [0x11, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x11],
        'P' => [0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10],
        'L' => [0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1f],
        'O' => [0x0e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e],
        'R' => [0x1e, 0x11, 0x11, 0x1e, 0x14, 0x12, 0x11],
        'S' => [0x0f, 0x10, 0x10, 0x0e, 0x01, 0x01, 0x1e],
        'U' => [0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e],
        'B' => [0x1e, 0x11, 0x11, 0x1e, 0x11, 0x11, 0x1e],
        'M' => [0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11],
        'A' => [0x0e, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11],
        'C' => [0x0e, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0e],
        'N' => [0x11, 0x19, 0x15, 0x13, 0x11, 0x11, 0x11],
        'D' => [0x1e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1e],
        _ => [0; 7],
    }
}

fn text(img: &mut image::RgbImage, s: &str, x0: u32, y0: u32, scale: u32, colour: image::Rgb<u8>) {
    let size = img.width();
    for (n, ch) in s.chars().enumerate() {
        let g = glyph(ch);
        for (row, bits) in g.iter().enumerate() {
            for col in 0..5 {
                if bits & (0x10 >> col) != 0 {
                    for dy in 0..scale {
                        for dx in 0..scale {
                            let x = x0 + (n as u32 * 6 + col) * scale + dx;
                            let y = y0 + row as u32 * scale + dy;
                            if x < size && y < size {
                                img.put_pixel(x, y, colour);
                            }
                        }
                    }
                }
            }
        }
    }
}

fn label(size: u32) -> image::RgbImage {
    let red = image::Rgb([178u8, 24, 30]);
    let cream = image::Rgb([244u8, 236, 214]);
    let gold = image::Rgb([212u8, 170, 60]);
    let mut img = image::RgbImage::from_pixel(size, size, image::Rgb([40, 42, 46]));
    let half = size / 2;
    // The label (upper half of the image = v in [0.5, 1]): red top and bottom, cream middle.
    for y in 0..half {
        let t = y as f32 / half as f32; // 0 at the top of the can
        for x in 0..size {
            let c = if (0.3..=0.72).contains(&t) {
                cream
            } else {
                red
            };
            let c = if (0.28..0.3).contains(&t) || (0.72..0.74).contains(&t) {
                gold
            } else {
                c
            };
            img.put_pixel(x, y, c);
        }
    }
    let s = size / 512;
    // Twice around the can, so one name always faces the camera.
    for x in [20 * s, 276 * s] {
        text(&mut img, "TEXPLORE", x, 22 * s, 4 * s, cream);
        text(&mut img, "SOUP", x + 32 * s, 92 * s, 8 * s, red);
        text(&mut img, "CONDENSED", x + 18 * s, 196 * s, 3 * s, cream);
    }
    // A barcode panel just left of the seam (u = 1) shows where the label's ends meet.
    for x in (size - 40 * s)..(size - 8 * s) {
        for y in (152 * s)..(182 * s) {
            let bar =
                ((x * 7) / (3 * s)).is_multiple_of(3) || ((x * 13) / (5 * s)).is_multiple_of(4);
            img.put_pixel(
                x,
                y,
                if bar {
                    image::Rgb([10, 10, 10])
                } else {
                    image::Rgb([250, 250, 250])
                },
            );
        }
    }
    // The lids (lower half): brushed metal discs with rings, centred at u = 0.25 and 0.75,
    // v = 0.25, radius 0.23 (as the mesh's lid islands).
    for (cu, word) in [(0.25f32, "TOP"), (0.75, "BASE")] {
        let (cx, cy) = (cu * size as f32, 0.75 * size as f32);
        let r_max = LID_UV_RADIUS * size as f32;
        for y in half..size {
            for x in 0..size {
                let (dx, dy) = (x as f32 + 0.5 - cx, y as f32 + 0.5 - cy);
                let r = (dx * dx + dy * dy).sqrt() / r_max;
                if r <= 1.02 {
                    let ring = (r * 40.0).sin() * 10.0;
                    let v = if (0.72..0.78).contains(&r) {
                        150.0
                    } else {
                        190.0 + ring
                    };
                    let v = if r > 0.9 { 165.0 + ring } else { v };
                    let grey = v.clamp(0.0, 255.0) as u8;
                    img.put_pixel(x, y, image::Rgb([grey, grey, grey.saturating_add(8)]));
                }
            }
        }
        let w = word.len() as u32 * 6 * 3 * s;
        text(
            &mut img,
            word,
            cx as u32 - w / 2,
            cy as u32 - 10 * s,
            3 * s,
            red,
        );
    }
    img
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let assets = Path::new("assets");
    let can = soup_can();
    write_obj(&can, &assets.join("soup-can.obj"), "soup-can.mtl")?;
    std::fs::write(
        assets.join("soup-can.mtl"),
        "# The soup can's label, written by texplore's examples/make_models.rs. CC0.\nnewmtl label\nKd 1 1 1\nmap_Kd soup-can-label.png\n",
    )?;
    label(512).save(assets.join("soup-can-label.png"))?;
    let knot = torus_knot();
    let mut f = std::io::BufWriter::new(std::fs::File::create(assets.join("torus-knot.ply"))?);
    write_ply(&mut f, &knot, PlyFormat::BinaryLittleEndian)?;
    println!(
        "soup can: {} vertices, {} triangles; torus knot: {} vertices, {} triangles",
        can.positions.len(),
        can.triangles.len(),
        knot.positions.len(),
        knot.triangles.len()
    );
    Ok(())
}
