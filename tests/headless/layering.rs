//! The library's layering: no module imports a module of a higher layer.
//!
//! Reads every file under `src/` (comments and string literals removed), finds the paths that
//! leave a module (`crate::x`, `crate::{x, y}`, `super::` chains that climb to the crate root,
//! `$crate::x` in macros) and fails naming the file and line of every import that runs against
//! [`LAYERS`]. ARCHITECTURE.md states the same order.
//!
//! Unit-test modules (`#[cfg(test)] mod x { .. }` and `#[cfg(test)] mod x;` with their files)
//! are not part of the library's layering: a low module's tests may use higher modules (to
//! check, say, that every enum of the crate round-trips through its name).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The layers, lowest first. A module may use modules of lower layers only: not those of its own
/// layer (peers stay independent) and never those above.
const LAYERS: &[&[&str]] = &[
    // Foundations every layer may use: the field path, the error type, then the names of closed sets (strum
    // helpers), the bounded reader of every input file and the atomic writer of every output
    // (both return the error type).
    // The one spelling of a field of a scene description, which the error type carries.
    &["field"],
    &["error"],
    &["names", "input", "output"],
    // The shipped files built into the binary, and their copy on disk (through input/output).
    &["shipped"],
    &["math"],
    &["geometry"],
    // Mesh files produce `geometry::MeshData`.
    &["meshio"],
    &["mapping"],
    &["texture"],
    &["material"],
    // Both import only `math` (and `names`); the scene builds them and the renderer drives them.
    &["camera", "sampler"],
    &["scene"],
    // Lessons edit presets (`scene`) and need nothing of the renderer.
    &["render", "lesson"],
    // Tools over the renderer: speed against error, golden images, light-probe conversion, the
    // fuzz entry points.
    // A link that opens a scene reads presets (`scene`) and names lessons.
    &["report", "snapshot", "probe", "robustness", "link"],
    // What the renderer did at one pixel, with the report's RMSE for the A/B split; which texels
    // the pixels read and which pixels read a texel (one 1-spp pass on the render pool).
    &["inspect", "coverage"],
    &["cli", "gui"],
];

/// Known edges against the layering, each with the change that removes it.
/// None today: the last one (`mapping/explain.rs` -> texture) went when `explain_lookup` moved
/// into texture.
const KNOWN_EXCEPTIONS: &[(&str, &str)] = &[];

/// One import of another top-level module.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Edge {
    file: String,
    line: usize,
    from: String,
    to: String,
}

#[derive(Clone, Debug, PartialEq, Eq)]
enum Tok {
    Ident(String),
    PathSep,
    Open,
    Close,
    Comma,
    Other(char),
}

/// Tokens with their line numbers; comments, strings and character literals are dropped.
fn tokenize(src: &str) -> Vec<(Tok, usize)> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    let mut line = 1;
    let count_lines = |from: usize, to: usize| b[from..to].iter().filter(|&&c| c == b'\n').count();
    while i < b.len() {
        let c = b[i];
        match c {
            b'\n' => {
                line += 1;
                i += 1;
            }
            _ if c.is_ascii_whitespace() => i += 1,
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                let start = i;
                let mut depth = 0usize;
                while i < b.len() {
                    if b[i..].starts_with(b"/*") {
                        depth += 1;
                        i += 2;
                    } else if b[i..].starts_with(b"*/") {
                        depth -= 1;
                        i += 2;
                        if depth == 0 {
                            break;
                        }
                    } else {
                        i += 1;
                    }
                }
                line += count_lines(start, i.min(b.len()));
            }
            b'r' if matches!(b.get(i + 1), Some(b'"' | b'#'))
                && b[i + 1..].iter().take_while(|&&c| c == b'#').count() < 256
                && b.get(i + 1 + b[i + 1..].iter().take_while(|&&c| c == b'#').count())
                    == Some(&b'"') =>
            {
                let start = i;
                let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
                let mut close = vec![b'"'];
                close.extend(std::iter::repeat_n(b'#', hashes));
                i += 2 + hashes;
                while i < b.len() && !b[i..].starts_with(&close) {
                    i += 1;
                }
                i = (i + close.len()).min(b.len());
                line += count_lines(start, i);
            }
            b'"' => {
                let start = i;
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                i = (i + 1).min(b.len());
                line += count_lines(start, i);
            }
            b'\'' => {
                // A character literal ('x', '\n', '\u{..}') or a lifetime ('a).
                if b.get(i + 1) == Some(&b'\\') {
                    i += 2;
                    while i < b.len() && b[i] != b'\'' {
                        i += 1;
                    }
                    i += 1;
                } else if b.get(i + 2) == Some(&b'\'') {
                    i += 3;
                } else {
                    let ch_len = src[i + 1..].chars().next().map_or(1, char::len_utf8);
                    if b.get(i + 1 + ch_len) == Some(&b'\'') {
                        i += 2 + ch_len;
                    } else {
                        i += 1; // a lifetime: its name follows as an identifier
                    }
                }
            }
            b':' if b.get(i + 1) == Some(&b':') => {
                out.push((Tok::PathSep, line));
                i += 2;
            }
            b'{' => {
                out.push((Tok::Open, line));
                i += 1;
            }
            b'}' => {
                out.push((Tok::Close, line));
                i += 1;
            }
            b',' => {
                out.push((Tok::Comma, line));
                i += 1;
            }
            _ if c.is_ascii_alphanumeric() || c == b'_' => {
                let start = i;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                out.push((Tok::Ident(src[start..i].to_string()), line));
            }
            _ => {
                let ch = src[i..].chars().next().unwrap_or('?');
                out.push((Tok::Other(ch), line));
                i += ch.len_utf8();
            }
        }
    }
    out
}

