//! A texture costs what it is, once: the texel storage is budgeted from the header before
//! decoding, the pixels are converted straight into it, and truncated image data is an error.
//! Memory cases run the real binary in a child process under an address-space limit
//! (`RLIMIT_AS`), so a copy too many makes the child fail and the test with it.
#![cfg(unix)]

use crate::common::crc32;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use texplore::texture::{Texels, load_image};

pub(crate) const MIB: u64 = 1 << 20;

/// The address space texplore needs besides the texture (binary, stacks, a small decoder state):
/// measured below 80 MiB for `render` of an 8 x 8 image of a 2048 x 1024 JPEG.
pub(crate) const BASELINE: u64 = 128 * MIB;

/// Runs `texplore ARGS` in `dir` with its address space limited to `limit` bytes, one thread and
/// one malloc arena (so the limit measures the program, not the allocator's reservations).
#[allow(unsafe_code)]
pub(crate) fn texplore_limited(dir: &Path, args: &[&str], limit: u64) -> Output {
    use std::os::unix::process::CommandExt;
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_texplore"));
    cmd.args(args)
        .current_dir(dir)
        .env("MALLOC_ARENA_MAX", "1")
        .stdin(Stdio::null());
    let rlim = libc::rlimit {
        rlim_cur: limit as libc::rlim_t,
        rlim_max: limit as libc::rlim_t,
    };
    // SAFETY: between fork and exec the closure only calls setrlimit, which is
    // async-signal-safe, on a value prepared before the fork; it allocates nothing.
    unsafe {
        cmd.pre_exec(move || {
            if libc::setrlimit(libc::RLIMIT_AS, &raw const rlim) == 0 {
                Ok(())
            } else {
                Err(std::io::Error::last_os_error())
            }
        });
    }
    cmd.output().unwrap()
}

/// Renders an 8 x 8 view of a sphere textured with `image` (nearest filter, so no mip pyramid)
/// under `limit` bytes of address space.
fn render_limited(dir: &Path, image: &str, srgb: bool, limit: u64) -> Output {
    let preset = format!(
        r#"(
    version: 1,
    camera: (eye: (0, 0, 3.6), projection: Pinhole(fov: 40)),
    render: (width: 8, height: 8, spp: 1),
    objects: [(
        shape: Sphere,
        material: Matte(ka: 0.6, kd: 0.85, cd: Image(path: "{image}", mapping: Spherical, filter: Nearest, srgb: {srgb})),
    )],
)"#
    );
    std::fs::write(dir.join("p.ron"), preset).unwrap();
    texplore_limited(
        dir,
        &["render", "p.ron", "-o", "out.png", "--threads", "1"],
        limit,
    )
}

pub(crate) fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Writes a `width` x `height` 8-bit grey PNG whose texel (x, y) is `(x + 3 y) % 251`, streamed
/// row by row.
pub(crate) fn grey_png(path: &Path, width: u32, height: u32) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    let mut enc = png::Encoder::new(file, width, height);
    enc.set_color(png::ColorType::Grayscale);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Fastest);
    let mut writer = enc.write_header().unwrap();
    let mut stream = writer.stream_writer().unwrap();
    // Row y is the pattern i % 251 from i = 3 y % 251 on.
    let pattern: Vec<u8> = (0..width as usize + 251).map(|i| (i % 251) as u8).collect();
    for y in 0..height as usize {
        let start = 3 * y % 251;
        stream
            .write_all(&pattern[start..start + width as usize])
            .unwrap();
    }
    stream.finish().unwrap();
}

#[test]
fn a_grey_png_loads_in_its_storage_plus_a_margin() {
    // 8192^2 grey: 256 MiB of sRGB texels. Before, the decoder's grey buffer, an RGB copy, an
    // RGBA copy and the tiled copy took 768 MiB at the peak.
    let dir = tempfile::tempdir().unwrap();
    grey_png(&dir.path().join("grey.png"), 8192, 8192);
    let storage = 8192 * 8192 * 4;
    let out = render_limited(dir.path(), "grey.png", true, BASELINE + storage + 32 * MIB);
    assert!(out.status.success(), "{}", stderr(&out));
    // The limit bites: without room for the storage, the load fails with a message (not an
    // abort), so the test above can fail.
    let out = render_limited(dir.path(), "grey.png", true, storage - 16 * MIB);
    let e = stderr(&out);
    assert!(!out.status.success());
    assert!(
        e.contains("grey.png") && e.contains("out of memory allocating 256.0 MiB for the texels"),
        "{e}"
    );
}

