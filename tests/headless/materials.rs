//! Materials whose coefficients and colours are textures (issue 14): each textured parameter
//! changes the image exactly where its texture varies, a constant texture renders as the plain
//! number, and old presets read as before.

use std::path::Path;
use texplore::math::Rgb;
use texplore::render::render_blocking;
use texplore::scene::{AssetCache, build_scene, parse_preset};

/// A lit rectangle seen from above at an angle, with a light so that ambient, diffuse and the
/// highlight all show; `MATERIAL` is replaced.
const SCENE: &str = r"(
    version: 1,
    camera: (eye: (0, 2.2, 2.2), look_at: (0, 0, 0), projection: Pinhole(fov: 50)),
    render: (width: 48, height: 36, spp: 1, sampler: Regular),
    ambient: (ls: 0.5),
    lights: [Point(position: (0, 1.5, 1.2), ls: 1.5)],
    objects: [(shape: Rectangle, material: MATERIAL)],
)";

fn render(material: &str) -> Vec<Rgb> {
    let text = SCENE.replace("MATERIAL", material);
    let path = Path::new("materials-test.ron");
    let desc = parse_preset(&text, path).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let scene = build_scene(&desc, path, &mut AssetCache::new()).unwrap_or_else(|e| panic!("{e}"));
    render_blocking(&scene, |_| {}).to_linear()
}

/// The checker of two values `a` (squares at even (i + j)) and `b`: a nearest-filtered 4 x 4
/// checker over the rectangle.
fn checker(a: &str, b: &str) -> String {
    format!("Checker(mapping: Rectangular, squares: (4, 4), colors: ({a}, {b}))")
}

/// Each parameter, a material template with `@` where it goes, and two values (as a plain
/// number or colour, and as a checker colour).
/// A value written as a plain number or colour, and as a colour for a texture.
type Value = (&'static str, &'static str);

const PARAMS: &[(&str, &str, Value, Value)] = &[
    (
        "ka",
        "Matte(ka: @, cd: Constant((0.6, 0.5, 0.4)))",
        ("0.2", "(0.2, 0.2, 0.2)"),
        ("0.9", "(0.9, 0.9, 0.9)"),
    ),
    (
        "kd",
        "Matte(kd: @, cd: Constant((0.6, 0.5, 0.4)))",
        ("0.1", "(0.1, 0.1, 0.1)"),
        ("0.8", "(0.8, 0.8, 0.8)"),
    ),
    (
        "ks",
        "Phong(ks: @, exp: 4, cd: Constant((0.3, 0.3, 0.3)))",
        ("0", "(0, 0, 0)"),
        ("1", "(1, 1, 1)"),
    ),
    (
        "exp",
        "Phong(ks: 1, exp: @, cd: Constant((0.3, 0.3, 0.3)))",
        ("2", "(2, 2, 2)"),
        ("200", "(200, 200, 200)"),
    ),
    (
        "cs",
        "Phong(ks: 1, exp: 4, cs: @, cd: Constant((0.3, 0.3, 0.3)))",
        ("(1, 0, 0)", "(1, 0, 0)"),
        ("(0, 0, 1)", "(0, 0, 1)"),
    ),
    (
        "ls",
        "Emissive(ls: @, ce: Constant((0.6, 0.5, 0.4)))",
        ("0.5", "(0.5, 0.5, 0.5)"),
        ("1.5", "(1.5, 1.5, 1.5)"),
    ),
];

#[test]
fn each_textured_parameter_changes_the_image_exactly_where_its_texture_varies() {
    for &(name, template, (a_plain, a_colour), (b_plain, b_colour)) in PARAMS {
        let plain_a = render(&template.replace('@', a_plain));
        let plain_b = render(&template.replace('@', b_plain));
        let textured = render(&template.replace('@', &checker(a_colour, b_colour)));
        let differ = plain_a.iter().zip(&plain_b).filter(|(a, b)| a != b).count();
        assert!(
            differ > 100,
            "{name}: the two values should look different ({differ} pixels differ)"
        );
        for (i, t) in textured.iter().enumerate() {
            assert!(
                *t == plain_a[i] || *t == plain_b[i],
                "{name}: pixel {i} is {t:?}, neither value's {:?} nor {:?}",
                plain_a[i],
                plain_b[i]
            );
        }
        // Where the two plain renders differ, the textured one takes each value in turn: the
        // change follows the checker, not the whole surface.
        let b_where_differ = textured
            .iter()
            .zip(plain_a.iter().zip(&plain_b))
            .filter(|(t, (a, b))| a != b && t == b)
            .count();
        assert!(
            b_where_differ > differ / 4 && b_where_differ < differ * 3 / 4,
            "{name}: {b_where_differ} of {differ} differing pixels follow b"
        );
    }
}

#[test]
fn a_constant_texture_renders_identically_to_the_plain_number() {
    for &(name, template, (a_plain, a_colour), _) in PARAMS {
        let plain = render(&template.replace('@', a_plain));
        let constant = render(&template.replace('@', &format!("Constant({a_colour})")));
        assert!(
            plain == constant,
            "{name}: Constant({a_colour}) differs from {a_plain}"
        );
    }
}

#[test]
fn a_channel_reads_one_colour_of_the_texture() {
    // The red channel of a checker whose red is 0.9 everywhere is the plain number 0.9.
    let red = render(
        "Matte(ka: (texture: Checker(colors: ((0.9, 0, 0.3), (0.9, 1, 0))), channel: Red), \
         cd: Constant((0.6, 0.5, 0.4)))",
    );
    let plain = render("Matte(ka: 0.9, cd: Constant((0.6, 0.5, 0.4)))");
    assert!(red == plain);
}

#[test]
fn every_shipped_preset_still_reads_and_writes_back_unchanged() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    for p in texplore::scene::list_presets(&dir).unwrap() {
        let desc = texplore::scene::load_preset(&p).unwrap();
        let again = parse_preset(&texplore::scene::to_ron(&desc), &p).unwrap();
        assert_eq!(desc, again, "{}", p.display());
    }
}