/// The module path of a file under `src/` (`src/scene/files.rs` -> `[scene, files]`).
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .iter()
        .skip(1)
        .map(|s| s.to_string_lossy().into_owned())
        .collect();
    if let Some(last) = parts.pop() {
        let stem = last.trim_end_matches(".rs");
        if stem != "mod" && stem != "lib" {
            parts.push(stem.to_string());
        }
    }
    parts
}

/// The first path segments named right after position `i` (one, or each item of a `{...}`
/// group), with their lines.
fn first_segments(toks: &[(Tok, usize)], i: usize) -> Vec<(String, usize)> {
    match toks.get(i) {
        Some((Tok::Ident(name), line)) => vec![(name.clone(), *line)],
        Some((Tok::Open, _)) => {
            let mut out = Vec::new();
            let mut depth = 0usize;
            let mut expect_item = true;
            for (t, line) in &toks[i..] {
                match t {
                    Tok::Open => {
                        depth += 1;
                        expect_item = depth == 1;
                    }
                    Tok::Close => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    Tok::Comma if depth == 1 => expect_item = true,
                    Tok::Ident(name) if depth == 1 && expect_item => {
                        out.push((name.clone(), *line));
                        expect_item = false;
                    }
                    _ if depth == 1 => expect_item = false,
                    _ => {}
                }
            }
            out
        }
        _ => Vec::new(),
    }
}

/// Whether tokens `i..` are the attribute `#[cfg(test)]`.
fn is_cfg_test(toks: &[(Tok, usize)], i: usize) -> bool {
    let want = [
        Tok::Other('#'),
        Tok::Other('['),
        Tok::Ident("cfg".into()),
        Tok::Other('('),
        Tok::Ident("test".into()),
        Tok::Other(')'),
        Tok::Other(']'),
    ];
    toks.len() >= i + want.len() && toks[i..i + want.len()].iter().map(|t| &t.0).eq(want.iter())
}