#[test]
fn a_16384_squared_grey_png_takes_1_gib_once_read_as_srgb_or_raw() {
    // A small file of 16384^2 grey texels: 1 GiB as sRGB (the budget, exactly), which took
    // 2.4 GB before; read raw (`srgb: false`) the same 1 GiB of bytes, where it took 3 GiB as
    // linear RGB (refused), and 6.5 GB before that was refused.
    let dir = tempfile::tempdir().unwrap();
    grey_png(&dir.path().join("big.png"), 16384, 16384);
    for srgb in [true, false] {
        let out = render_limited(
            dir.path(),
            "big.png",
            srgb,
            BASELINE + 1024 * MIB + 32 * MIB,
        );
        assert!(out.status.success(), "srgb {srgb}: {}", stderr(&out));
    }
    // Without room for the bytes, the load fails with a message naming the file (not an
    // abort), so the test above can fail.
    let out = render_limited(dir.path(), "big.png", false, BASELINE + 512 * MIB);
    let e = stderr(&out);
    assert!(!out.status.success());
    assert!(
        e.contains("big.png") && e.contains("out of memory allocating 1.0 GiB for the texels"),
        "{e}"
    );
}

/// An 8 x 8 grey baseline JPEG whose frame header then claims `width` x `height`: the
/// entropy-coded data of all but the first block is missing.
fn jpeg_claiming(width: u16, height: u16) -> Vec<u8> {
    let mut out = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 90)
        .encode(&[128u8; 64], 8, 8, image::ExtendedColorType::L8)
        .unwrap();
    let sof = out
        .windows(2)
        .position(|m| m == [0xFF, 0xC0])
        .expect("a baseline frame header");
    // FF C0, length (2), precision (1), height (2), width (2).
    out[sof + 5..sof + 7].copy_from_slice(&height.to_be_bytes());
    out[sof + 7..sof + 9].copy_from_slice(&width.to_be_bytes());
    out
}

#[test]
fn a_small_jpeg_claiming_18000_squared_is_refused_without_allocating() {
    let dir = tempfile::tempdir().unwrap();
    let file = jpeg_claiming(18000, 18000);
    assert!(file.len() < 1024, "{} bytes", file.len());
    std::fs::write(dir.path().join("huge.jpg"), &file).unwrap();
    // Refused from the header: the address space holds no more than the program itself.
    for (srgb, need) in [
        (true, "1.2 GiB as sRGB (4 bytes"),
        (false, "1.2 GiB as raw 8-bit RGB (4 bytes"),
    ] {
        let out = render_limited(dir.path(), "huge.jpg", srgb, BASELINE);
        let e = stderr(&out);
        assert!(!out.status.success());
        assert!(
            e.contains("huge.jpg: cannot load image: 18000 x 18000 texels need ")
                && e.contains(need)
                && e.contains("above the 1.0 GiB texture budget"),
            "{e}"
        );
    }
}

#[test]
fn a_small_jpeg_claiming_a_size_within_the_budget_is_truncated() {
    // 8000^2 fits the budget (244 MiB of texels), but its data is missing: refused, not grey,
    // and before allocating (the limit leaves no room for the texels).
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("claims.jpg"), jpeg_claiming(8000, 8000)).unwrap();
    let out = render_limited(dir.path(), "claims.jpg", true, BASELINE);
    let e = stderr(&out);
    assert!(!out.status.success());
    assert!(
        e.contains("claims.jpg: cannot load image: truncated image data"),
        "{e}"
    );
    let e = load_image(&dir.path().join("claims.jpg"), true)
        .unwrap_err()
        .to_string();
    assert!(e.contains("truncated image data"), "{e}");
}

