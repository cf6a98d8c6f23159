//! Issue 18: the lecture's formulas at the closed ends. (u, v) lives in the closed square
//! [0, 1] x [0, 1]; u = 1 and v = 1 are the last texel's (`column = (int)((hres - 1) u)` is
//! hres - 1 there), under both lookups and every wrap mode. Only the periodic mappings'
//! u = 1 is the seam u = 0 (the first column).

use std::path::Path;
use std::process::Command;
use std::sync::Arc;
use strum::VariantArray;
use texplore::mapping::{Mapping, TexCoord};
use texplore::math::{Rgb, Vec2, Vec3A};
use texplore::render::render_blocking;
use texplore::scene::{AssetCache, build_scene, parse_preset};
use texplore::texture::{Filter, ImageData, ImageTexture, Lookup, Wrap};

/// The lecture's texel index, worked independently in f64: `(int)((n - 1) t)` or the centred
/// `min(floor(t n), n - 1)`, for t in the closed [0, 1].
fn lecture_index(lookup: Lookup, t: f64, n: u32) -> u32 {
    assert!((0.0..=1.0).contains(&t), "{t} is outside the closed square");
    match lookup {
        Lookup::Lecture => (f64::from(n - 1) * t) as u32,
        Lookup::Centred => ((t * f64::from(n)) as u32).min(n - 1),
    }
}

/// An image whose texel (column c, row-from-bottom r) has colour (c, r, 7): every texel tells
/// where it is.
fn coordinates_image(w: u32, h: u32) -> ImageData {
    ImageData::from_fn(w, h, "coordinates", |c, row_top| {
        Rgb(c as f32, (h - 1 - row_top) as f32, 7.0)
    })
}

/// The texel the renderer's nearest filter reads for point `p` (the whole path: mapping, the
/// wraps of `ImageTexture::wraps`, the lookup), or `None` where it reads black.
fn rendered_texel(
    image: &Arc<ImageData>,
    mapping: Mapping,
    lookup: Lookup,
    wrap: Wrap,
    p: Vec3A,
) -> Option<(u32, u32)> {
    let texture = ImageTexture {
        image: image.clone(),
        mapping: mapping.into(),
        filter: Filter::Nearest,
        lookup,
        wrap,
        scale: 1.0,
        mip: None,
        max_anisotropy: 8.0,
        transform: None,
    };
    let tc = TexCoord {
        uv: mapping.map_uv(p),
        ..TexCoord::default()
    };
    let c = texture.sample(tc);
    (c.2 == 7.0).then_some((c.0 as u32, c.1 as u32))
}

/// A domain edge: the point, the lecture's (u, v) there worked by hand, and whether u = 1 is
/// the periodic seam (documented to read the first column).
struct Edge {
    p: [f32; 3],
    uv: (f64, f64),
    seam: bool,
}

const fn edge(p: [f32; 3], u: f64, v: f64) -> Edge {
    Edge {
        p,
        uv: (u, v),
        seam: false,
    }
}