#[test]
fn a_bad_texture_in_a_coefficient_names_the_parameter() {
    let text = SCENE.replace(
        "MATERIAL",
        "Phong(ks: Checker(squares: (0, 4)), cd: Constant((1, 1, 1)))",
    );
    let path = Path::new("p.ron");
    let desc = parse_preset(&text, path).unwrap();
    let e = build_scene(&desc, path, &mut AssetCache::new())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("p.ron: objects[0].material.ks.squares: (0.0, 4.0) must be positive"),
        "{e}"
    );
    let text = SCENE.replace(
        "MATERIAL",
        r#"Phong(ks: Image(path: "no-such-mask.png"), cd: Constant((1, 1, 1)))"#,
    );
    let desc = parse_preset(&text, path).unwrap();
    let e = build_scene(&desc, path, &mut AssetCache::new())
        .unwrap_err()
        .to_string();
    assert!(e.contains("no-such-mask.png"), "{e}");
}

// ---------------------------------------------------------------------------------------------
// (u, v) transforms (part 2).

use texplore::mapping::{Mapping, TexCoord, UvTransform};
use texplore::math::{Vec2, Vec3A};

#[test]
fn a_uv_transform_scales_then_rotates_then_offsets() {
    let t = UvTransform {
        scale: Vec2::new(2.0, 3.0),
        rotate: 90.0,
        offset: Vec2::new(0.5, 0.25),
    };
    let a = t.affine().expect("not the identity");
    let tc = a.apply(TexCoord {
        uv: Vec2::new(0.1, 0.2),
        duvdx: Vec2::new(0.01, 0.0),
        duvdy: Vec2::new(0.0, 0.01),
    });
    // (0.1, 0.2) scaled is (0.2, 0.6); turned a quarter anticlockwise (-0.6, 0.2); offset.
    assert!(
        (tc.uv - Vec2::new(-0.1, 0.45)).length() < 1e-6,
        "{:?}",
        tc.uv
    );
    assert!(
        (tc.duvdx - Vec2::new(0.0, 0.02)).length() < 1e-7,
        "{:?}",
        tc.duvdx
    );
    assert!(
        (tc.duvdy - Vec2::new(-0.03, 0.0)).length() < 1e-7,
        "{:?}",
        tc.duvdy
    );
    assert!(UvTransform::IDENTITY.affine().is_none());
}

#[test]
fn transformed_derivatives_match_finite_differences() {
    let t = UvTransform {
        scale: Vec2::new(3.0, 0.5),
        rotate: 37.0,
        offset: Vec2::new(-0.2, 0.7),
    }
    .affine()
    .unwrap();
    let p = Vec3A::new(0.3, 0.4, 0.866).normalize();
    let tangent_x = Vec3A::new(0.0, -0.866, 0.4).normalize() * 1e-3;
    let tangent_y = p.cross(tangent_x);
    for mapping in [
        Mapping::Spherical,
        Mapping::Cylindrical,
        Mapping::Rectangular,
    ] {
        let tc = t.apply(mapping.map_with_differentials(p, tangent_x, tangent_y, None, mapping));
        for (d, analytic) in [(tangent_x, tc.duvdx), (tangent_y, tc.duvdy)] {
            let uv = |q: Vec3A| {
                t.apply(TexCoord {
                    uv: mapping.map_uv(q),
                    ..TexCoord::default()
                })
                .uv
            };
            let central = (uv(p + d * 0.5) - uv(p - d * 0.5)) * 1.0;
            assert!(
                (central - analytic).length() < 1e-3 * analytic.length().max(1e-4),
                "{mapping:?}: finite difference {central:?}, analytic {analytic:?}"
            );
        }
    }
}

#[test]
fn tiling_by_two_equals_twice_the_squares() {
    let tiled =
        render("Matte(cd: Checker(mapping: Rectangular, squares: (4, 4), uv: (scale: (2, 2))))");
    let doubled = render("Matte(cd: Checker(mapping: Rectangular, squares: (8, 8)))");
    assert!(tiled == doubled);
    let plain = render("Matte(cd: Checker(mapping: Rectangular, squares: (4, 4)))");
    assert!(tiled != plain);
    // An offset of one checker square swaps the colours.
    let shifted = render(
        "Matte(cd: Checker(mapping: Rectangular, squares: (4, 4), uv: (offset: (0.25, 0))))",
    );
    let swapped = render(
        "Matte(cd: Checker(mapping: Rectangular, squares: (4, 4), \
         colors: ((0.05, 0.05, 0.05), (0.8, 0.8, 0.8))))",
    );
    assert!(shifted == swapped);
}

#[test]
fn wrap_modes_matter_on_a_sphere_once_the_texture_is_tiled() {
    let sphere = |wrap: &str| {
        let text = SCENE.replace("shape: Rectangle", "shape: Sphere").replace(
            "MATERIAL",
            &format!("Matte(cd: UvGrid(mapping: Spherical, wrap: {wrap}, uv: (scale: (2, 2))))"),
        );
        let path = Path::new("sphere.ron");
        let desc = parse_preset(&text, path).unwrap();
        let scene = build_scene(&desc, path, &mut AssetCache::new()).unwrap();
        render_blocking(&scene, |_| {}).to_linear()
    };
    let repeat = sphere("Repeat");
    let clamp = sphere("Clamp");
    let differ = repeat.iter().zip(&clamp).filter(|(a, b)| a != b).count();
    assert!(differ > 100, "{differ} pixels differ");
}

// ---------------------------------------------------------------------------------------------
// The reflective material (part 3).

fn render_text(text: &str) -> Vec<Rgb> {
    let path = Path::new("mirror.ron");
    let desc = parse_preset(text, path).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let scene = build_scene(&desc, path, &mut AssetCache::new()).unwrap_or_else(|e| panic!("{e}"));
    let film = render_blocking(&scene, |_| {});
    assert!(film.is_finite());
    film.to_linear()
}

