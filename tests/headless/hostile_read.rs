//! Hostile and unusual inputs on the reading side: what cannot be read is refused at once with
//! a message naming the file (nothing blocks, nothing reads without end, nothing panics), and
//! valid files that were refused before are read. Every child process runs under a deadline.

use crate::common::crc32;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};
use texplore::meshio::read_obj;
use texplore::texture::load_image;

/// Runs texplore in `dir`, killing it (and failing the test) after `limit`.
fn texplore_in(dir: &Path, args: &[&str], limit: Duration) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_texplore"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let out = child.wait_with_output().unwrap();
            panic!(
                "texplore {args:?} still running after {limit:?} (killed); stderr: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn texplore(dir: &Path, args: &[&str]) -> Output {
    texplore_in(dir, args, Duration::from_mins(1))
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Asserts `out` failed with one line on stderr containing `expected`.
fn refused(out: &Output, expected: &str) {
    let e = stderr(out);
    assert!(!out.status.success(), "succeeded; stderr: {e}");
    assert!(e.contains(expected), "expected '{expected}' in: {e}");
    assert!(!e.contains("panicked"), "{e}");
}

#[cfg(unix)]
fn mkfifo(path: &Path) {
    let ok = Command::new("mkfifo").arg(path).status().unwrap().success();
    assert!(ok, "mkfifo {}", path.display());
}

/// A unit quad in z = 0 with (u, v) = (x, y).
const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";

/// A preset looking straight at the quad of `obj`, lit by ambient light only (so a pixel is
/// the texel), 8 x 6 pixels.
fn quad_preset(obj: &str) -> String {
    format!(
        "(version: 1, camera: (eye: (0.5, 0.5, 3), look_at: (0.5, 0.5, 0), projection: Pinhole(fov: 8)),
          render: (width: 8, height: 6, spp: 1, background: (0, 0, 1)),
          ambient: (ls: 1), lights: [],
          objects: [(shape: Mesh(path: \"{obj}\", shading: Flat),
                     material: Matte(ka: 1, kd: 0, cd: MeshMaterial(filter: Nearest)))])"
    )
}

/// A 2 x 2 PNG of one colour.
fn solid_png(path: &Path, rgb: [u8; 3]) {
    let img = image::RgbImage::from_pixel(2, 2, image::Rgb(rgb));
    img.save(path).unwrap();
}

fn centre_pixel(png: &Path) -> [u8; 3] {
    let img = image::open(png).unwrap().to_rgb8();
    img.get_pixel(img.width() / 2, img.height() / 2).0
}

#[cfg(unix)]
#[test]
fn fifos_devices_and_directories_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for name in [
        "p.ron", "p.png", "img.png", "m.obj", "m.ply", "m", "lib.mtl", "tex.png",
    ] {
        mkfifo(&d.join(name));
    }
    let fifo = "not a regular file (a FIFO)";
    let quick = Duration::from_secs(20);
    // A preset, a screenshot, an image, meshes of each kind (and one sniffed).
    let out = texplore_in(d, &["render", "p.ron", "-o", "o.png", "-q"], quick);
    refused(&out, &format!("p.ron: {fifo}"));
    let out = texplore_in(d, &["render", "p.png", "-o", "o.png", "-q"], quick);
    refused(&out, &format!("p.png: {fifo}"));
    let out = texplore_in(d, &["probe", "img.png", "-o", "o.png"], quick);
    refused(&out, &format!("img.png: {fifo}"));
    for mesh in ["m.obj", "m.ply", "m"] {
        let out = texplore_in(d, &["mesh-info", mesh], quick);
        refused(&out, &format!("{mesh}: {fifo}"));
    }
    // A material library: the mesh loads, the problem names the library.
    std::fs::write(
        d.join("a.obj"),
        format!("mtllib lib.mtl\n{QUAD}usemtl x\nf 1/1 2/2 3/3 4/4\n"),
    )
    .unwrap();
    let out = texplore_in(d, &["mesh-info", "a.obj", "--json"], quick);
    assert!(out.status.success(), "{}", stderr(&out));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let problem = json["material_problem"].as_str().unwrap();
    assert!(problem.contains(&format!("lib.mtl: {fifo}")), "{problem}");
    // A map_Kd texture.
    std::fs::write(d.join("good.mtl"), "newmtl x\nKd 1 1 1\nmap_Kd tex.png\n").unwrap();
    std::fs::write(
        d.join("b.obj"),
        format!("mtllib good.mtl\n{QUAD}usemtl x\nf 1/1 2/2 3/3 4/4\n"),
    )
    .unwrap();
    std::fs::write(d.join("b.ron"), quad_preset("b.obj")).unwrap();
    let out = texplore_in(d, &["render", "b.ron", "-o", "o.png", "-q"], quick);
    refused(&out, &format!("tex.png: {fifo}"));
    // A directory and a device.
    std::fs::create_dir(d.join("folder.ron")).unwrap();
    let out = texplore_in(d, &["render", "folder.ron", "-o", "o.png", "-q"], quick);
    refused(&out, "folder.ron: not a regular file (a directory)");
    let out = texplore_in(d, &["render", "/dev/zero", "-o", "o.png", "-q"], quick);
    refused(&out, "/dev/zero: not a regular file (a character device)");
    let out = texplore_in(d, &["probe", "/dev/zero", "-o", "o.png"], quick);
    refused(&out, "/dev/zero: not a regular file (a character device)");
    assert!(!d.join("o.png").exists());
}

