//! The renderer's hot paths: ray-shape intersection per shape, each mapping, each texture filter
//! per lookup, the footprint filter's summed-area table against its tap grid by footprint size
//! (and the table's build), one full 1-spp pass of the Earth, and meshes traced as packets
//! against one ray at a time (`mesh-N`: the `bench --mesh N` scene's primary and shadow rays).
//!
//! `cargo bench --bench hot_paths -- --warm-up-time 1 --measurement-time 3`

#[path = "hot_paths/mesh_packets.rs"]
mod mesh_packets;

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;
use strum::VariantArray;
use texplore::geometry::{Shape, intersect_shape};
use texplore::mapping::{Mapping, TexCoord};
use texplore::math::{Ray, SampleRng, Vec2, Vec3A};
use texplore::names::Named as _;
use texplore::render::{Film, render_pass};
use texplore::scene::{AssetCache, Overrides, apply_overrides, build_scene, load_preset};
use texplore::texture::{
    DEFAULT_MAX_ANISOTROPY, Filter, ImageData, ImageTexture, Lookup, MipPyramid, SummedArea, Wrap,
    footprint, load_image,
};

/// Rays from a camera-like origin toward random points near the unit shapes, so hits and
/// misses mix as in a render.
fn rays(n: usize) -> Vec<Ray> {
    let mut rng = SampleRng::new(1, 2, 3);
    (0..n)
        .map(|_| {
            let target = Vec3A::new(
                rng.next_f32() * 2.4 - 1.2,
                rng.next_f32() * 2.4 - 1.2,
                rng.next_f32() * 2.4 - 1.2,
            );
            let origin = Vec3A::new(0.3, 2.0, 3.6);
            Ray::new(origin, target - origin)
        })
        .collect()
}

fn intersection(c: &mut Criterion) {
    let rays = rays(1024);
    let mut g = c.benchmark_group("intersect");
    for (name, shape) in [
        ("sphere", Shape::Sphere),
        ("cylinder", Shape::Cylinder { capped: false }),
        ("cylinder-capped", Shape::Cylinder { capped: true }),
        ("plane", Shape::Plane),
        ("rectangle", Shape::Rectangle),
        ("disk", Shape::Disk),
    ] {
        let mut i = 0;
        g.bench_function(name, |b| {
            b.iter(|| {
                i = (i + 1) % rays.len();
                black_box(intersect_shape(&shape, black_box(&rays[i]), f32::INFINITY))
            });
        });
    }
    g.finish();
}

fn mappings(c: &mut Criterion) {
    let mut rng = SampleRng::new(4, 5, 6);
    let points: Vec<Vec3A> = (0..1024)
        .map(|_| {
            Vec3A::new(
                rng.next_f32() * 2.0 - 1.0,
                rng.next_f32() * 2.0 - 1.0,
                rng.next_f32() * 2.0 - 1.0,
            )
            .normalize_or(Vec3A::Y)
        })
        .collect();
    let (dpdx, dpdy) = (Vec3A::new(1e-3, 0.0, 0.0), Vec3A::new(0.0, 1e-3, 0.0));
    let mut g = c.benchmark_group("mapping");
    for &m in Mapping::VARIANTS {
        let mut i = 0;
        g.bench_function(m.name(), |b| {
            b.iter(|| {
                i = (i + 1) % points.len();
                black_box(m.map_with_differentials(
                    black_box(points[i]),
                    dpdx,
                    dpdy,
                    None,
                    Mapping::Spherical,
                ))
            });
        });
    }
    g.finish();
}