/// A mirror floor under a checker sphere, lit; `DEPTH` and `MATERIAL` replaced.
const MIRROR: &str = r"(
    version: 1,
    camera: (eye: (0, 1.5, 5), look_at: (0, 0.3, 0), projection: Pinhole(fov: 45)),
    render: (width: 48, height: 36, spp: 1, sampler: Regular, background: (0.1, 0.2, 0.3),
             reflection_depth: DEPTH),
    ambient: (ls: 0.3),
    lights: [Directional(direction: (1, 2, 1))],
    objects: [
        (shape: Rectangle, transform: (scale: (3, 1, 3)), material: MATERIAL),
        (shape: Sphere, transform: (translate: (0, 1.2, 0), scale: (0.8, 0.8, 0.8)),
         material: Matte(cd: Checker(squares: (8, 4)))),
    ],
)";

fn mirror(depth: u32, material: &str) -> Vec<Rgb> {
    render_text(
        &MIRROR
            .replace("DEPTH", &depth.to_string())
            .replace("MATERIAL", material),
    )
}

#[test]
fn reflection_depth_zero_is_the_old_phong() {
    let params = "ka: 0.3, kd: 0.6, ks: 0.5, exp: 30, cd: Constant((0.4, 0.5, 0.6))";
    let reflective = mirror(
        0,
        &format!("Reflective({params}, kr: 0.8, cr: (1, 0.9, 0.8))"),
    );
    let phong = mirror(0, &format!("Phong({params})"));
    assert!(reflective == phong);
    // With bounces the mirror shows something: the images differ.
    let bouncing = mirror(
        4,
        &format!("Reflective({params}, kr: 0.8, cr: (1, 0.9, 0.8))"),
    );
    assert!(bouncing != phong);
}

#[test]
fn a_perfect_mirror_shows_the_sphere_and_the_background() {
    let black = "cd: Constant((0, 0, 0)), ka: 0, kd: 0, ks: 0";
    let full = mirror(1, &format!("Reflective({black}, kr: 1)"));
    let half = mirror(1, &format!("Reflective({black}, kr: 0.5)"));
    let off = mirror(0, &format!("Reflective({black}, kr: 1)"));
    // Where the bottom rows see the floor, the mirror of the background is the background.
    let (w, h) = (48, 36);
    let bg = Rgb(0.1, 0.2, 0.3);
    let mut reflected_bg = 0;
    let mut reflected_sphere = 0;
    for y in h * 2 / 3..h {
        for x in 0..w {
            let i = y * w + x;
            if off[i] != Rgb::BLACK {
                continue; // not the mirror
            }
            if full[i] == bg {
                reflected_bg += 1;
                assert_eq!(half[i], bg * 0.5, "pixel ({x}, {y})");
            } else {
                reflected_sphere += 1;
                // Halving kr halves what the mirror shows, exactly.
                assert_eq!(half[i], full[i] * 0.5, "pixel ({x}, {y})");
            }
        }
    }
    assert!(
        reflected_bg > 50 && reflected_sphere > 50,
        "{reflected_bg} {reflected_sphere}"
    );
}

#[test]
fn textures_seen_in_a_mirror_are_filtered() {
    // A fine checker far along a mirror floor, at 1 sample per pixel: with its footprint
    // (EWA, through the mirrored differentials) it averages to grey; point-sampled it
    // aliases into noise.
    let scene = |filter: &str| {
        render_text(&format!(
            r"(
    version: 1,
    camera: (eye: (0, 0.3, 4), look_at: (0, 0.3, 0), projection: Pinhole(fov: 40)),
    render: (width: 64, height: 48, spp: 1, sampler: Regular),
    ambient: (ls: 1),
    objects: [
        (shape: Rectangle, transform: (scale: (4, 1, 8)),
         material: Reflective(cd: Constant((0, 0, 0)), ka: 0, kd: 0, ks: 0, kr: 1)),
        (shape: Rectangle, transform: (translate: (0, 0.6, -4), scale: (4, 1, 4)),
         material: Matte(ka: 1, kd: 0, cd: Checker(mapping: Rectangular, squares: (200, 200),
                         colors: ((1, 1, 1), (0, 0, 0)), filter: {filter}))),
    ],
)"
        ))
    };
    let contrast = |img: &[Rgb]| {
        // Mean absolute difference between horizontal neighbours over the mirror's rows.
        let (w, h) = (64, 48);
        let mut sum = 0.0;
        let mut n = 0;
        for y in h / 2 + 2..h * 3 / 4 {
            for x in 1..w {
                let (a, b) = (img[y * w + x], img[y * w + x - 1]);
                sum += (a.luminance() - b.luminance()).abs();
                n += 1;
            }
        }
        sum / n as f32
    };
    let nearest = contrast(&scene("Nearest"));
    let ewa = contrast(&scene("Ewa"));
    assert!(
        nearest > 0.1,
        "the point-sampled reflection should alias: {nearest}"
    );
    assert!(
        ewa < nearest * 0.25,
        "filtered {ewa} against point-sampled {nearest}"
    );
}

// ---------------------------------------------------------------------------------------------
// The orthographic camera (part 4).