#[test]
fn a_preset_is_bounded_by_the_bytes_read() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("big.ron");
    let mut f = std::fs::File::create(&p).unwrap();
    let block = vec![b' '; 1 << 20];
    for _ in 0..17 {
        f.write_all(&block).unwrap();
    }
    drop(f);
    let out = texplore(dir.path(), &["render", "big.ron", "-o", "o.png", "-q"]);
    refused(&out, "big.ron: too large (larger than 16 MiB)");
}

#[test]
fn counts_and_numbers_out_of_range_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let quick = Duration::from_secs(10);
    let cases: [(&[&str], &str); 6] = [
        (
            &["render", "x.ron", "-o", "o.png", "--threads", "100000"],
            "100000 is out of range (0 to 1024)",
        ),
        (
            &["bench", "--mesh", "2000000000"],
            "2000000000 is out of range (8 to 8388608)",
        ),
        (
            &["bench", "x.ron", "--repeat", "99999999999999"],
            "99999999999999 is out of range (1 to 1000)",
        ),
        (
            &["report", "-o", "r", "--time-budget", "1e300"],
            "1e300 seconds is out of range (0 to 86400)",
        ),
        (
            &["report", "-o", "r", "--time-budget", "NaN"],
            "NaN seconds is out of range",
        ),
        (
            &["report", "-o", "r", "--reference-spp", "4000000000"],
            "4000000000 is out of range (1 to 1048576)",
        ),
    ];
    for (args, message) in cases {
        let out = texplore_in(d, args, quick);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        refused(&out, message);
    }
    assert!(
        !d.join("r").exists(),
        "report made its output before refusing"
    );
}

