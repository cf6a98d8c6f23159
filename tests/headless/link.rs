//! A link that opens a scene (issue 36 §5): every shipped preset goes through a link and comes
//! back the same scene; hostile links are refused with a message that says why.

use base64::Engine as _;
use std::path::Path;
use texplore::link::{LINK_PRESET, Link, MAX_LINK_BYTES, lesson_fragment, parse, scene_fragment};
use texplore::scene::{TextureDesc, list_presets, load_preset, parse_preset};

#[test]
fn every_shipped_preset_round_trips_through_a_link() {
    let presets = list_presets(Path::new("presets")).unwrap();
    assert!(presets.len() > 10);
    for file in presets {
        let desc = load_preset(&file).unwrap();
        let (fragment, notices) = scene_fragment(&desc, Path::new("presets")).unwrap();
        assert!(notices.is_empty(), "{}: {notices:?}", file.display());
        assert!(fragment.len() <= MAX_LINK_BYTES);
        let url = format!("https://teacher.example/texplore/#{fragment}");
        let Link::Scene(text) = parse(&url).unwrap() else {
            panic!("{}: not a scene", file.display());
        };
        let back = parse_preset(&text, Path::new(LINK_PRESET)).unwrap();
        // The presets live beside the link's preset: their asset paths read the same.
        assert_eq!(back, desc, "{}", file.display());
    }
}

#[test]
fn a_lesson_link_names_the_lesson_and_the_experiment() {
    let f = lesson_fragment("06-spherical-mapping", Some(2));
    assert_eq!(f, "texplore1-l-06-spherical-mapping~3");
    assert_eq!(
        parse(&format!("http://localhost:8000/index.html#{f}")).unwrap(),
        Link::Lesson {
            lesson: "06-spherical-mapping".into(),
            experiment: Some(2)
        }
    );
    assert_eq!(
        parse("#texplore1-l-01-constant-vs-image").unwrap(),
        Link::Lesson {
            lesson: "01-constant-vs-image".into(),
            experiment: None
        }
    );
}

#[test]
fn a_student_s_own_image_is_left_out_with_a_notice() {
    let dir = tempfile::tempdir().unwrap();
    let mine = dir.path().join("my-image.png");
    std::fs::copy("assets/checker_512.png", &mine).unwrap();
    std::fs::write(&mine, b"not the shipped bytes").unwrap();
    let mut desc = load_preset(Path::new("presets/earth.ron")).unwrap();
    if let TextureDesc::Image { path, .. } = desc.objects[0].material.texture_mut() {
        *path = mine.to_string_lossy().into_owned();
    }
    let (fragment, notices) = scene_fragment(&desc, Path::new("presets")).unwrap();
    assert_eq!(notices.len(), 1);
    assert!(
        notices[0].contains("my-image.png is not one of the shipped files"),
        "{notices:?}"
    );
    let Link::Scene(text) = parse(&fragment).unwrap() else {
        panic!()
    };
    let back = parse_preset(&text, Path::new(LINK_PRESET)).unwrap();
    assert!(matches!(
        back.objects[0].material.texture(),
        TextureDesc::Constant(_)
    ));
}

fn refused(link: &str) -> String {
    parse(link).expect_err("refused").to_string()
}

#[test]
fn hostile_links_are_refused_with_a_clear_message() {
    let desc = load_preset(Path::new("presets/earth.ron")).unwrap();
    let (good, _) = scene_fragment(&desc, Path::new("presets")).unwrap();
    // Truncated.
    let cut = &good[..good.len() / 2];
    let m = refused(cut);
    assert!(m.contains("damaged"), "{m}");
    // Oversized.
    let m = refused(&format!("#texplore1-s-{}", "A".repeat(MAX_LINK_BYTES)));
    assert!(m.contains("links stop at 8192"), "{m}");
    // Wrong version, not a link.
    let m = refused(&good.replacen("texplore1", "texplore2", 1));
    assert!(
        m.contains("texplore2 link; this texplore reads texplore1"),
        "{m}"
    );
    let m = refused("https://example.org/#top");
    assert!(m.contains("not a texplore link"), "{m}");
    // A path outside the shipped files, however spelled.
    for path in [
        "/etc/passwd",
        "../../../etc/passwd",
        "../uploads/x.png",
        "../assets/nope.png",
        "../presets/earth.ron",
    ] {
        let text = std::fs::read_to_string("presets/earth.ron")
            .unwrap()
            .replace("../assets/earth_2048x1024.jpg", path);
        let deflated = miniz_oxide::deflate::compress_to_vec(text.as_bytes(), 9);
        let data = base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(deflated);
        let m = refused(&format!("#texplore1-s-{data}"));
        assert!(m.contains("not one of the shipped files"), "{path}: {m}");
    }
    // A preset that a preset file would not be.
    let bad = "(objects: [(shape: Sphere, material: Matte(ka: NaN))])";
    let deflated = miniz_oxide::deflate::compress_to_vec(bad.as_bytes(), 9);
    let data = base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(deflated);
    let m = refused(&format!("#texplore1-s-{data}"));
    assert!(
        m.starts_with("this link does not open a scene: presets/link.ron"),
        "{m}"
    );
    // A lesson name that is a path, an experiment that is not a number.
    assert!(refused("#texplore1-l-../../etc").contains("not a lesson's name"));
    assert!(refused("#texplore1-l-06-spherical~x").contains("not an experiment's number"));
}

#[test]
fn a_link_opens_as_a_preset_file_with_the_same_scene() {
    let desc = load_preset(Path::new("presets/earth.ron")).unwrap();
    let (fragment, _) = scene_fragment(&desc, Path::new("presets")).unwrap();
    let path = texplore::link::materialise(&format!("#{fragment}")).unwrap();
    let opened = load_preset(&path).unwrap();
    assert_eq!(opened.objects.len(), desc.objects.len());
    // Its image is the shipped Earth, wherever the file was written.
    let scene =
        texplore::scene::build_scene(&opened, &path, &mut texplore::scene::AssetCache::new());
    assert!(scene.is_ok(), "{:?}", scene.err());
    // A lesson link opens the experiment's scene.
    let lesson = texplore::link::scene_text("#texplore1-l-06-spherical-mapping~3").unwrap();
    assert!(lesson.contains("UvGrid"), "{lesson}");
    let m = texplore::link::scene_text("#texplore1-l-06-spherical-mapping~99").unwrap_err();
    assert!(m.to_string().contains("experiments, not 99"), "{m}");
}