#[test]
fn the_orthographic_camera_sees_parallel_rays_of_the_stated_height() {
    use texplore::camera::{Camera, Projection};
    let cam = Camera::new(
        Vec3A::new(0.0, 0.0, 5.0),
        Vec3A::ZERO,
        Vec3A::Y,
        Projection::Orthographic { height: 2.0 },
        40,
        20,
    );
    // The film is 2 units high and 4 wide (the aspect ratio), centred on the eye.
    let top_left = cam.primary_ray(Vec2::new(0.0, 0.0)).unwrap();
    let bottom_right = cam.primary_ray(Vec2::new(40.0, 20.0)).unwrap();
    assert!((top_left.origin - Vec3A::new(-2.0, 1.0, 5.0)).length() < 1e-6);
    assert!((bottom_right.origin - Vec3A::new(2.0, -1.0, 5.0)).length() < 1e-6);
    assert_eq!(top_left.dir, bottom_right.dir);
    // Differentials: the neighbours start one pixel (0.1 units) over, in the same direction.
    let (ray, diff) = cam.ray(Vec2::new(20.0, 10.0), 1.0).unwrap();
    assert!((diff.rx_origin - ray.origin - Vec3A::new(0.1, 0.0, 0.0)).length() < 1e-6);
    assert!((diff.ry_origin - ray.origin - Vec3A::new(0.0, -0.1, 0.0)).length() < 1e-6);
    assert_eq!(diff.rx_dir, ray.dir);
    // A unit sphere fills a view 2 units high, whatever the distance: a pixel row through its
    // centre is lit from edge to edge, and the same at eye distance 5 and 50.
    let row = |eye_z: f32| {
        let text = format!(
            "(version: 1, camera: (eye: (0, 0, {eye_z}), projection: Orthographic(height: 2)),
              render: (width: 40, height: 20, spp: 1, sampler: Regular),
              objects: [(shape: Sphere, material: Emissive(ce: Constant((1, 1, 1))))])"
        );
        let img = render_text(&text);
        (0..40).filter(|x| img[10 * 40 + x] != Rgb::BLACK).count()
    };
    assert_eq!(row(5.0), 20);
    assert_eq!(row(50.0), 20);
}

// ---------------------------------------------------------------------------------------------
// Presets (part 5).

/// The RMSE, in display units (sRGB-encoded [0, 1] after the preset's exposure), over the
/// disc, between the ray-traced mirror ball of `presets/mirror-ball-probe.ron` (16 spp) and
/// `texplore probe --format mirror-ball` of the same panorama (3 x 3 supersampled), both
/// 128 x 128, stays below this. Measured 0.021: what differs is mostly the rim of the ball,
/// where one pixel spans half the panorama and the two paths filter it differently.
const MIRROR_BALL_RMSE: f64 = 0.03;

#[test]
fn the_mirror_ball_preset_is_the_mirror_ball_probe_of_its_panorama() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = tempfile::tempdir().unwrap();
    let probe_path = tmp.path().join("probe.hdr");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(root)
        .args(["probe", "assets/courtyard_1024x512.hdr", "-o"])
        .arg(&probe_path)
        .args(["--size", "128", "--format", "mirror-ball"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let probe = texplore::texture::load_image(&probe_path, true).unwrap();

    let preset = root.join("presets/mirror-ball-probe.ron");
    let mut desc = texplore::scene::load_preset(&preset).unwrap();
    desc.render.width = 128;
    desc.render.height = 128;
    desc.render.spp = 16;
    let scene = build_scene(&desc, &preset, &mut AssetCache::new()).unwrap();
    let film = render_blocking(&scene, |_| {});
    let exposure = scene.settings.exposure_scale;
    let traced = texplore::math::DisplayImage::from_linear(128, 128, &film.to_linear(), exposure);
    let probe_pixels: Vec<Rgb> = (0..128)
        .flat_map(|y| (0..128).map(move |x| (x, y)))
        .map(|(x, y)| probe.texel_top(x, y))
        .collect();
    let direct = texplore::math::DisplayImage::from_linear(128, 128, &probe_pixels, exposure);
    let (a, b) = (traced.rgb(), direct.rgb());
    // The probe is the disc; around it the render sees the panorama behind the ball. Compare
    // the pixels whose centres lie inside the disc.
    let inside = |i: usize| {
        let (x, y) = ((i / 3) % 128, (i / 3) / 128);
        let (dx, dy) = ((x as f64 + 0.5) / 64.0 - 1.0, (y as f64 + 0.5) / 64.0 - 1.0);
        dx * dx + dy * dy < 1.0
    };
    let (mut sum, mut n) = (0.0, 0usize);
    for (i, (&p, &q)) in a.iter().zip(&b).enumerate() {
        if inside(i) {
            sum += (f64::from(p) - f64::from(q)).powi(2) / (255.0 * 255.0);
            n += 1;
        }
    }
    let rmse = (sum / n as f64).sqrt();
    eprintln!("mirror-ball probe: RMSE {rmse:.4} between the ray-traced ball and `texplore probe`");
    assert!(rmse < MIRROR_BALL_RMSE, "RMSE {rmse}");
    // Not trivially so: the image has content (a black or flat render would not match).
    let mean = b.iter().map(|&v| f64::from(v)).sum::<f64>() / b.len() as f64 / 255.0;
    assert!(mean > 0.1, "{mean}");
}

/// The ocean mask of `earth-day-night` (its `ks`), derived from the Blue Marble: a day pixel is
/// ocean where blue leads red by more than 10 (of 255) and is at least green (the dark navy of
/// the sea; not ice, desert or forest); each mask pixel is the share of ocean in a 2 x 2 block
/// of the day image, as 0-255 grey. This test is the recipe: it derives the mask again and
/// compares it with the shipped file byte for byte; `TEXPLORE_WRITE_OCEAN_MASK=1` writes it.
#[test]
fn the_ocean_mask_is_derived_from_the_day_image() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let day = image::open(root.join("assets/earth_2048x1024.jpg"))
        .unwrap()
        .to_rgb8();
    let (w, h) = (day.width() / 2, day.height() / 2);
    let ocean = |x: u32, y: u32| {
        let [r, g, b] = day.get_pixel(x, y).0.map(i32::from);
        u32::from(b > r + 10 && b >= g)
    };
    let mask = image::GrayImage::from_fn(w, h, |x, y| {
        let n = ocean(2 * x, 2 * y)
            + ocean(2 * x + 1, 2 * y)
            + ocean(2 * x, 2 * y + 1)
            + ocean(2 * x + 1, 2 * y + 1);
        image::Luma([(n * 255 / 4) as u8])
    });
    let shipped = root.join("assets/earth_ocean_mask_1024x512.png");
    if std::env::var_os("TEXPLORE_WRITE_OCEAN_MASK").is_some() {
        mask.save(&shipped).unwrap();
    }
    let on_disk = image::open(&shipped).unwrap().to_luma8();
    assert!(
        on_disk == mask,
        "{} differs from its recipe",
        shipped.display()
    );
    // Most of the Earth is ocean; the mask says so (about 70 % of the map's pixels are ocean;
    // the poles' ice is not).
    let share = mask.pixels().map(|p| f64::from(p.0[0])).sum::<f64>() / (255.0 * f64::from(w * h));
    assert!((0.5..0.8).contains(&share), "ocean share {share}");
}