#[test]
fn mtl_lines_never_panic_and_errors_name_the_library_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let obj = d.join("m.obj");
    std::fs::write(
        &obj,
        format!("mtllib m.mtl\n{QUAD}usemtl grey\nf 1/1 2/2 3/3 4/4\n"),
    )
    .unwrap();
    // `Kd r` is valid MTL (g = b = r); the short lines of keywords texplore does not use are
    // not its business; none of them panics.
    std::fs::write(
        d.join("m.mtl"),
        "newmtl grey\nKd 0.5\nKa 1\nKs\nNs\nd\nillum\nNi\nmap_Ka\nmap_Bump\nbump\nmap_d\n",
    )
    .unwrap();
    let data = read_obj(&obj).unwrap();
    let m = data.material.as_ref().unwrap();
    assert_eq!((m.name.as_str(), m.diffuse), ("grey", Some([0.5; 3])));
    assert_eq!(data.material_problem, None);
    // Two numbers, a word where a number goes, an empty map_Kd, an unknown option.
    for (line, message) in [
        (
            "Kd 0.5 0.5",
            "m.mtl: line 2: Kd: expected 1 or 3 numbers (r [g b]), found 2",
        ),
        ("Kd 0.5 red 1", "m.mtl: line 2: Kd: 'red' is not a number"),
        ("map_Kd", "m.mtl: line 2: map_Kd: no file name"),
        (
            "map_Kd -s",
            "m.mtl: line 2: map_Kd: option '-s' needs 1 numbers",
        ),
        (
            "map_Kd -zoom 2 a.png",
            "m.mtl: line 2: map_Kd: unknown option '-zoom'",
        ),
        ("newmtl", "m.mtl: line 2: 'newmtl' names no material"),
    ] {
        std::fs::write(d.join("m.mtl"), format!("newmtl grey\n{line}\n")).unwrap();
        let data = read_obj(&obj).unwrap();
        let problem = data.material_problem.unwrap_or_default();
        assert!(problem.contains(message), "{line}: {problem}");
    }
    // A missing library is named.
    std::fs::remove_file(d.join("m.mtl")).unwrap();
    let data = read_obj(&obj).unwrap();
    let problem = data.material_problem.unwrap_or_default();
    assert!(
        problem.contains("m.mtl: No such file or directory"),
        "{problem}"
    );
}