#[test]
fn headers_claiming_more_than_the_budget_are_refused_before_allocating() {
    let dir = tempfile::tempdir().unwrap();
    let mut ihdr = b"\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR".to_vec();
    ihdr.extend_from_slice(&30000u32.to_be_bytes());
    ihdr.extend_from_slice(&30000u32.to_be_bytes());
    ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
    let crc = crc32(&ihdr[12..]);
    ihdr.extend_from_slice(&crc.to_be_bytes());
    // An empty IDAT: the header is all there is.
    ihdr.extend_from_slice(b"\0\0\0\0IDAT");
    ihdr.extend_from_slice(&crc32(b"IDAT").to_be_bytes());
    let cases: [(&str, Vec<u8>, &str); 3] = [
        (
            "wide.png",
            ihdr,
            "30000 x 30000 texels need 3.4 GiB as sRGB",
        ),
        (
            "grey.pgm",
            b"P5 20000 20000 255\n\x80\x80".to_vec(),
            "20000 x 20000 texels need 1.5 GiB as sRGB",
        ),
        (
            "turned.hdr",
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+X 20000 -Y 10000\n\x80\x80\x80\x88".to_vec(),
            "20000 x 10000 texels need 2.2 GiB as linear RGB",
        ),
    ];
    for (name, data, message) in cases {
        std::fs::write(dir.path().join(name), data).unwrap();
        let out = render_limited(dir.path(), name, true, BASELINE);
        let e = stderr(&out);
        assert!(!out.status.success());
        assert!(
            e.contains(&format!("{name}: cannot load image: {message}"))
                && e.contains("above the 1.0 GiB texture budget"),
            "{name}: {e}"
        );
    }
}

/// The first `bytes` of the repository's asset `name`, written to `dir` as `out`.
fn truncated_asset(dir: &Path, name: &str, bytes: usize, out: &str) {
    let data = std::fs::read(crate::common::root().join("assets").join(name)).unwrap();
    assert!(data.len() > bytes);
    std::fs::write(dir.join(out), &data[..bytes]).unwrap();
}

#[test]
fn the_first_3000_bytes_of_the_earth_jpeg_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    truncated_asset(dir.path(), "earth_2048x1024.jpg", 3000, "earth.jpg");
    // By `render` ...
    let out = render_limited(dir.path(), "earth.jpg", true, BASELINE + 64 * MIB);
    let e = stderr(&out);
    assert!(!out.status.success());
    assert!(
        e.contains("earth.jpg: cannot load image: truncated image data"),
        "{e}"
    );
    assert!(!dir.path().join("out.png").exists());
    // ... by the window, which builds the scene through the same asset cache ...
    let desc = texplore::scene::read_preset_or_png(&dir.path().join("p.ron")).unwrap();
    let mut cache = texplore::scene::AssetCache::new();
    let Err(e) = texplore::scene::build_scene(&desc, &dir.path().join("p.ron"), &mut cache) else {
        panic!("the truncated texture is accepted");
    };
    let e = e.to_string();
    assert!(
        e.contains("earth.jpg") && e.contains("truncated image data"),
        "{e}"
    );
    // ... and by the image loader itself, in either colour space.
    for srgb in [true, false] {
        let e = load_image(&dir.path().join("earth.jpg"), srgb)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("earth.jpg") && e.contains("truncated image data"),
            "{e}"
        );
    }
    // Cut inside the header, or just before the last scan's end: refused too.
    for bytes in [300, 600_000] {
        truncated_asset(dir.path(), "earth_2048x1024.jpg", bytes, "cut.jpg");
        let e = load_image(&dir.path().join("cut.jpg"), true)
            .unwrap_err()
            .to_string();
        assert!(e.contains("truncated image data"), "{bytes} bytes: {e}");
    }
}

#[test]
fn the_whole_earth_jpeg_loads_with_its_colours() {
    let img = load_image(
        &crate::common::root().join("assets/earth_2048x1024.jpg"),
        true,
    )
    .unwrap();
    assert_eq!((img.width(), img.height()), (2048, 1024));
    // The decoder `image` uses gives the same texels (the JPEG is decoded by the same library).
    let reference = image::open(crate::common::root().join("assets/earth_2048x1024.jpg"))
        .unwrap()
        .to_rgb8();
    for (x, y) in [(0, 0), (1024, 512), (2047, 1023), (300, 700), (1500, 100)] {
        let expected = reference.get_pixel(x, y).0;
        let got = img
            .texel_top(x, y)
            .to_array()
            .map(texplore::math::linear_to_srgb8);
        assert_eq!(got, expected, "texel ({x}, {y})");
    }
}