#[test]
fn the_glow_shows_only_where_the_light_does_not_reach() {
    let sphere = |extra: &str| {
        render_text(&format!(
            "(version: 1, camera: (eye: (0, 0, 4)),
              render: (width: 40, height: 30, spp: 1, sampler: Regular),
              ambient: (ls: 0.1),
              lights: [Directional(direction: (1, 0, 0))],
              objects: [(shape: Sphere,
                         material: Phong(cd: Constant((0.5, 0.5, 0.5)){extra}))])"
        ))
    };
    let plain = sphere("");
    let black = sphere(", ce: (0, 0, 0)");
    assert!(plain == black, "a black glow is no glow");
    let glowing = sphere(", ce: Checker(colors: ((0, 1, 0), (0, 1, 0)))");
    let (w, h) = (40usize, 30usize);
    let (mut dark, mut day) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if plain[i] == Rgb::BLACK {
                continue; // the background
            }
            if x < w / 2 - 2 {
                // The left half faces away from the light: the glow is added in full.
                assert_eq!(glowing[i], plain[i] + Rgb(0.0, 1.0, 0.0), "({x}, {y})");
                dark += 1;
            } else if x > w / 2 + 4 {
                // Well into the lit half: unchanged.
                assert_eq!(glowing[i], plain[i], "({x}, {y})");
                day += 1;
            }
        }
    }
    assert!(dark > 50 && day > 30, "{dark} {day}");
}

// ---------------------------------------------------------------------------------------------
// Clip maps (part 6).

/// The cut-out of the `cutout` preset, `assets/cutout_holes_256.png`: a wooden board (RGB) with
/// a 4 x 4 grid of round holes and a star in alpha, edges antialiased by 4 x 4 supersampling.
/// This test is the recipe (no free image fitted): it draws the board again and compares it
/// with the shipped file byte for byte; `TEXPLORE_WRITE_CUTOUT=1` writes it.
#[test]
fn the_cutout_image_is_drawn_by_its_recipe() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let n = 256u32;
    let solid = |x: f32, y: f32| {
        // Holes: circles of radius 0.3 cell in a 4 x 4 grid, the centre cells a five-point star.
        let (cx, cy) = ((x * 4.0).floor(), (y * 4.0).floor());
        let (fx, fy) = (x * 4.0 - cx - 0.5, y * 4.0 - cy - 0.5);
        let centre = (1.0..=2.0).contains(&cx) && (1.0..=2.0).contains(&cy);
        if centre {
            let (dx, dy) = (x - 0.5, y - 0.5);
            let r = (dx * dx + dy * dy).sqrt();
            let a = dy.atan2(dx) * 5.0 / 2.0;
            let star = 0.13 + 0.09 * (a.cos().abs() * 2.0 - 1.0).max(0.0);
            r > star
        } else {
            fx * fx + fy * fy > 0.3 * 0.3
        }
    };
    let board = image::RgbaImage::from_fn(n, n, |px, py| {
        let mut cover = 0u32;
        for sy in 0..4 {
            for sx in 0..4 {
                let x = (px as f32 + (sx as f32 + 0.5) / 4.0) / n as f32;
                let y = (py as f32 + (sy as f32 + 0.5) / 4.0) / n as f32;
                cover += u32::from(solid(x, y));
            }
        }
        let grain = ((py as f32 * 0.35).sin() * 0.5 + 0.5) * 40.0;
        let alpha = (cover * 255 / 16) as u8;
        image::Rgba([(150.0 + grain) as u8, (95.0 + grain * 0.6) as u8, 50, alpha])
    });
    let shipped = root.join("assets/cutout_holes_256.png");
    if std::env::var_os("TEXPLORE_WRITE_CUTOUT").is_some() {
        board.save(&shipped).unwrap();
    }
    let on_disk = image::open(&shipped).unwrap().to_rgba8();
    assert!(
        on_disk == board,
        "{} differs from its recipe",
        shipped.display()
    );
}

/// The floor under `cutout`'s board, lit through it, seen from straight above; and the board
/// itself seen from straight above (white where it exists). The light comes from (-1, 1, 0), the
/// board is 2 above the floor, so the shadow is the board moved 2 along +x.
fn cutout_views(filter: &str) -> (Vec<Rgb>, Vec<Rgb>) {
    let scene = |centre_x: f32, floor: bool| {
        let floor_obj = if floor {
            "(shape: Plane, material: Matte(ka: 0, kd: 1, cd: Constant((1, 1, 1)))),"
        } else {
            ""
        };
        let board_material = if floor {
            "Matte(cd: Constant((0.5, 0.5, 0.5)))"
        } else {
            "Emissive(ce: Constant((1, 1, 1)))"
        };
        format!(
            r#"(version: 1,
                camera: (eye: ({centre_x}, 10, 0), look_at: ({centre_x}, 0, 0), up: (0, 0, -1),
                         projection: Orthographic(height: 2)),
                render: (width: 64, height: 64, spp: 1, sampler: Regular),
                ambient: (ls: 0),
                lights: [Directional(direction: (-1, 1, 0), ls: 1)],
                objects: [
                    {floor_obj}
                    (shape: Rectangle, transform: (translate: (0, 2, 0), scale: (0.95, 1, 0.95)),
                     material: {board_material}, casts_shadows: Some(true),
                     alpha: (texture: Image(path: "assets/cutout_holes_256.png",
                             mapping: Rectangular, filter: {filter}), channel: Alpha)),
                ])"#
        )
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let render_at = |text: String| {
        let path = root.join("cutout-test.ron");
        let desc = parse_preset(&text, &path).unwrap();
        let scene = build_scene(&desc, &path, &mut AssetCache::new()).unwrap();
        let film = render_blocking(&scene, |_| {});
        assert!(film.is_finite());
        film.to_linear()
    };
    (render_at(scene(2.0, true)), render_at(scene(0.0, false)))
}

