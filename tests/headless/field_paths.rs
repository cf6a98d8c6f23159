//! One field path (issue 23, item 4): an error names a field as a lesson edit does
//! (`objects[0].material.kd.texture`), then the object's name in one form (`(object "Ball")`),
//! so the path copied out of an error is one a lesson (or `set_path`) can set.

use texplore::field::FieldPath;
use texplore::lesson::edit::set_path;
use texplore::scene::{AssetCache, SceneDesc, build_scene};

/// A preset of `objects` and `lights` (RON lists' contents), rendered at 8 x 8.
fn preset(objects: &str, lights: &str) -> SceneDesc {
    ron::from_str(&format!(
        "(version: 1, camera: (eye: (0, 0, 6)), render: (width: 8, height: 8, spp: 1), \
         lights: [{lights}], objects: [{objects}])"
    ))
    .unwrap_or_else(|e| panic!("{e}"))
}

/// The path an error message names: after `file: `, up to the object's name or the reason.
fn path_in<'a>(message: &'a str, file: &str) -> &'a str {
    let rest = message
        .strip_prefix(&format!("{file}: "))
        .unwrap_or_else(|| panic!("{message} does not start with {file}"));
    let end = [rest.find(" (object "), rest.find(": ")]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or_else(|| panic!("no field in {message}"));
    &rest[..end]
}

#[test]
fn the_path_in_an_error_is_the_path_a_lesson_edit_sets() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("p.ron");
    std::fs::write(dir.path().join("bad.png"), b"not a PNG").unwrap();
    let bad = dir.path().join("bad.png");
    let gravel = crate::common::root().join("assets/gravel_gray_512.png");
    let knot = crate::common::root().join("assets/torus-knot.ply");
    let ball = |material: &str, maps: &str| {
        format!(r#"(name: "Ball", shape: Sphere, material: {material}{maps})"#)
    };
    let light = "Point(position: (0, 4, 4))";
    // Each failure, the path its error names, the object named after it, and a value that
    // mends it when set at the path copied from the message.
    let cases: [(&str, SceneDesc, &str, Option<&str>, &str); 5] = [
        (
            "a bad image in kd",
            preset(
                &ball(
                    &format!(
                        r#"Matte(cd: Constant((0.5, 0.5, 0.5)), kd: (texture: Image(path: "{}", mapping: Spherical), channel: Red))"#,
                        bad.display()
                    ),
                    "",
                ),
                light,
            ),
            "objects[0].material.kd.texture",
            Some("Ball"),
            "Constant((0.5, 0.5, 0.5))",
        ),
        (
            "a NaN in a light's colour",
            preset(
                &ball("Matte(cd: Constant((0.5, 0.5, 0.5)))", ""),
                "Point(position: (0, 4, 4), color: (1, NaN, 1))",
            ),
            "lights[0].color",
            None,
            "(1, 1, 1)",
        ),
        (
            "a bump height's negative scale",
            preset(
                &ball(
                    "Matte(cd: Constant((0.5, 0.5, 0.5)))",
                    &format!(
                        r#", bump: (height: Image(path: "{}", mapping: Spherical, scale: -1), scale: 1)"#,
                        gravel.display()
                    ),
                ),
                light,
            ),
            "objects[0].bump.height.scale",
            Some("Ball"),
            "1",
        ),
        (
            "a displacement that overflows",
            preset(
                &format!(
                    r#"(name: "Knot", shape: Mesh(path: "{}"), material: Matte(cd: Constant((0.5, 0.5, 0.5))),
                        displace: (height: Image(path: "{}", mapping: Uv, scale: 1e38), scale: 1e6, subdivide: 1))"#,
                    knot.display(),
                    gravel.display()
                ),
                light,
            ),
            "objects[0].displace.scale",
            Some("Knot"),
            "0.01",
        ),
        (
            "a mistake in a coefficient's formula mapping",
            preset(
                &ball(
                    "Phong(cd: Constant((0.5, 0.5, 0.5)), ks: Checker(mapping: Formula(u: \"x\", v: \"y +\")))",
                    "",
                ),
                light,
            ),
            "objects[0].material.ks.mapping.v",
            Some("Ball"),
            "\"y\"",
        ),
    ];
    for (what, desc, want, object, mend) in cases {
        let e = build_scene(&desc, &p, &mut AssetCache::new())
            .err()
            .unwrap_or_else(|| panic!("{what} is accepted"));
        let want_path = FieldPath::parse(want).unwrap();
        assert_eq!(e.field(), Some(&want_path), "{what}: {e}");
        let message = e.to_string();
        let named = path_in(&message, &p.display().to_string());
        assert_eq!(named, want, "{what}: {message}");
        assert_eq!(FieldPath::parse(named), Ok(want_path), "{what}: {message}");
        let after = match object {
            Some(name) => format!("{want} (object \"{name}\"): "),
            None => format!("{want}: "),
        };
        assert!(message.contains(&after), "{what}: {message}");
        // The path copied out of the message, set to a good value: the scene builds.
        let mended = set_path(&desc, named, mend).unwrap_or_else(|e| panic!("{what}: {e}"));
        build_scene(&mended, &p, &mut AssetCache::new())
            .unwrap_or_else(|e| panic!("{what}, mended at {named}: {e}"));
    }
}