#[test]
fn a_truncated_png_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let full = std::fs::read(crate::common::root().join("assets/coffee_600x400.png")).unwrap();
    truncated_asset(
        dir.path(),
        "coffee_600x400.png",
        full.len() / 2,
        "coffee.png",
    );
    let out = render_limited(dir.path(), "coffee.png", true, BASELINE + 64 * MIB);
    let e = stderr(&out);
    assert!(!out.status.success());
    assert!(e.contains("coffee.png: cannot load image: "), "{e}");
    let e = load_image(&dir.path().join("coffee.png"), true)
        .unwrap_err()
        .to_string();
    assert!(e.contains("coffee.png"), "{e}");
}

#[test]
fn an_image_of_extreme_aspect_loads() {
    let dir = tempfile::tempdir().unwrap();
    for (w, h) in [(1, 100_000), (100_000, 1)] {
        let p = dir.path().join(format!("strip_{w}x{h}.png"));
        grey_png(&p, w, h);
        let img = load_image(&p, true).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((img.width(), img.height()), (w, h));
        // Both ends and the middle hold the texels written, (x + 3 y) % 251.
        for (x, y) in [(0, 0), (w / 2, h / 2), (w - 1, h - 1)] {
            let expected = ((u64::from(x) + 3 * u64::from(y)) % 251) as u8;
            let got = texplore::math::linear_to_srgb8(img.texel_top(x, y).0);
            assert_eq!(got, expected, "{w} x {h} at ({x}, {y})");
        }
        // 4 bytes a texel, rows padded to whole 4 x 4 tiles: 1.6 MB, not a 32768-per-side refusal.
        let Texels::Srgb8(texels) = img.texels() else {
            panic!("8-bit sRGB texels expected");
        };
        assert_eq!(texels.len(), 100_000 * 4);
    }
}

#[test]
fn a_16384_squared_render_is_refused_by_the_render_budget_before_allocating() {
    // A 200-byte preset asking for the largest resolution: the film, the display image and a
    // linear copy would take 11 GiB; under a 6 GB address space it used to abort.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("huge.ron"),
        "(version: 1, camera: (eye: (0, 0, 3.6)), render: (width: 16384, height: 16384, spp: 1), objects: [(shape: Sphere, material: Matte(cd: Constant((0.5, 0.5, 0.5))))])",
    )
    .unwrap();
    let out = texplore_limited(
        dir.path(),
        &["render", "huge.ron", "-o", "out.png"],
        6 << 30,
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("huge.ron")
            && err.contains("16384x16384 pixels need 11.0 GiB")
            && err.contains("above the 2 GiB render budget"),
        "{err}"
    );
    assert!(!dir.path().join("out.png").exists());
    // Just inside the budget (6986 x 6986 needs 2.0 GiB) the settings are accepted.
    let desc: texplore::scene::SceneDesc = ron::from_str(
        "(version: 1, camera: (eye: (0, 0, 3.6)), render: (width: 6986, height: 6986, spp: 1), objects: [(shape: Sphere, material: Matte(cd: Constant((0.5, 0.5, 0.5))))])",
    )
    .unwrap();
    let mut cache = texplore::scene::AssetCache::default();
    let built = texplore::scene::build_scene(&desc, &dir.path().join("p.ron"), &mut cache);
    assert!(built.is_ok(), "{:?}", built.err().map(|e| e.to_string()));
}

/// 24 grey 2048 x 2048 PNGs, `g0.png` to `g23.png`, in `dir` (distinct files, so a scene reading
/// them all builds 24 images, pyramids and tables): the scene of the texture budget's tests.
pub(crate) fn greys_2048(dir: &Path) {
    grey_png(&dir.join("g0.png"), 2048, 2048);
    for i in 1..24 {
        std::fs::copy(dir.join("g0.png"), dir.join(format!("g{i}.png"))).unwrap();
    }
}