/// One file's imports of other top-level modules (outside its unit-test modules), and the
/// names of the test-only module files it declares (`#[cfg(test)] mod x;`).
fn edges_of(
    file: &str,
    rel: &Path,
    src: &str,
    top_modules: &BTreeSet<String>,
) -> (Vec<Edge>, Vec<String>) {
    let toks = tokenize(src);
    let file_path = module_path(rel);
    let Some(from) = file_path.first().cloned() else {
        return (Vec::new(), Vec::new()); // lib.rs: the module list
    };
    // Inline modules (`mod tests { .. }`): (name, brace depth inside them, test-only).
    let mut inline: Vec<(String, usize, bool)> = Vec::new();
    let mut test_files = Vec::new();
    let mut cfg_test = false;
    let mut depth = 0usize;
    let mut out = Vec::new();
    let mut push = |targets: Vec<(String, usize)>, in_test: bool| {
        for (to, line) in targets {
            if top_modules.contains(&to) && to != from && !in_test {
                out.push(Edge {
                    file: file.to_string(),
                    line,
                    from: from.clone(),
                    to,
                });
            }
        }
    };
    let mut i = 0;
    while i < toks.len() {
        let in_test = inline.iter().any(|m| m.2);
        if is_cfg_test(&toks, i) {
            cfg_test = true;
            i += 7;
            continue;
        }
        // `#[cfg(test)]` waits for a `mod`; another item's `;`, `{` or `}` drops it.
        if matches!(&toks[i].0, Tok::Open | Tok::Close | Tok::Other(';')) {
            cfg_test = false;
        }
        match &toks[i].0 {
            Tok::Open => depth += 1,
            Tok::Close => {
                if inline.last().is_some_and(|m| m.1 == depth) {
                    inline.pop();
                }
                depth = depth.saturating_sub(1);
            }
            Tok::Ident(kw) if kw == "mod" => match (toks.get(i + 1), toks.get(i + 2)) {
                (Some((Tok::Ident(name), _)), Some((Tok::Open, _))) => {
                    inline.push((name.clone(), depth + 1, cfg_test || in_test));
                }
                (Some((Tok::Ident(name), _)), Some((Tok::Other(';'), _))) if cfg_test => {
                    test_files.push(name.clone());
                }
                _ => {}
            },
            Tok::Ident(kw)
                if kw == "crate" && toks.get(i + 1).map(|t| &t.0) == Some(&Tok::PathSep) =>
            {
                push(first_segments(&toks, i + 2), in_test);
                i += 2;
                continue;
            }
            Tok::Ident(kw)
                if kw == "super"
                    && toks.get(i + 1).map(|t| &t.0) == Some(&Tok::PathSep)
                    && !matches!(
                        toks.get(i.wrapping_sub(1)).map(|t| &t.0),
                        Some(Tok::PathSep)
                    ) =>
            {
                let mut here: Vec<String> = file_path.clone();
                here.extend(inline.iter().map(|m| m.0.clone()));
                let mut j = i;
                while matches!(&toks.get(j).map(|t| &t.0), Some(Tok::Ident(s)) if s == "super")
                    && toks.get(j + 1).map(|t| &t.0) == Some(&Tok::PathSep)
                {
                    here.pop();
                    j += 2;
                }
                if here.is_empty() {
                    push(first_segments(&toks, j), in_test);
                }
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    (out, test_files)
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// Every import of another top-level module under `src/`, and the top-level module names.
fn crate_edges(root: &Path) -> (Vec<Edge>, BTreeSet<String>) {
    let src = root.join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let top_modules: BTreeSet<String> = files
        .iter()
        .filter_map(|p| module_path(p.strip_prefix(root).ok()?).first().cloned())
        .filter(|m| m != "main" && m != "bin")
        .collect();
    let mut edges = Vec::new();
    // Files of `#[cfg(test)] mod x;` declarations: `dir/x.rs` and everything under `dir/x/`.
    let mut test_only: Vec<PathBuf> = Vec::new();
    for p in &files {
        let rel = p.strip_prefix(root).expect("under the root");
        if rel == Path::new("src/main.rs") || rel.starts_with("src/bin") {
            continue; // the binaries (the desktop's, the page's) sit above every layer
        }
        let text = std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        let file = rel.to_string_lossy().replace('\\', "/");
        let (found, test_children) = edges_of(&file, rel, &text, &top_modules);
        let stem = rel.file_stem().unwrap_or_default();
        let dir = if stem == "mod" || stem == "lib" {
            rel.parent().unwrap_or(rel).to_path_buf()
        } else {
            rel.with_extension("")
        };
        for child in test_children {
            test_only.push(dir.join(format!("{child}.rs")));
            test_only.push(dir.join(child));
        }
        edges.extend(found.into_iter().map(|e| (rel.to_path_buf(), e)));
    }
    let edges = edges
        .into_iter()
        .filter(|(rel, _)| !test_only.iter().any(|t| rel.starts_with(t)))
        .map(|(_, e)| e)
        .collect();
    (edges, top_modules)
}

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

/// The edges that run against [`LAYERS`], as messages naming the file and line.
fn violations(edges: &[Edge]) -> Vec<String> {
    let mut out = Vec::new();
    for e in edges {
        let (Some(lf), Some(lt)) = (layer_of(&e.from), layer_of(&e.to)) else {
            continue; // unplaced modules are reported separately
        };
        if lt >= lf
            && !KNOWN_EXCEPTIONS
                .iter()
                .any(|(f, to)| *f == e.file && *to == e.to)
        {
            let why = if lt == lf {
                "its peer"
            } else {
                "a higher layer"
            };
            out.push(format!(
                "{}:{}: `{}` imports `{}`, {why}",
                e.file, e.line, e.from, e.to
            ));
        }
    }
    out
}

#[test]
fn no_module_imports_a_higher_layer() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let (edges, modules) = crate_edges(root);
    let unplaced: Vec<_> = modules.iter().filter(|m| layer_of(m).is_none()).collect();
    assert!(
        unplaced.is_empty(),
        "modules with no place in tests/headless/layering.rs's LAYERS (add them, and to ARCHITECTURE.md): {unplaced:?}"
    );
    let bad = violations(&edges);
    assert!(
        bad.is_empty(),
        "imports against the layering (see ARCHITECTURE.md):\n{}",
        bad.join("\n")
    );
}

#[test]
fn every_known_exception_still_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let (edges, _) = crate_edges(root);
    for (file, to) in KNOWN_EXCEPTIONS {
        assert!(
            edges.iter().any(|e| e.file == *file && e.to == *to),
            "{file} no longer imports `{to}`: delete the exception"
        );
    }
}

fn edges_in(rel: &str, src: &str) -> Vec<(String, usize)> {
    let modules: BTreeSet<String> = ["scene", "render", "math", "texture", "report"]
        .into_iter()
        .map(String::from)
        .collect();
    edges_of(rel, Path::new(rel), src, &modules)
        .0
        .into_iter()
        .map(|e| (e.to, e.line))
        .collect()
}

#[test]
fn the_scanner_finds_every_spelling_of_an_import() {
    let src = r#"
use crate::render::Film;
use crate::{math::Rgb, texture::{Filter, Wrap}};
use super::super::report::x;
fn f() -> crate::scene::Scene { todo!() }
// use crate::report::Hidden;
/* use crate::report::Hidden; */
const S: &str = "crate::report::Hidden";
const C: char = '{';
fn g<'a>(x: &'a str) -> &'a str { x }
mod tests {
    use super::*;
    use super::super::Local;
}
"#;
    assert_eq!(
        edges_in("src/scene/files.rs", src),
        vec![
            ("render".to_string(), 2),
            ("math".to_string(), 3),
            ("texture".to_string(), 3),
            ("report".to_string(), 4),
        ]
    );
    // From a mod.rs, one `super` reaches the crate root.
    assert_eq!(
        edges_in(
            "src/math/mod.rs",
            "use super::texture::Lookup;\nmod tests { use super::Rgb; }"
        ),
        vec![("texture".to_string(), 1)]
    );
}

#[test]
fn unit_test_modules_are_outside_the_layering() {
    let src = r"
#[cfg(test)]
mod tests {
    use crate::report::Metrics;
    mod deeper { use crate::scene::Scene; }
}
#[cfg(test)]
pub(crate) mod more;
mod helpers { use crate::render::Film; }
#[cfg(test)]
fn only_modules_are_exempt() -> crate::report::Metrics { todo!() }
mod plain;
";
    let modules: BTreeSet<String> = ["scene", "render", "report"]
        .into_iter()
        .map(String::from)
        .collect();
    let rel = "src/math/color.rs";
    let (edges, test_files) = edges_of(rel, Path::new(rel), src, &modules);
    let found: Vec<_> = edges.iter().map(|e| (e.to.as_str(), e.line)).collect();
    assert_eq!(found, vec![("render", 9), ("report", 11)]);
    assert_eq!(test_files, vec!["more".to_string()]);
}

#[test]
fn an_upward_import_is_reported_with_file_and_line() {
    let edges = vec![
        Edge {
            file: "src/scene/files.rs".into(),
            line: 6,
            from: "scene".into(),
            to: "render".into(),
        },
        Edge {
            file: "src/render/film.rs".into(),
            line: 4,
            from: "render".into(),
            to: "math".into(),
        },
        Edge {
            file: "src/camera.rs".into(),
            line: 9,
            from: "camera".into(),
            to: "sampler".into(),
        },
    ];
    assert_eq!(
        violations(&edges),
        vec![
            "src/scene/files.rs:6: `scene` imports `render`, a higher layer".to_string(),
            "src/camera.rs:9: `camera` imports `sampler`, its peer".to_string(),
        ]
    );
}