fn domain_edges(m: Mapping) -> Vec<Edge> {
    let tiny = f32::from_bits(1);
    // Rim angles away from quarter turns, so no f32 rounding sits on a texel boundary.
    let rim = [0.3f64, 1.1, 2.0, 2.9, 4.0, 5.2, 6.0];
    match m {
        Mapping::Rectangular => {
            // The four corners of the generic rectangle, the middles of its edges.
            let mut v = Vec::new();
            for x in [-1.0f32, 0.0, 1.0] {
                for z in [-1.0f32, 0.0, 1.0] {
                    let uv = (
                        f64::midpoint(f64::from(z), 1.0),
                        f64::midpoint(f64::from(x), 1.0),
                    );
                    v.push(edge([x, 0.0, z], uv.0, uv.1));
                }
            }
            v
        }
        Mapping::Cylindrical => {
            let mut v = Vec::new();
            for y in [-1.0f32, 1.0] {
                let vv = f64::midpoint(f64::from(y), 1.0);
                v.push(edge([0.0, y, 1.0], 0.0, vv));
                for phi in rim {
                    let p = [phi.sin() as f32, y, phi.cos() as f32];
                    v.push(edge(p, phi / std::f64::consts::TAU, vv));
                }
                // The seam from the west: phi = 2 pi, u = 1 is u = 0.
                v.push(Edge {
                    p: [-tiny, y, 1.0],
                    uv: (1.0, vv),
                    seam: true,
                });
            }
            v
        }
        Mapping::Spherical | Mapping::Uv => {
            let mut v = vec![
                // The poles: atan2(0, 0) = 0.
                edge([0.0, 1.0, 0.0], 0.0, 1.0),
                edge([0.0, -1.0, 0.0], 0.0, 0.0),
                edge([0.0, 0.0, 1.0], 0.0, 0.5),
            ];
            for y in [-0.9f32, 0.0, 0.9] {
                let r = (1.0 - y * y).sqrt();
                let vv = 1.0 - f64::from(y).acos() / std::f64::consts::PI;
                v.push(Edge {
                    p: [-tiny, y, r],
                    uv: (1.0, vv),
                    seam: true,
                });
            }
            v
        }
        Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall => {
            let s = if m == Mapping::Panoramic { -1.0 } else { 1.0 };
            let r90 = if m == Mapping::MirrorBall {
                std::f64::consts::FRAC_1_SQRT_2
            } else {
                0.5
            };
            vec![
                // The image centre, the four points a quarter turn from the axis and the
                // antipode, where the whole rim meets (documented: the rim point (1, 0.5)).
                edge([0.0, 0.0, s], 0.5, 0.5),
                edge([1.0, 0.0, 0.0], 0.5 + r90 / 2.0, 0.5),
                edge([-1.0, 0.0, 0.0], 0.5 - r90 / 2.0, 0.5),
                edge([0.0, 1.0, 0.0], 0.5, 0.5 + r90 / 2.0),
                edge([0.0, -1.0, 0.0], 0.5, 0.5 - r90 / 2.0),
                edge([0.0, 0.0, -s], 1.0, 0.5),
            ]
        }
    }
}

#[test]
fn every_mapping_reads_the_lectures_texel_at_the_edges_of_its_domain() {
    let mut checked = 0;
    for (w, h) in [(7, 5), (1024, 512), (1, 1), (3, 2)] {
        let image = Arc::new(coordinates_image(w, h));
        for &m in Mapping::VARIANTS {
            for e in domain_edges(m) {
                let p = Vec3A::from(e.p);
                for &lookup in Lookup::VARIANTS {
                    for &wrap in Wrap::VARIANTS {
                        let (u, v) = e.uv;
                        let want_column = if e.seam {
                            0
                        } else {
                            lecture_index(lookup, u, w)
                        };
                        let want = (want_column, lecture_index(lookup, v, h));
                        let got = rendered_texel(&image, m, lookup, wrap, p);
                        assert_eq!(
                            got,
                            Some(want),
                            "{m} at {p} ((u, v) = {:?}), {lookup} lookup, {wrap}, {w} x {h}",
                            e.uv
                        );
                        checked += 1;
                    }
                }
            }
        }
    }
    assert!(checked > 1000, "{checked}");
}

/// Outside [0, 1] the wrap modes still decide; just outside the far edge repeat reads the first
/// column again and black reads black.
#[test]
fn just_outside_the_far_edge_the_wrap_decides() {
    let image = Arc::new(coordinates_image(4, 4));
    let beyond = f32::from_bits(1.0f32.to_bits() + 1);
    let p = Vec3A::new(0.0, 0.0, 2.0 * beyond - 1.0); // u just above 1
    let at = |lookup, wrap| rendered_texel(&image, Mapping::Rectangular, lookup, wrap, p);
    for &lookup in Lookup::VARIANTS {
        assert_eq!(at(lookup, Wrap::Repeat).map(|t| t.0), Some(0));
        assert_eq!(at(lookup, Wrap::Clamp).map(|t| t.0), Some(3));
        // Mirrored to just below 1: the lecture's (int)(3 x 0.99999988) is 2.
        let mirrored = if lookup == Lookup::Lecture { 2 } else { 3 };
        assert_eq!(at(lookup, Wrap::Mirror).map(|t| t.0), Some(mirrored));
        assert_eq!(at(lookup, Wrap::Black), None);
    }
    // Exactly on the far corner every mode reads the last texel.
    let corner = Vec3A::new(1.0, 0.0, 1.0);
    for &lookup in Lookup::VARIANTS {
        for &wrap in Wrap::VARIANTS {
            assert_eq!(
                rendered_texel(&image, Mapping::Rectangular, lookup, wrap, corner),
                Some((3, 3)),
                "{lookup} {wrap}"
            );
        }
    }
}