#[test]
fn valid_objs_with_tabs_continuations_libraries_and_texture_options_load() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("first.mtl"), "newmtl other\nKd 0 1 0\n").unwrap();
    // Tabs, an option list, a file name with a space.
    std::fs::write(
        d.join("second.mtl"),
        "newmtl\tlabel\nKd\t1 1 1\nmap_Kd -s 2 2 1 -bm 1 -clamp on my tex.png\n",
    )
    .unwrap();
    solid_png(&d.join("my tex.png"), [230, 20, 10]);
    solid_png(&d.join("tex.png"), [10, 200, 10]);
    // Two libraries on one line after a tab, `usemtl` and a tab, a face split over lines.
    let obj =
        format!("mtllib\tfirst.mtl second.mtl\n{QUAD}usemtl\tlabel\nf 1/1 2/2 \\\n  3/3 4/4\n");
    std::fs::write(d.join("q.obj"), obj).unwrap();
    let data = read_obj(&d.join("q.obj")).unwrap();
    assert_eq!(data.triangles.len(), 2);
    assert_eq!(data.uvs[2], texplore::math::Vec2::new(1.0, 1.0));
    let m = data.material.as_ref().unwrap();
    assert_eq!(m.name, "label");
    assert_eq!(
        m.diffuse_texture.as_deref(),
        Some(d.join("my tex.png").as_path())
    );
    assert_eq!(data.material_problem, None);
    // The render shows the texture the file names (red), not `tex.png` (green).
    std::fs::write(d.join("q.ron"), quad_preset("q.obj")).unwrap();
    let out = texplore(d, &["render", "q.ron", "-o", "o.png", "-q"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(centre_pixel(&d.join("o.png")), [230, 20, 10]);
    // `vt u` (v is optional in OBJ and defaults to 0).
    std::fs::write(
        d.join("u.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25\nvt 0.5\nvt 0.75\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let data = read_obj(&d.join("u.obj")).unwrap();
    assert_eq!(data.uvs[1], texplore::math::Vec2::new(0.5, 0.0));
    // A line continued past the face: an error in it still names the line it starts on.
    std::fs::write(d.join("bad.obj"), format!("{QUAD}\nf 1 2 \\\n 9\n")).unwrap();
    let e = read_obj(&d.join("bad.obj")).unwrap_err().to_string();
    assert!(e.contains("bad.obj: line 10: face index 9"), "{e}");
}

/// A flat RGBE file (`signature`, `resolution`) whose pixel k in file order has red k.
fn rgbe(signature: &str, resolution: &str, count: u8) -> Vec<u8> {
    let mut v = format!("{signature}\nFORMAT=32-bit_rle_rgbe\n\n{resolution}\n").into_bytes();
    for k in 0..count {
        v.extend_from_slice(&[k, 0, 0, 136]);
    }
    v
}

#[test]
fn radiance_hdr_in_other_orientations_and_signatures_loads() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("up.hdr");
    // Scanlines from the bottom: the file's first pixel is the bottom-left texel.
    std::fs::write(&p, rgbe("#?RADIANCE", "+Y 2 +X 3", 6)).unwrap();
    let img = load_image(&p, false).unwrap();
    assert_eq!((img.width(), img.height()), (3, 2));
    assert_eq!(img.texel(0, 0).0, 0.0);
    assert_eq!(img.texel(2, 0).0, 2.0);
    assert_eq!(img.texel(0, 1).0, 3.0);
    // Column-major, and the older signature.
    std::fs::write(&p, rgbe("#?RGBE", "+X 3 -Y 2", 6)).unwrap();
    let img = load_image(&p, false).unwrap();
    assert_eq!((img.width(), img.height()), (3, 2));
    assert_eq!(img.texel_top(0, 1).0, 1.0);
    assert_eq!(img.texel_top(1, 0).0, 2.0);
    // A bad resolution line is named.
    std::fs::write(&p, rgbe("#?RADIANCE", "+Y 2 +Y 3", 6)).unwrap();
    let e = load_image(&p, false).unwrap_err().to_string();
    assert!(
        e.contains("up.hdr: cannot load image: resolution line '+Y 2 +Y 3'"),
        "{e}"
    );
}

/// A little-endian, uncompressed, one-strip TIFF of 32-bit floats, `channels` per pixel.
fn float_tiff(w: u16, h: u16, channels: u16, samples: &[f32]) -> Vec<u8> {
    let pixels: Vec<u8> = samples.iter().flat_map(|s| s.to_le_bytes()).collect();
    let ifd_at = 8 + pixels.len() as u32;
    let entries = 10u32;
    let arrays_at = ifd_at + 2 + entries * 12 + 4;
    // (tag, type, count, value); type 3 = SHORT, 4 = LONG. Per-channel arrays come after the
    // IFD when there are several channels.
    let per_channel = |value: u16, k: u32| -> (u32, u32) {
        if channels == 1 {
            (1, u32::from(value))
        } else {
            (u32::from(channels), arrays_at + k * u32::from(channels) * 2)
        }
    };
    let (n_bits, bits) = per_channel(32, 0);
    let (n_fmt, fmt) = per_channel(3, 1);
    let tags: [(u16, u16, u32, u32); 10] = [
        (256, 3, 1, u32::from(w)),
        (257, 3, 1, u32::from(h)),
        (258, 3, n_bits, bits),
        (259, 3, 1, 1),
        (262, 3, 1, if channels == 3 { 2 } else { 1 }),
        (273, 4, 1, 8),
        (277, 3, 1, u32::from(channels)),
        (278, 3, 1, u32::from(h)),
        (279, 4, 1, pixels.len() as u32),
        (339, 3, n_fmt, fmt),
    ];
    let mut v = b"II*\0".to_vec();
    v.extend_from_slice(&ifd_at.to_le_bytes());
    v.extend_from_slice(&pixels);
    v.extend_from_slice(&(tags.len() as u16).to_le_bytes());
    for (tag, ty, count, value) in tags {
        v.extend_from_slice(&tag.to_le_bytes());
        v.extend_from_slice(&ty.to_le_bytes());
        v.extend_from_slice(&count.to_le_bytes());
        if ty == 3 && count == 1 {
            v.extend_from_slice(&(value as u16).to_le_bytes());
            v.extend_from_slice(&[0, 0]);
        } else {
            v.extend_from_slice(&value.to_le_bytes());
        }
    }
    v.extend_from_slice(&0u32.to_le_bytes());
    if channels > 1 {
        for value in [32u16, 3] {
            for _ in 0..channels {
                v.extend_from_slice(&value.to_le_bytes());
            }
        }
    }
    v
}

#[test]
fn float_tiffs_load_with_their_values() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("height.tif");
    std::fs::write(&p, float_tiff(2, 2, 1, &[0.0, 0.25, 2.5, 1e3])).unwrap();
    let img = load_image(&p, true).unwrap();
    assert!(img.is_linear());
    assert_eq!(img.texel_top(1, 0).to_array(), [0.25; 3]);
    assert_eq!(img.texel_top(0, 1).to_array(), [2.5; 3]);
    assert_eq!(img.texel_top(1, 1).to_array(), [1e3; 3]);
    let p = dir.path().join("rgb.tif");
    let rgb: Vec<f32> = (0..12).map(|k| k as f32 / 4.0).collect();
    std::fs::write(&p, float_tiff(2, 2, 3, &rgb)).unwrap();
    let img = load_image(&p, true).unwrap();
    assert_eq!(img.texel_top(1, 1).to_array(), [2.25, 2.5, 2.75]);
}

fn chunk(kind: [u8; 4], data: &[u8]) -> Vec<u8> {
    let mut v = (data.len() as u32).to_be_bytes().to_vec();
    let mut body = kind.to_vec();
    body.extend_from_slice(data);
    v.extend_from_slice(&body);
    v.extend_from_slice(&crc32(&body).to_be_bytes());
    v
}

/// A 2 x 2 grey PNG; `configure` adds chunks through the encoder; `before_iend` are raw chunks
/// spliced in after the image data.
fn png_with(
    configure: impl FnOnce(&mut png::Encoder<'_, &mut Vec<u8>>),
    before_iend: &[Vec<u8>],
) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, 2, 2);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        configure(&mut enc);
        let mut w = enc.write_header().unwrap();
        w.write_image_data(&[128; 12]).unwrap();
        w.finish().unwrap();
    }
    let iend = out.len() - 12;
    let tail = out.split_off(iend);
    for c in before_iend {
        out.extend_from_slice(c);
    }
    out.extend_from_slice(&tail);
    out
}

