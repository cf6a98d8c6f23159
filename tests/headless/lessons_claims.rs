//! What the lessons' *Look for* sentences claim, measured on renders of the experiments: a
//! colour that appears, a dark side that comes into view, an eye widened by the 3:2 photo, an
//! image that is the mirror of another, blocks that shrink, a horizon that calms but stays
//! grainier than EWA's, a light that does (and a probe that does not) light the scene.
//! Claims that cannot be measured (wedges at a pole, a photo that looks magnified) are looked
//! at by a person before a lesson ships.

use crate::common::root;
use texplore::lesson::{Lesson, find, load_dir};
use texplore::scene::SimdMode;
use texplore::scene::{AssetCache, SceneDesc, load_preset};
use texplore::snapshot::render_snapshot;

fn lesson(name: &str) -> (Lesson, SceneDesc) {
    let loaded = load_dir(&root().join("lessons")).unwrap();
    let l = find(&loaded.lessons, name).unwrap().clone();
    let base = load_preset(&l.preset).unwrap();
    (l, base)
}

/// The scene of the experiment labelled `label`.
fn scene(l: &Lesson, base: &SceneDesc, label: &str) -> SceneDesc {
    let k = l
        .experiments
        .iter()
        .position(|x| x.label == label)
        .unwrap_or_else(|| panic!("{}: no experiment \"{label}\"", l.name));
    l.scene(k, base).unwrap()
}