/// A 4 x 4 PNG whose last column is red and no other texel is.
fn write_far_column_red(path: &Path) {
    let img = image::RgbImage::from_fn(4, 4, |c, r| match c {
        3 => image::Rgb([255, 0, 0]),
        0 => image::Rgb([0, 255, 0]),
        1 => image::Rgb([0, 0, 255]),
        _ => image::Rgb([0, 255 * (r % 2) as u8, 255]),
    });
    img.save(path).unwrap();
}

const RED: Rgb = Rgb(1.0, 0.0, 0.0);

/// The generic rectangle seen head-on from above its far edge: the film's middle row looks
/// straight down at z = 1 (u = 1), the rows above miss, the rows below see z < 1.
#[test]
fn a_render_shows_the_last_column_along_the_far_edge() {
    let dir = tempfile::tempdir().unwrap();
    write_far_column_red(&dir.path().join("far.png"));
    let preset = dir.path().join("far.ron");
    for &lookup in Lookup::VARIANTS {
        for &wrap in Wrap::VARIANTS {
            let text = format!(
                "(version: 1,
                  camera: (eye: (0, 5, 1), look_at: (0, 0, 1), up: (0, 0, 1), projection: Pinhole(fov: 30)),
                  render: (width: 9, height: 9, spp: 1, sampler: Regular),
                  objects: [(shape: Rectangle, material: Emissive(ce: Image(path: \"far.png\",
                      mapping: Rectangular, filter: Nearest, lookup: {lookup:?}, wrap: {wrap:?})))])"
            );
            let desc = parse_preset(&text, &preset).unwrap();
            let scene = build_scene(&desc, &preset, &mut AssetCache::new()).unwrap();
            // The middle row's rays hit exactly z = 1: the far edge, u = 1.
            let probe = scene.inspect(Vec2::new(4.5, 4.5)).unwrap();
            assert_eq!(probe.local_point.z, 1.0);
            assert_eq!(probe.tex.unwrap().uv.x, 1.0);
            // The inspector shows the texel the renderer reads, with the lecture's numbers.
            let pick = probe.texels.iter().find(|t| t.lookup == lookup).unwrap();
            assert_eq!(pick.column, 3, "{lookup} {wrap}");
            if lookup == Lookup::Lecture {
                assert_eq!(
                    pick.lines[0],
                    "column = (int)((hres - 1) u) = (int)(3 x 1.0000) = 3"
                );
            }
            let film = render_blocking(&scene, |_| {}).to_linear();
            let px = |x: usize, y: usize| film[y * 9 + x];
            // Columns 1..=7 of the film see the rectangle (|x| <= 1), 0 and 8 miss it.
            for x in 1..=7 {
                assert_eq!(px(x, 4), RED, "far edge, film column {x}, {lookup} {wrap}");
                for y in 0..4 {
                    assert_eq!(px(x, y), Rgb::BLACK, "beyond the far edge ({x}, {y})");
                }
                // Just inside the far edge: u = 0.85, the lecture's (int)(3 x 0.85) = 2,
                // the centred floor(4 x 0.85) = 3.
                let inside = px(x, 5);
                if lookup == Lookup::Lecture {
                    assert_ne!(inside, RED, "({x}, 5), {wrap}");
                    assert_ne!(inside, Rgb::BLACK, "({x}, 5), {wrap}");
                } else {
                    assert_eq!(inside, RED, "({x}, 5), {wrap}");
                }
            }
            assert_eq!(px(0, 4), Rgb::BLACK);
            assert_eq!(px(8, 4), Rgb::BLACK);
        }
    }
}

fn texplore(args: &[&str]) -> (String, String, bool) {
    let out = Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .unwrap();
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.success(),
    )
}