#[test]
fn a_clip_maps_shadow_has_the_cut_outs_shape() {
    let (floor, board) = cutout_views("Nearest");
    let lit_floor = Rgb::WHITE * (std::f32::consts::FRAC_1_SQRT_2 / std::f32::consts::PI);
    // Seen from above against black, the white board shows its alpha `a`; the floor under it
    // receives the light times the board's transmittance `1 - a` at the shadow ray's crossing,
    // the same point of the board: the shadow is the cut-out, texel for texel.
    let (mut shadow, mut hole, mut wrong) = (0, 0, 0);
    for (f, b) in floor.iter().zip(&board) {
        let expected = lit_floor.1 * (1.0 - b.1);
        if (f.1 - expected).abs() > 0.01 {
            wrong += 1;
        }
        shadow += usize::from(b.1 > 0.99);
        hole += usize::from(b.1 < 0.01);
    }
    assert!(
        shadow > 1000 && hole > 500,
        "{shadow} in shadow, {hole} in holes"
    );
    assert!(
        wrong < 20,
        "{wrong} pixels disagree ({shadow} shadow, {hole} hole)"
    );
}

#[test]
fn a_filtered_alpha_gives_soft_edges_at_one_sample() {
    // Seen directly, the board's edges against black: nearest alpha is 0 or 1 per pixel; the
    // EWA-filtered alpha blends partly covered pixels.
    let (_, hard) = cutout_views("Nearest");
    let (_, soft) = cutout_views("Ewa");
    let partial = |img: &[Rgb]| img.iter().filter(|c| c.1 > 0.02 && c.1 < 0.98).count();
    let (ph, ps) = (partial(&hard), partial(&soft));
    assert!(
        ps > ph + 100,
        "partly covered pixels: {ph} nearest, {ps} EWA"
    );
}

#[test]
fn an_image_without_alpha_is_refused_as_a_clip_map() {
    let text = SCENE.replace(
        "objects: [(shape: Rectangle, material: MATERIAL)]",
        r#"objects: [(shape: Rectangle, material: Matte(cd: Constant((1, 1, 1))),
            alpha: (texture: Image(path: "assets/earth_2048x1024.jpg"), channel: Alpha))]"#,
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("p.ron");
    let desc = parse_preset(&text, &path).unwrap();
    let e = build_scene(&desc, &path, &mut AssetCache::new())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("earth_2048x1024.jpg") && e.contains("no alpha channel"),
        "{e}"
    );
}

// ---------------------------------------------------------------------------------------------
// Bump maps (part 5).

#[test]
fn a_flat_height_map_changes_nothing() {
    let base = "Phong(ks: 0.5, exp: 10, cd: Checker(mapping: Rectangular))";
    let plain = render(base);
    for height in [
        "Constant((0.4, 0.4, 0.4))",
        "Checker(colors: ((0.3, 0.3, 0.3), (0.3, 0.3, 0.3)), filter: Ewa)",
    ] {
        let text = SCENE.replace("MATERIAL", base).replace(
            "material: Phong",
            &format!("bump: (height: {height}, scale: 0.5), material: Phong"),
        );
        let flat = render_text(&text);
        assert!(flat == plain, "{height}");
    }
    // A height that varies does change the image.
    let text = SCENE.replace("MATERIAL", base).replace(
        "material: Phong",
        "bump: (height: UvGrid(mapping: Rectangular), scale: 0.05), material: Phong",
    );
    assert!(render_text(&text) != plain);
}

#[test]
fn bumped_normals_are_finite_and_unit_at_poles_seams_and_degenerate_triangles() {
    use texplore::material::{Bump, dual_basis};
    use texplore::scene::Perturbation;
    use texplore::texture::TextureContext;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("bump-test.ron");
    let text = r#"(version: 1, camera: (eye: (0, 0, 4)),
        objects: [(shape: Sphere, material: Matte(cd: Constant((1, 1, 1))),
                   bump: (height: Image(path: "assets/brick_gray_512.png", mapping: Spherical,
                          filter: Ewa), scale: 0.5))])"#;
    let desc = parse_preset(text, &path).unwrap();
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).unwrap();
    let Some(Perturbation::Bump(bump)) = &scene.surfaces[0].perturbation else {
        panic!("the object has a bump map");
    };
    let points = [
        Vec3A::Y,                                // north pole
        -Vec3A::Y,                               // south pole
        Vec3A::new(0.0, 0.0, 1.0),               // the seam (u = 0)
        Vec3A::new(-1e-7, 0.0, 1.0).normalize(), // just across it
        Vec3A::new(0.6, 0.0, -0.8),
        Vec3A::new(1e-20, 1.0, 1e-20).normalize(),
    ];
    for p in points {
        for (dpdx, dpdy) in [
            (Vec3A::ZERO, Vec3A::ZERO),
            (Vec3A::new(1e-3, 0.0, 0.0), Vec3A::new(0.0, 0.0, 1e-3)),
        ] {
            let ctx = TextureContext {
                p,
                dpdx,
                dpdy,
                shape_uv: None,
                natural: Mapping::Spherical,
            };
            let n = bump.perturb(&ctx, p);
            assert!(
                n.is_finite() && (n.length() - 1.0).abs() < 1e-5,
                "{p:?}: {n:?}"
            );
        }
    }
    // A degenerate (u, v) layout on a mesh triangle has no slope to follow: the normal stays.
    assert_eq!(
        dual_basis(Vec3A::X, Vec3A::X * 2.0),
        (Vec3A::ZERO, Vec3A::ZERO)
    );
    let ctx = TextureContext {
        p: Vec3A::ZERO,
        dpdx: Vec3A::ZERO,
        dpdy: Vec3A::ZERO,
        shape_uv: Some((Vec2::new(0.3, 0.3), Some((Vec3A::X, Vec3A::X)))),
        natural: Mapping::Spherical,
    };
    let uv_bump = Bump {
        height: bump.height.clone(),
        scale: 0.5,
    };
    let mut uv_bump = uv_bump;
    if let texplore::texture::Texture::Image(t) = &mut uv_bump.height {
        t.mapping = Mapping::Uv.into();
    }
    assert_eq!(uv_bump.perturb(&ctx, Vec3A::Z), Vec3A::Z);
    // Rendered: every pixel finite, also where the bumped normal would face away.
    let film = render_blocking(&scene, |_| {});
    assert!(film.is_finite());
}