fn filters(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let image: Arc<ImageData> = Arc::new(
        load_image(&root.join("assets/earth_2048x1024.jpg"), true).expect("the Earth texture"),
    );
    let mut rng = SampleRng::new(7, 8, 9);
    // A footprint of about one texel of a 2048-wide image (magnification to mild minification).
    let coords: Vec<TexCoord> = (0..4096)
        .map(|_| TexCoord {
            uv: Vec2::new(rng.next_f32(), rng.next_f32()),
            duvdx: Vec2::new(1.0 / 1024.0, 0.0),
            duvdy: Vec2::new(0.0, 1.0 / 1024.0),
        })
        .collect();
    let mut g = c.benchmark_group("filter");
    let mip = Arc::new(MipPyramid::build(image.clone()));
    let _ = mip.build_summed_area();
    for &filter in Filter::VARIANTS {
        let tex = ImageTexture {
            image: image.clone(),
            mapping: Mapping::Spherical.into(),
            filter,
            lookup: Lookup::Centred,
            wrap: Wrap::Repeat,
            scale: 1.0,
            mip: filter.needs_mip().then(|| mip.clone()),
            max_anisotropy: DEFAULT_MAX_ANISOTROPY,
            transform: None,
        };
        let mut i = 0;
        g.bench_function(filter.name(), |b| {
            b.iter(|| {
                i = (i + 1) % coords.len();
                black_box(tex.sample(black_box(coords[i])))
            });
        });
    }
    g.finish();
}

/// The footprint filter per lookup on the peer's 2048x1024 checker: its summed-area table
/// against the tap grid it replaced, for footprints 1, 4 and 16 texels wide (a quarter turned,
/// so sheared against the texel grid); and the table's build.
fn footprint_sizes(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let image: Arc<ImageData> = Arc::new(
        load_image(&root.join("assets/tex_checker_2048x1024.png"), false).expect("the checker"),
    );
    let mip = MipPyramid::build(image.clone());
    let _ = mip.build_summed_area();
    let mut rng = SampleRng::new(3, 5, 7);
    let uvs: Vec<Vec2> = (0..4096)
        .map(|_| Vec2::new(rng.next_f32(), rng.next_f32()))
        .collect();
    let (w, h) = (image.width() as f32, image.height() as f32);
    let mut g = c.benchmark_group("footprint");
    for texels in [1.0_f32, 4.0, 16.0] {
        let dx = Vec2::new(texels * 0.97 / w, texels * 0.24 / h);
        let dy = Vec2::new(-texels * 0.24 / w, texels * 0.97 / h);
        let r = Wrap::Repeat;
        let mut i = 0;
        g.bench_function(format!("table-{texels}-texels"), |b| {
            b.iter(|| {
                i = (i + 1) % uvs.len();
                black_box(footprint::footprint(
                    Some(&mip),
                    &image,
                    uvs[i],
                    dx,
                    dy,
                    r,
                    r,
                    DEFAULT_MAX_ANISOTROPY,
                ))
            });
        });
        g.bench_function(format!("taps-{texels}-texels"), |b| {
            b.iter(|| {
                i = (i + 1) % uvs.len();
                black_box(footprint::supersampled(
                    Some(&mip),
                    &image,
                    uvs[i],
                    dx,
                    dy,
                    r,
                    r,
                ))
            });
        });
    }
    g.sample_size(10);
    g.bench_function("table-build-2048x1024", |b| {
        b.iter(|| black_box(SummedArea::for_pyramid(&mip, mip.table_plan()).expect("memory")));
    });
    g.finish();
}

fn earth_pass(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/earth.ron");
    let mut desc = load_preset(&path).expect("presets/earth.ron");
    let (w, h) = (320, 240);
    apply_overrides(
        &mut desc,
        Overrides {
            width: Some(w),
            height: Some(h),
            spp: Some(1),
            ..Overrides::default()
        },
    );
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("the Earth builds");
    let mut film = Film::new(w, h);
    let never = || false;
    let mut g = c.benchmark_group("pass");
    g.throughput(criterion::Throughput::Elements(u64::from(w * h)));
    g.bench_function("earth-320x240-1spp", |b| {
        b.iter(|| black_box(render_pass(&scene, &mut film, 0, &never)));
    });
    g.finish();
}

criterion_group!(
    benches,
    intersection,
    mappings,
    filters,
    footprint_sizes,
    earth_pass,
    mesh_packets::mesh_packets
);
criterion_main!(benches);