#[test]
fn screenshots_carry_presets_compressed_after_the_image_and_with_a_bom() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let checker = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/checker.ron");
    let text = std::fs::read_to_string(&checker).unwrap();
    let want = texplore::scene::load_preset(&checker).unwrap();
    let key = texplore::scene::PRESET_CHUNK;
    let cases: [(&str, Vec<u8>); 3] = [
        (
            "ztxt.png",
            png_with(|e| e.add_ztxt_chunk(key.into(), text.clone()).unwrap(), &[]),
        ),
        ("after.png", {
            let mut data = key.as_bytes().to_vec();
            data.push(0);
            data.extend_from_slice(text.as_bytes());
            png_with(|_| {}, &[chunk(*b"tEXt", &data)])
        }),
        (
            "bom.png",
            png_with(
                |e| {
                    e.add_itxt_chunk(key.into(), format!("\u{feff}{text}"))
                        .unwrap();
                },
                &[],
            ),
        ),
    ];
    for (name, bytes) in cases {
        let p = d.join(name);
        std::fs::write(&p, bytes).unwrap();
        let got = texplore::scene::read_preset_or_png(&p).unwrap();
        assert_eq!(got, want, "{name}");
    }
    // A preset file starting with a byte-order mark renders.
    std::fs::write(d.join("bom.ron"), format!("\u{feff}{text}")).unwrap();
    let out = texplore(
        d,
        &[
            "render", "bom.ron", "-o", "o.png", "--width", "8", "--height", "6", "-q",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn compressed_chunks_inflate_under_their_limits() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let key = texplore::scene::PRESET_CHUNK;
    // A preset that inflates to 64 MiB, in a file of about 64 KiB.
    let bomb = png_with(
        |e| e.add_ztxt_chunk(key.into(), " ".repeat(64 << 20)).unwrap(),
        &[],
    );
    assert!(bomb.len() < 1 << 20, "{} bytes", bomb.len());
    let p = d.join("bomb.png");
    std::fs::write(&p, &bomb).unwrap();
    let start = Instant::now();
    let e = texplore::scene::read_preset_or_png(&p)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("bomb.png: the preset in its 'texplore-preset' chunk is larger than 16 MiB"),
        "{e}"
    );
    assert!(start.elapsed() < Duration::from_secs(10));
    // An uncompressed preset above 16 MiB is refused as well.
    let big = png_with(
        |e| {
            e.add_text_chunk(key.into(), " ".repeat((16 << 20) + 1))
                .unwrap();
        },
        &[],
    );
    std::fs::write(&p, &big).unwrap();
    let e = texplore::scene::read_preset_or_png(&p)
        .unwrap_err()
        .to_string();
    assert!(e.contains("is larger than 16 MiB"), "{e}");
    // A colour profile that inflates to 64 MiB is skipped: the texture loads, quickly, with its
    // texels (the unit test in src/texture/image/png_decode.rs shows it is never inflated).
    let mut info = png::Info::with_size(2, 2);
    info.color_type = png::ColorType::Rgb;
    info.bit_depth = png::BitDepth::Eight;
    info.icc_profile = Some(std::borrow::Cow::Owned(vec![0; 64 << 20]));
    let mut with_icc = Vec::new();
    {
        let enc = png::Encoder::with_info(&mut with_icc, info).unwrap();
        let mut w = enc.write_header().unwrap();
        w.write_image_data(&[128; 12]).unwrap();
        w.finish().unwrap();
    }
    assert!(with_icc.len() < 1 << 20, "{} bytes", with_icc.len());
    let p = d.join("icc.png");
    std::fs::write(&p, &with_icc).unwrap();
    let start = Instant::now();
    let img = load_image(&p, false).unwrap();
    assert!(start.elapsed() < Duration::from_secs(10));
    assert!((img.texel(1, 1).0 - 128.0 / 255.0).abs() < 1e-6);
}