// ---------------------------------------------------------------------------------------------
// Normal maps (part 5).

/// The normal map of `bumps`, `assets/brick_normal_512.png`, derived from the brick photograph
/// as a height field: heights h = grey / 255 (raw, not sRGB-decoded), slopes by central
/// differences per unit of u and v (the image repeats at its edges; v grows upwards, rows
/// downwards), strength S = 0.01 (a height of 1 stands S units above a surface one unit per
/// u): n = normalize(-S dh/du, -S dh/dv, 1), each component stored as round(127 n + 128).
/// This test is the recipe: it derives the map again and compares it with the shipped file
/// byte for byte; `TEXPLORE_WRITE_NORMAL_MAP=1` writes it.
#[test]
fn the_brick_normal_map_is_derived_from_the_height_field() {
    const S: f32 = 0.01;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let height = image::open(root.join("assets/brick_gray_512.png"))
        .unwrap()
        .to_luma8();
    let (w, h) = (height.width(), height.height());
    let at = |x: i64, y: i64| {
        let (x, y) = (x.rem_euclid(i64::from(w)), y.rem_euclid(i64::from(h)));
        f32::from(height.get_pixel(x as u32, y as u32).0[0]) / 255.0
    };
    let map = image::RgbImage::from_fn(w, h, |x, y| {
        let (x, y) = (i64::from(x), i64::from(y));
        let dhdu = (at(x + 1, y) - at(x - 1, y)) * 0.5 * w as f32;
        let dhdv = (at(x, y - 1) - at(x, y + 1)) * 0.5 * h as f32;
        let (nx, ny, nz) = (-S * dhdu, -S * dhdv, 1.0f32);
        let len = (nx * nx + ny * ny + nz * nz).sqrt();
        let e = |c: f32| (127.0 * c / len + 128.0).round().clamp(0.0, 255.0) as u8;
        image::Rgb([e(nx), e(ny), e(nz)])
    });
    let shipped = root.join("assets/brick_normal_512.png");
    if std::env::var_os("TEXPLORE_WRITE_NORMAL_MAP").is_some() {
        map.save(&shipped).unwrap();
    }
    let on_disk = image::open(&shipped).unwrap().to_rgb8();
    assert!(
        on_disk == map,
        "{} differs from its recipe",
        shipped.display()
    );
    // The library's codec reads the texels back as the unit normals they were made from.
    let p = map.get_pixel(10, 20).0;
    let n = texplore::material::decode_normal(Rgb(
        f32::from(p[0]) / 255.0,
        f32::from(p[1]) / 255.0,
        f32::from(p[2]) / 255.0,
    ));
    assert!((n.length() - 1.0).abs() < 0.02, "{n:?}");
    assert_eq!(texplore::material::encode_normal(n.normalize()), p);
}

/// The rectangle seen from straight above, lit from the side; `OBJECT` is the rectangle's
/// extra fields (a bump or normal map).
const TOP: &str = r"(
    version: 1,
    camera: (eye: (0, 3, 0.0001), look_at: (0, 0, 0), projection: Pinhole(fov: 38)),
    render: (width: 256, height: 256, spp: 1, sampler: Regular),
    ambient: (ls: 0.2),
    lights: [Directional(direction: (-1, 1.2, 0.5), ls: 1.5)],
    objects: [(shape: Rectangle, OBJECT material: Matte(cd: Constant((0.7, 0.7, 0.7))))],
)";

fn top(object: &str) -> Vec<Rgb> {
    render_text(&TOP.replace("OBJECT", object))
}

fn rmse(a: &[Rgb], b: &[Rgb]) -> f32 {
    let sum: f32 = a
        .iter()
        .zip(b)
        .map(|(a, b)| (a.0 - b.0).powi(2) + (a.1 - b.1).powi(2) + (a.2 - b.2).powi(2))
        .sum();
    (sum / (3 * a.len()) as f32).sqrt()
}