/// An RGB render of `desc` at `w` x `h` and `spp` samples per pixel.
fn render(desc: &SceneDesc, l: &Lesson, w: u32, h: u32, spp: u32) -> Vec<[u8; 3]> {
    let mut d = desc.clone();
    d.snapshot.width = w;
    d.snapshot.height = h;
    d.snapshot.spp = spp;
    render_snapshot(&d, &l.preset, &mut AssetCache::new(), SimdMode::Auto)
        .unwrap()
        .2
        .chunks(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect()
}

#[test]
fn lesson_1_the_night_side_comes_into_view() {
    let (l, base) = lesson("constant-vs-image");
    let side = scene(&l, &base, "A constant blue, seen from the side");
    // The same blue from the camera's start, for comparison.
    let mut front = base.clone();
    front.objects[0].material = side.objects[0].material.clone();
    // Of the sphere's pixels (blue), the share on the night side: where the light adds
    // nothing, so the render is the one without the light.
    let dark_share = |desc: &SceneDesc| {
        let lit = render(desc, &l, 96, 72, 4);
        let mut ambient = desc.clone();
        ambient.lights.clear();
        let unlit = render(&ambient, &l, 96, 72, 4);
        let sphere: Vec<usize> = (0..lit.len())
            .filter(|&i| lit[i][2] > lit[i][0] + 8)
            .collect();
        let night = sphere
            .iter()
            .filter(|&&i| lit[i][2].abs_diff(unlit[i][2]) <= 2)
            .count();
        night as f64 / sphere.len() as f64
    };
    let from_front = dark_share(&front);
    let from_side = dark_share(&side);
    assert!(
        from_front < 0.1,
        "from the front {from_front:.2} of the sphere is dark"
    );
    assert!(
        from_side > 0.3,
        "from the side only {from_side:.2} of the sphere is dark"
    );
}

#[test]
fn lesson_2_each_right_edge_view_shows_its_own_lookup() {
    let (l, base) = lesson("texel-coordinates");
    let yellow = |img: &[[u8; 3]]| {
        img.iter()
            .filter(|p| p[0] > 150 && p[1] > 120 && p[2] < 80)
            .count()
    };
    let lecture = render(
        &scene(&l, &base, "Fly to the right edge (lecture's lookup)"),
        &l,
        64,
        48,
        1,
    );
    let centred = render(
        &scene(&l, &base, "Fly to the right edge (centred lookup)"),
        &l,
        64,
        48,
        1,
    );
    assert_eq!(yellow(&lecture), 0, "no yellow under the lecture's lookup");
    assert!(
        yellow(&centred) > 64 * 48 / 10,
        "up to the edge it is yellow: {} pixels",
        yellow(&centred)
    );
}

#[test]
fn lesson_7_turning_round_mirrors_the_panoramic_view() {
    let (l, base) = lesson("light-probes");
    let turned = scene(&l, &base, "Turn around to +z");
    // Panoramic without the balls (they stand in its view, not behind the camera).
    let mut panoramic = scene(&l, &base, "Panoramic: flip z");
    panoramic.objects.truncate(1);
    let (w, h) = (64, 48);
    let a = render(&turned, &l, w, h, 4);
    let b = render(&panoramic, &l, w, h, 4);
    let diff = |flip: bool| {
        let mut sum = 0u64;
        for y in 0..h as usize {
            for x in 0..w as usize {
                let xa = if flip { w as usize - 1 - x } else { x };
                let (p, q) = (a[y * w as usize + xa], b[y * w as usize + x]);
                sum += (0..3).map(|c| u64::from(p[c].abs_diff(q[c]))).sum::<u64>();
            }
        }
        sum as f64 / f64::from(w * h * 3)
    };
    let (mirrored, same) = (diff(true), diff(false));
    assert!(
        mirrored < 3.0 && same > 4.0 * mirrored,
        "mirrored: {mirrored:.2} per channel, unmirrored: {same:.2}"
    );
}

/// The mean length of the runs of identical pixels along the rows: large where one texel
/// covers many pixels (flat blocks), near 1 where each pixel reads another texel.
fn run_length(img: &[[u8; 3]], w: usize) -> f64 {
    let mut runs = 0usize;
    for row in img.chunks(w) {
        runs += 1 + row.windows(2).filter(|p| p[0] != p[1]).count();
    }
    img.len() as f64 / runs as f64
}

#[test]
fn lesson_8_both_cures_shrink_the_blocks() {
    let (l, base) = lesson("aliasing");
    let (w, h) = (160, 120);
    let blocks =
        |label: &str| run_length(&render(&scene(&l, &base, label), &l, w, h, 1), w as usize);
    let magnified = blocks("Magnify: the cat up close, nearest");
    let resolution = blocks("Cure 1: a higher-resolution image");
    let distance = blocks("Cure 2: do not zoom in close");
    assert!(
        magnified > 3.0 * resolution,
        "blocks {magnified:.1} px up close, {resolution:.1} with the larger image"
    );
    assert!(
        magnified > 3.0 * distance,
        "blocks {magnified:.1} px up close, {distance:.1} from further away"
    );
}

#[test]
fn lesson_10_the_light_lights_the_earth_and_the_probe_does_not() {
    let (l, base) = lesson("the-lectures-examples");
    let earth = scene(&l, &base, "The Earth in the courtyard");
    let (w, h) = (64, 48);
    // The Earth fills the middle of the frame: a block of 8 x 8 pixels there.
    let middle = |img: &[[u8; 3]]| -> Vec<[u8; 3]> {
        (20..28)
            .flat_map(|y| (28..36).map(move |x| (x, y)))
            .map(|(x, y)| img[y * w as usize + x])
            .collect()
    };
    let sum = |px: &[[u8; 3]]| px.iter().flatten().map(|&c| u32::from(c)).sum::<u32>();
    let lit = middle(&render(&earth, &l, w, h, 1));
    // A probe five times dimmer: the Earth does not change (the probe is emissive only).
    let dim = texplore::lesson::edit::set_path(&earth, "objects[0].material.ls", "0.2").unwrap();
    assert_eq!(middle(&render(&dim, &l, w, h, 1)), lit);
    // Without the directional light it is darker (the ambient term stays): the light lights it.
    let mut unlit = earth.clone();
    unlit.lights.clear();
    let dark = middle(&render(&unlit, &l, w, h, 1));
    assert!(
        sum(&dark) * 10 < sum(&lit) * 8,
        "without the light {} against {}",
        sum(&dark),
        sum(&lit)
    );
}

/// Whether a pixel is the cat's iris: saturated, its hue between 36 and 90 degrees (yellow to
/// olive green; the fur is orange, below 32 degrees, and the pupil is dark).
fn iris(p: [u8; 3]) -> bool {
    let [r, g, b] = p.map(f64::from);
    let (max, min) = (r.max(g).max(b), r.min(g).min(b));
    if max - min < 40.0 || b == max {
        return false;
    }
    let hue = if r == max {
        60.0 * (g - b) / (max - min)
    } else {
        60.0 * (2.0 + (b - r) / (max - min))
    };
    (36.0..90.0).contains(&hue)
}

/// The width over the height of the bounding box of the pixels `keep` selects within
/// `window` (x0, y0, x1, y1) of an image `w` pixels wide, and their count.
fn aspect(
    img: &[[u8; 3]],
    w: usize,
    window: (usize, usize, usize, usize),
    keep: fn([u8; 3]) -> bool,
) -> (f64, usize) {
    let (x0, y0, x1, y1) = window;
    let (mut lo, mut hi, mut n) = ((usize::MAX, usize::MAX), (0, 0), 0);
    for y in y0..y1 {
        for x in x0..x1 {
            if keep(img[y * w + x]) {
                lo = (lo.0.min(x), lo.1.min(y));
                hi = (hi.0.max(x), hi.1.max(y));
                n += 1;
            }
        }
    }
    ((hi.0 + 1 - lo.0) as f64 / (hi.1 + 1 - lo.1) as f64, n)
}

#[test]
fn lesson_6_the_cats_eye_comes_out_wider_and_the_pole_is_in_view() {
    let (l, base) = lesson("spherical-mapping");
    let cat = scene(&l, &base, "The 3:2 cat photo");
    let photo = image::open(root().join("assets/chelsea_451x300.png"))
        .unwrap()
        .to_rgb8();
    let px: Vec<[u8; 3]> = photo.pixels().map(|p| p.0).collect();
    // The photo's left eye: its iris, in the left half around the middle rows.
    let (in_photo, n) = aspect(&px, 451, (100, 60, 230, 180), iris);
    // On the sphere the same eye faces the camera: its iris around the middle of the image.
    let (w, h) = (320, 240);
    let img = render(&cat, &l, w, h, 4);
    let (on_sphere, m) = aspect(&img, w as usize, (60, 50, 260, 210), iris);
    assert!(
        n > 500 && m > 500,
        "iris pixels: {n} in the photo, {m} on the sphere"
    );
    // Widened by 4/3 at the equator, times cos(latitude) of the eye (about 15 degrees north).
    let widened = on_sphere / in_photo;
    assert!(
        (1.1..1.45).contains(&widened),
        "the eye is {in_photo:.2} times as wide as tall in the photo, {on_sphere:.2} on the sphere: {widened:.2}"
    );
    // The north pole, (0, 1, 0) under a turn about y alone, faces the camera.
    let [rx, _, rz] = cat.objects[0].transform.rotate.to_array();
    assert!(rx == 0.0 && rz == 0.0, "turned about y only");
    assert!(cat.camera.eye.y > 1.0, "the camera sees the north pole");
}

/// The mean difference between horizontally neighbouring pixels (summed over R, G, B) in the
/// band of `rows` rows just below the horizon: the first row that is not the sky's colour.
fn graininess(img: &[[u8; 3]], w: usize, rows: usize) -> f64 {
    let sky = img[0];
    let horizon = img
        .chunks(w)
        .position(|row| row.iter().any(|p| p != &sky))
        .expect("the plane is in view");
    let band = &img[horizon * w..(horizon + rows) * w];
    let mut sum = 0u64;
    for row in band.chunks(w) {
        for p in row.windows(2) {
            sum += (0..3)
                .map(|c| u64::from(p[0][c].abs_diff(p[1][c])))
                .sum::<u64>();
        }
    }
    sum as f64 / (rows * (w - 1)) as f64
}

#[test]
fn lesson_8_sixteen_samples_calm_the_horizon_but_leave_it_grainier_than_ewa() {
    let (l, base) = lesson("aliasing");
    let (w, h) = (320, 240);
    let grain = |label: Option<&str>, spp: u32| {
        let desc = label.map_or_else(|| base.clone(), |label| scene(&l, &base, label));
        graininess(&render(&desc, &l, w, h, spp), w as usize, 12)
    };
    // The lesson's own scene is EWA at 1 sample.
    let ewa = grain(None, 1);
    let nearest = grain(Some("Nearest, 1 sample"), 1);
    let sixteen = grain(Some("Nearest, 16 samples"), 16);
    let told =
        format!("along the horizon: EWA {ewa:.1}, nearest {nearest:.1}, 16 samples {sixteen:.1}");
    // Calmer: 16 samples cut the single sample's grain by more than half...
    assert!(sixteen * 2.0 < nearest, "{told}");
    // ...but leave it far grainier than EWA's ("as with EWA" would fail here).
    assert!(sixteen > 2.5 * ewa, "{told}");
}