#[test]
fn snapshot_check_with_no_presets_fails_saying_so() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("empty")).unwrap();
    let out = texplore(
        dir.path(),
        &[
            "snapshot",
            "check",
            "--presets",
            "empty",
            "--screenshots",
            "empty",
        ],
    );
    refused(&out, "empty: no presets (*.ron) here, nothing to check");
}

#[test]
fn snapshot_check_with_an_unknown_name_fails_naming_it_before_any_render() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let presets = root.join("presets");
    let presets = presets.to_str().unwrap();
    let start = Instant::now();
    let out = texplore(
        root,
        &[
            "snapshot",
            "check",
            "earth",
            "nosuch-preset",
            "--presets",
            presets,
        ],
    );
    refused(&out, "no preset named nosuch-preset in");
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("earth"),
        "lists the presets there"
    );
    assert!(
        String::from_utf8_lossy(&out.stdout).is_empty(),
        "nothing was checked"
    );
    assert!(start.elapsed() < Duration::from_secs(20));
}

#[test]
fn a_preset_chunk_that_is_not_utf8_is_named_as_broken_not_missing() {
    let dir = tempfile::tempdir().unwrap();
    let key = texplore::scene::PRESET_CHUNK;
    // iTXt: keyword, 0, compression flag 0, method 0, empty language, 0, empty translated
    // keyword, 0, then text that is not UTF-8.
    let mut data = key.as_bytes().to_vec();
    data.extend_from_slice(&[0, 0, 0, 0, 0]);
    data.extend_from_slice(b"(version: 1, \xff\xfe broken)");
    let p = dir.path().join("broken.png");
    std::fs::write(&p, png_with(|_| {}, &[chunk(*b"iTXt", &data)])).unwrap();
    let e = texplore::scene::read_png_preset(&p)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("broken.png") && e.contains("iTXt chunk is not valid text"),
        "{e}"
    );
    // Without the chunk: missing, as before.
    let q = dir.path().join("plain.png");
    std::fs::write(&q, png_with(|_| {}, &[])).unwrap();
    let e = texplore::scene::read_png_preset(&q)
        .unwrap_err()
        .to_string();
    assert!(e.contains("has no 'texplore-preset' text chunk"), "{e}");
}