/// The example: `texplore map rectangular 1 0 1 --res 1024 512 --lookup lecture`.
#[test]
fn map_shows_the_far_corner_reaching_the_last_column() {
    let (out, err, ok) = texplore(&[
        "map",
        "rectangular",
        "1",
        "0",
        "1",
        "--res",
        "1024",
        "512",
        "--lookup",
        "lecture",
    ]);
    assert!(ok, "{err}");
    assert!(
        out.contains("u = (z + 1) / 2 = (1.0000 + 1) / 2 = 1.0000"),
        "{out}"
    );
    assert!(
        !out.contains("wrapped") && !out.contains("outside"),
        "{out}"
    );
    assert!(
        out.contains("column = (int)((hres - 1) u) = (int)(1023 x 1.0000) = 1023"),
        "{out}"
    );
    assert!(
        out.contains("row = (int)((vres - 1) v) = (int)(511 x 1.0000) = 511"),
        "{out}"
    );
    for wrap in ["repeat", "clamp", "mirror", "black"] {
        for (lookup, column) in [("lecture", 1023), ("centred", 1023)] {
            let (out, err, ok) = texplore(&[
                "map",
                "rectangular",
                "1",
                "0",
                "1",
                "--res",
                "1024",
                "512",
                "--lookup",
                lookup,
                "--wrap",
                wrap,
                "--json",
            ]);
            assert!(ok, "{err}");
            let v: serde_json::Value = serde_json::from_str(&out).unwrap();
            assert_eq!(v["column"], column, "{wrap} {lookup}: {out}");
            assert_eq!(v["row"], 511, "{wrap} {lookup}: {out}");
            assert_eq!(v["file_row"], 0, "{wrap} {lookup}: {out}");
        }
    }
    // Outside, the named wrap speaks; black has no texel.
    let (out, _, ok) = texplore(&["map", "rectangular", "1.5", "0", "0", "--wrap", "mirror"]);
    assert!(ok);
    assert!(
        out.contains("v = 1.2500 is outside [0, 1]: mirror brings it to v = 0.7500"),
        "{out}"
    );
    let (out, _, ok) = texplore(&[
        "map",
        "rectangular",
        "1.5",
        "0",
        "0",
        "--wrap",
        "black",
        "--json",
    ]);
    assert!(ok);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["column"].is_null() && v["row"].is_null(), "{out}");
    let (_, err, ok) = texplore(&["map", "rectangular", "1", "0", "1", "--wrap", "tile"]);
    assert!(!ok);
    assert!(err.contains("repeat, clamp, mirror, black"), "{err}");
}

/// The periodic mappings' u = 1 is their seam, u = 0: the worked formula says so.
#[test]
fn map_shows_the_seam_as_u_0() {
    let (out, err, ok) = texplore(&[
        "map",
        "cylindrical",
        "-1e-300",
        "1",
        "1",
        "--res",
        "1024",
        "512",
        "--lookup",
        "lecture",
    ]);
    assert!(ok, "{err}");
    assert!(
        out.contains("phi = atan2(x, z) = atan2(-1.0000e-300, 1.0000) = -1.0000e-300 rad"),
        "{out}"
    );
    assert!(out.contains("u = 1 is the seam u = 0"), "{out}");
    assert!(out.contains("(int)(1023 x 0.0000) = 0"), "{out}");
    // The top rim, v = 1, is the last row.
    assert!(out.contains("(int)(511 x 1.0000) = 511"), "{out}");
}

/// Coordinates are read as f64: (5e-324, 5e-324, 1) is not flushed to the axis.
#[test]
fn map_reads_coordinates_as_f64() {
    let (out, err, ok) = texplore(&["map", "light-probe", "5e-324", "5e-324", "1"]);
    assert!(ok, "{err}");
    assert!(out.contains("local hit point (5e-324, 5e-324, 1)"), "{out}");
    assert!(
        out.contains(
            "sin beta = y / sqrt(x^2 + y^2) = 0.7071, cos beta = x / sqrt(x^2 + y^2) = 0.7071"
        ),
        "{out}"
    );
    assert!(!out.contains("undefined"), "{out}");
}