#[test]
fn a_flat_normal_map_changes_nothing() {
    let dir = std::env::temp_dir().join(format!("texplore-flat-normal-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let flat = dir.join("flat.png");
    image::RgbImage::from_pixel(8, 8, image::Rgb([128, 128, 255]))
        .save(&flat)
        .unwrap();
    let plain = top("");
    for filter in ["Nearest", "Bilinear", "Trilinear", "Ewa"] {
        let mapped = top(&format!(
            r#"normal: (map: Image(path: "{}", mapping: Rectangular, filter: {filter})),"#,
            flat.display()
        ));
        let worst = plain
            .iter()
            .zip(&mapped)
            .map(|(a, b)| {
                (a.0 - b.0)
                    .abs()
                    .max((a.1 - b.1).abs())
                    .max((a.2 - b.2).abs())
            })
            .fold(0.0f32, f32::max);
        assert!(worst <= 1e-3, "{filter}: {worst}");
    }
    // The brick map does change the image.
    let bricks =
        top(r#"normal: (map: Image(path: "assets/brick_normal_512.png", mapping: Rectangular)),"#);
    assert!(rmse(&bricks, &plain) > 0.02);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Two independent paths: the brick height field as a bump map (the height's filtered finite
/// differences through the mapping's gradients) and its derived normal map (stored normals in
/// the mapping's tangent frame). On the rectangle, u and v run 1 per 2 units, so the map's
/// S = 0.01 at strength 4 (slopes times 4: S = 0.04) is a bump scale of 2 x 0.04 = 0.08. Seen
/// at about 2 texels a pixel (both trilinear), they shade alike within an RMSE of 0.03 (about
/// 0.024 measured; radiance 0.1 to 1.3; the rest is the bump's differences over the pixel's
/// footprint against the map's over two texels); the unmapped rectangle is about 0.054 off,
/// the map with its slopes inverted about 0.077.
#[test]
fn a_normal_map_shades_like_the_bump_map_of_its_height_field() {
    let bump = top(
        r#"bump: (height: Image(path: "assets/brick_gray_512.png", mapping: Rectangular,
                  filter: Trilinear, srgb: false), scale: 0.08),"#,
    );
    let normal = |strength: f32| {
        top(&format!(
            r#"normal: (map: Image(path: "assets/brick_normal_512.png", mapping: Rectangular,
                        filter: Trilinear), strength: {strength}),"#
        ))
    };
    let plain = top("");
    let same = rmse(&normal(4.0), &bump);
    let inverted = rmse(&normal(-4.0), &bump);
    let unmapped = rmse(&plain, &bump);
    eprintln!("RMSE normal vs bump {same}, inverted {inverted}, unmapped {unmapped}");
    assert!(same < 0.03, "{same}");
    assert!(
        inverted > 3.0 * same && unmapped > 1.8 * same,
        "{inverted} {unmapped} {same}"
    );
}

#[test]
fn normal_mapped_normals_are_finite_and_unit_at_poles_seams_and_degenerate_triangles() {
    use texplore::material::NormalMap;
    use texplore::scene::Perturbation;
    use texplore::texture::TextureContext;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("normal-test.ron");
    let text = r#"(version: 1, camera: (eye: (0, 0, 4)),
        objects: [(shape: Sphere, material: Matte(cd: Constant((1, 1, 1))),
                   normal: (map: Image(path: "assets/brick_normal_512.png", mapping: Spherical,
                            filter: Ewa), strength: 3))])"#;
    let desc = parse_preset(text, &path).unwrap();
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).unwrap();
    let Some(Perturbation::Normal(map)) = &scene.surfaces[0].perturbation else {
        panic!("the object has a normal map");
    };
    let points = [
        Vec3A::Y,                                // north pole
        -Vec3A::Y,                               // south pole
        Vec3A::new(0.0, 0.0, 1.0),               // the seam (u = 0)
        Vec3A::new(-1e-7, 0.0, 1.0).normalize(), // just across it
        Vec3A::new(0.6, 0.0, -0.8),
        Vec3A::new(1e-20, 1.0, 1e-20).normalize(),
    ];
    let mut tilted = 0;
    for p in points {
        for (dpdx, dpdy) in [
            (Vec3A::ZERO, Vec3A::ZERO),
            (Vec3A::new(1e-3, 0.0, 0.0), Vec3A::new(0.0, 0.0, 1e-3)),
        ] {
            let ctx = TextureContext {
                p,
                dpdx,
                dpdy,
                shape_uv: None,
                natural: Mapping::Spherical,
            };
            let n = map.perturb(&ctx, p);
            assert!(
                n.is_finite() && (n.length() - 1.0).abs() < 1e-5,
                "{p:?}: {n:?}"
            );
            tilted += usize::from(n.dot(p) < 0.9999);
        }
    }
    // Away from the poles the bricks do tilt the normal.
    assert!(tilted >= 2, "{tilted}");
    // A mesh triangle whose (u, v) layout collapses (dp/du parallel to dp/dv) has no tangent
    // frame: the normal stays.
    let mut uv_map = NormalMap {
        map: map.map.clone(),
        strength: 3.0,
    };
    if let texplore::texture::Texture::Image(t) = &mut uv_map.map {
        t.mapping = Mapping::Uv.into();
    }
    for (dpdu, dpdv) in [
        (Vec3A::X, Vec3A::X),
        (Vec3A::X, Vec3A::X * -2.0),
        (Vec3A::ZERO, Vec3A::Y),
        (Vec3A::Z, Vec3A::X), // along the normal: nothing in the tangent plane
    ] {
        let ctx = TextureContext {
            p: Vec3A::ZERO,
            dpdx: Vec3A::ZERO,
            dpdy: Vec3A::ZERO,
            shape_uv: Some((Vec2::new(0.3, 0.3), Some((dpdu, dpdv)))),
            natural: Mapping::Spherical,
        };
        assert_eq!(
            uv_map.perturb(&ctx, Vec3A::Z),
            Vec3A::Z,
            "{dpdu:?} {dpdv:?}"
        );
    }
    // A proper layout tilts it, and stays unit.
    let ctx = TextureContext {
        p: Vec3A::ZERO,
        dpdx: Vec3A::ZERO,
        dpdy: Vec3A::ZERO,
        shape_uv: Some((Vec2::new(0.3, 0.3), Some((Vec3A::X, Vec3A::Y)))),
        natural: Mapping::Spherical,
    };
    let n = uv_map.perturb(&ctx, Vec3A::Z);
    assert!((n.length() - 1.0).abs() < 1e-5 && n != Vec3A::Z, "{n:?}");
    // Rendered: every pixel finite, also where the mapped normal would face away.
    let film = render_blocking(&scene, |_| {});
    assert!(film.is_finite());
}

#[test]
fn a_bad_normal_map_is_refused_with_its_reason() {
    let path = Path::new("normal-bad.ron");
    let scene = |object: &str| {
        let text = TOP.replace("OBJECT", object);
        let desc = parse_preset(&text, path).unwrap();
        build_scene(&desc, path, &mut AssetCache::new())
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let e = scene(r"normal: (map: Constant((0.5, 0.5, 1))),");
    assert!(
        e.contains("normal.map") && e.contains("no tangent frame"),
        "{e}"
    );
    let e = scene(
        r"bump: (height: UvGrid(mapping: Rectangular)),
           normal: (map: UvGrid(mapping: Rectangular)),",
    );
    assert!(e.contains("both a bump map and a normal map"), "{e}");
    let e = scene(r#"normal: (map: Image(path: "missing_normals.png", mapping: Rectangular)),"#);
    assert!(e.contains("missing_normals.png"), "{e}");
}
