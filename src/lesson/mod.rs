//! Lessons: the lecture in order, one TOML file per topic in `lessons/` (ordered by file name).
//!
//! A lesson names the preset it starts from, says what it shows, offers *Try this* experiments
//! (each a label, a *Look for* sentence and edits of the scene: a path into the preset and a
//! value in the preset's own RON syntax, see [`edit`]) and asks a question with its answer:
//!
//! ```toml
//! title = "Cylindrical mapping"
//! preset = "../presets/cylinder.ron"
//! text = "phi = atan2(x, z), u = phi / 2 pi, v = (y + 1) / 2."
//!
//! [[experiment]]
//! label = "Show (u, v) as colour"
//! look_for = "Red (u) grows around the can and drops to 0 at the seam."
//! set = { "render.view" = "Uv" }
//!
//! [question]
//! ask = "Where is the seam?"
//! answer = "At x = 0, z = 1."
//! ```
//!
//! Each experiment applies to the lesson's own scene, not on top of the experiment before it;
//! `after = "label"` makes an experiment build on another one of the lesson (declared before it):
//! its edits go on top of that experiment's scene ([`Lesson::scene`]).
//!
//! Loading checks every edit of every experiment against the lesson's preset, so a lesson that
//! loads applies. A lesson that does not load is one error naming its file and line; the others
//! still load ([`load_dir`]).
//!
//! Where lessons are found ([`default_dirs`]): the shipped ones are built into the binary
//! ([`crate::shipped`]), a teacher's own go in [`user_dir`]. A lesson's preset is found beside
//! the lesson file, else (for a copy of a shipped lesson) among the shipped files.

pub mod edit;
pub mod exercise;

use crate::error::{Error, Result};
use crate::scene::{AssetCache, SceneDesc, build_scene, load_preset};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Largest lesson file read (a lesson is a few kilobytes of text).
pub const MAX_LESSON_BYTES: u64 = 1 << 20;

/// One lesson, loaded and checked against its preset.
#[derive(Clone, Debug, PartialEq)]
pub struct Lesson {
    /// The file's name without `.toml` (`05-cylindrical`): what `texplore lesson` takes.
    pub name: String,
    /// The lesson file.
    pub file: PathBuf,
    /// The heading.
    pub title: String,
    /// The preset the lesson starts from (resolved against the lesson's folder).
    pub preset: PathBuf,
    /// What the lesson explains, with its formulas (plain text, paragraphs split by blank lines).
    pub text: String,
    /// The *Try this* experiments, in the file's order.
    pub experiments: Vec<Experiment>,
    /// The exercises: formulas to write, checked against a built-in mapping or texture.
    pub exercises: Vec<exercise::Exercise>,
    /// The question for the learner.
    pub question: String,
    /// Its answer, shown on request.
    pub answer: String,
    /// What the check of its scenes said about their textures (a footprint filter whose
    /// summed-area tables would not fit the texture budget, read with EWA instead), each once,
    /// with the scene it came from: `lesson --list` prints them.
    pub warnings: Vec<String>,
}

/// A *Try this* experiment: named edits of the scene, and what to look for once applied.
#[derive(Clone, Debug, PartialEq)]
pub struct Experiment {
    /// The button's text.
    pub label: String,
    /// What should change when the learner clicks.
    pub look_for: String,
    /// The edits, applied in order.
    pub edits: Vec<Edit>,
    /// The experiment (an index into the lesson's, always an earlier one) whose scene this one
    /// builds on (`after = "label"`); `None`: the lesson's own scene.
    pub after: Option<usize>,
}

/// One edit: the value at `path` (`objects[0].material.cd.mapping`) becomes `value` (RON text,
/// as in a preset: `Cylindrical`, `(0, 1, 4)`, `"../assets/chelsea_451x300.png"`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Edit {
    /// Where in the preset.
    pub path: String,
    /// The new value, in RON.
    pub value: String,
}

impl Experiment {
    /// `desc` with this experiment's edits applied.
    ///
    /// # Errors
    /// An edit does not fit `desc` (possible when the learner changed the scene first): the
    /// message names the path.
    pub fn apply(&self, desc: &SceneDesc) -> std::result::Result<SceneDesc, String> {
        let mut d = desc.clone();
        for e in &self.edits {
            d = edit::set_path(&d, &e.path, &e.value)?;
        }
        Ok(d)
    }
}

impl Lesson {
    /// The scene of experiment `k`: `base` (the lesson's preset) with the edits of the
    /// experiments it builds on (`after`), then its own.
    ///
    /// # Errors
    /// No experiment `k`, or an edit does not fit (as [`Experiment::apply`]).
    pub fn scene(&self, k: usize, base: &SceneDesc) -> std::result::Result<SceneDesc, String> {
        let x = self
            .experiments
            .get(k)
            .ok_or_else(|| format!("{}: no experiment {k}", self.name))?;
        // `after` always names an earlier experiment, so this ends.
        let start = match x.after {
            Some(a) if a < k => self.scene(a, base)?,
            _ => base.clone(),
        };
        x.apply(&start)
    }

    /// The experiments `k` builds on, nearest first.
    #[must_use]
    pub fn chain(&self, k: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut at = self.experiments.get(k).and_then(|x| x.after);
        while let Some(a) = at.filter(|a| !out.contains(a)) {
            out.push(a);
            at = self.experiments.get(a).and_then(|x| x.after);
        }
        out
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LessonFile {
    title: String,
    preset: Spanned<String>,
    text: String,
    #[serde(default, rename = "experiment")]
    experiments: Vec<ExperimentFile>,
    #[serde(default, rename = "exercise")]
    exercises: Vec<exercise::ExerciseFile>,
    question: QuestionFile,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ExperimentFile {
    label: String,
    look_for: String,
    #[serde(default)]
    after: Option<Spanned<String>>,
    set: Spanned<toml::Table>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct QuestionFile {
    ask: String,
    answer: String,
}

/// 1-based line and column of byte `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before
        .rfind('\n')
        .map_or(before.len(), |i| before.len() - i - 1)
        + 1;
    (line, col)
}

fn at(path: &Path, text: &str, offset: usize, message: impl Into<String>) -> Error {
    let (line, column) = line_col(text, offset);
    Error::Preset {
        path: path.to_path_buf(),
        line,
        column,
        message: message.into(),
    }
}

/// A TOML value as RON text: strings are RON already; numbers and booleans are the same in
/// both; a list of numbers is a point or colour `(x, y, z)`.
fn ron_text(v: &toml::Value) -> std::result::Result<String, String> {
    Ok(match v {
        toml::Value::String(s) => s.clone(),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(f) => format!("{f:?}"),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::Array(items) => {
            let parts: std::result::Result<Vec<String>, String> =
                items.iter().map(ron_text).collect();
            format!("({})", parts?.join(", "))
        }
        toml::Value::Table(_) | toml::Value::Datetime(_) => {
            return Err(
                "write this value as RON text in a string, as in a preset: \"Image(path: ...)\""
                    .into(),
            );
        }
    })
}

/// Parses a lesson's text (`file` names it in errors, and its folder is where `preset` is
/// found) and checks every edit against the preset.
///
/// # Errors
/// One error naming the file, line and column: TOML syntax, an unknown or missing field, a
/// preset that does not load or build, an empty `set`, an edit whose path or value does not fit
/// the preset, or an experiment whose scene does not build (a value out of range, a missing
/// image).
pub fn parse_lesson(text: &str, file: &Path) -> Result<Lesson> {
    parse_with(text, file, &mut AssetCache::checking())
}

/// [`parse_lesson`] with a cache shared by several lessons (each image is read once).
fn parse_with(text: &str, file: &Path, cache: &mut AssetCache) -> Result<Lesson> {
    let raw: LessonFile = toml::from_str(text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        at(file, text, offset, e.message().trim().to_owned())
    })?;
    let folder = file.parent().unwrap_or(Path::new("."));
    let preset = preset_path(folder, Path::new(raw.preset.get_ref()));
    let base = load_preset(&preset).map_err(|e| {
        at(
            file,
            text,
            raw.preset.span().start,
            format!("preset {:?} does not load: {e}", raw.preset.get_ref()),
        )
    })?;
    build_scene(&base, &preset, cache).map_err(|e| {
        at(
            file,
            text,
            raw.preset.span().start,
            format!("preset {:?} does not build: {e}", raw.preset.get_ref()),
        )
    })?;
    // The notices of each scene checked, each once (the experiments repeat the preset's).
    let (mut seen, mut warnings) = (Vec::new(), Vec::new());
    let mut notice = |c: &AssetCache, scene: &str| notice_once(c, scene, &mut seen, &mut warnings);
    notice(cache, &format!("preset {:?}", raw.preset.get_ref()));
    let mut experiments: Vec<Experiment> = Vec::new();
    // Each experiment's scene, for those that build on it.
    let mut scenes: Vec<SceneDesc> = Vec::new();
    for x in raw.experiments {
        let span = x.set.span();
        if x.set.get_ref().is_empty() {
            return Err(at(
                file,
                text,
                span.start,
                format!("experiment \"{}\": `set` is empty", x.label),
            ));
        }
        let mut edits = Vec::new();
        let after = match &x.after {
            None => None,
            Some(a) => Some(
                experiments
                    .iter()
                    .position(|e| e.label == *a.get_ref())
                    .ok_or_else(|| {
                        at(
                            file,
                            text,
                            a.span().start,
                            format!(
                                "experiment \"{}\": `after` names no experiment before it: \"{}\"",
                                x.label,
                                a.get_ref()
                            ),
                        )
                    })?,
            ),
        };
        let start = after.map_or_else(|| base.clone(), |a| scenes[a].clone());
        let mut desc = start.clone();
        for (key, value) in x.set.get_ref() {
            // The line of this key inside the `set` table (its span covers the whole table).
            let slice = &text[span.clone()];
            let offset = span.start + slice.find(key.as_str()).unwrap_or(0);
            let fail = |m: String| {
                at(
                    file,
                    text,
                    offset,
                    format!("experiment \"{}\": {m}", x.label),
                )
            };
            let value = ron_text(value).map_err(|m| fail(format!("`{key}`: {m}")))?;
            desc = edit::set_path(&desc, key, &value).map_err(fail)?;
            edits.push(Edit {
                path: key.clone(),
                value,
            });
        }
        if desc == start {
            return Err(at(
                file,
                text,
                span.start,
                format!(
                    "experiment \"{}\" changes nothing: the scene it starts from already has these values",
                    x.label
                ),
            ));
        }
        build_scene(&desc, &preset, cache).map_err(|e| {
            at(
                file,
                text,
                span.start,
                format!("experiment \"{}\": the scene does not build: {e}", x.label),
            )
        })?;
        notice(cache, &format!("experiment \"{}\"", x.label));
        scenes.push(desc);
        experiments.push(Experiment {
            label: x.label,
            look_for: x.look_for,
            edits,
            after,
        });
    }
    let mut exercises = Vec::new();
    for (k, x) in raw.exercises.into_iter().enumerate() {
        let built = x
            .build(&base)
            .map_err(|(offset, m)| at(file, text, offset, format!("exercise {}: {m}", k + 1)))?;
        let applied = built
            .apply(&base, &built.solution)
            .map_err(|m| at(file, text, 0, format!("exercise {}: {m}", k + 1)))?;
        build_scene(&applied, &preset, cache).map_err(|e| {
            at(
                file,
                text,
                0,
                format!(
                    "exercise {}: the scene with the solution does not build: {e}",
                    k + 1
                ),
            )
        })?;
        notice(cache, &format!("exercise {}", k + 1));
        exercises.push(built);
    }
    Ok(Lesson {
        name: lesson_name(file),
        file: file.to_path_buf(),
        title: raw.title.trim().to_owned(),
        preset,
        // Only blank lines go: a text may start with an indented formula.
        text: raw
            .text
            .trim_start_matches(['\n', '\r'])
            .trim_end()
            .to_owned(),
        experiments,
        exercises,
        question: raw.question.ask.trim().to_owned(),
        answer: raw.question.answer.trim().to_owned(),
        warnings,
    })
}

/// Adds to `warnings` the notices of the scene `cache` checked last that are not in `seen`,
/// each prefixed with `scene`.
fn notice_once(cache: &AssetCache, scene: &str, seen: &mut Vec<String>, out: &mut Vec<String>) {
    for n in cache.notices() {
        if !seen.contains(n) {
            seen.push(n.clone());
            out.push(format!("{scene}: {n}"));
        }
    }
}

/// Reads (at most [`MAX_LESSON_BYTES`], through [`crate::input`]) and parses one lesson.
///
/// # Errors
/// As [`parse_lesson`], or the file cannot be read.
pub fn load_lesson(file: &Path) -> Result<Lesson> {
    load_with(file, &mut AssetCache::checking())
}

fn load_with(file: &Path, cache: &mut AssetCache) -> Result<Lesson> {
    let text = crate::input::read_input_text(file, MAX_LESSON_BYTES)?;
    parse_with(&text, file, cache)
}

/// The preset `named` in a lesson of `folder`: beside the lesson, else (a teacher's copy of a
/// shipped lesson, naming `../presets/earth.ron`) the shipped file of that name.
fn preset_path(folder: &Path, named: &Path) -> PathBuf {
    let beside = folder.join(named);
    if crate::input::exists(&beside) || named.is_absolute() {
        return beside;
    }
    match crate::shipped::lessons_dir() {
        Ok(shipped) if crate::input::exists(&shipped.join(named)) => shipped.join(named),
        _ => beside,
    }
}

/// The folder of a teacher's own lessons: `texplore/lessons` in the user's data folder
/// (`~/.local/share` on Linux, `~/Library/Application Support` on macOS, `%APPDATA%` on
/// Windows). The window and `texplore lesson` list them after the shipped ones.
#[must_use]
pub fn user_dir() -> Option<PathBuf> {
    dirs::data_dir().map(|d| d.join("texplore").join("lessons"))
}

/// Where lessons are looked for when no folder is named: the shipped lessons (the copy of
/// those built into the binary), then [`user_dir`].
#[must_use]
pub fn default_dirs() -> Vec<PathBuf> {
    let mut dirs = Vec::new();
    if let Ok(d) = crate::shipped::lessons_dir() {
        dirs.push(d);
    }
    dirs.extend(user_dir());
    dirs
}

/// The lessons of several folders, each folder's in file-name order, the folders in the order
/// given. A folder that does not exist lists nothing (the user folder until a teacher makes
/// it); the shipped lessons that cannot be copied out are one error.
#[must_use]
pub fn load_dirs(dirs: &[PathBuf]) -> Lessons {
    let mut out = Lessons::default();
    for d in dirs {
        if !crate::input::exists(d) {
            continue;
        }
        match load_dir(d) {
            Ok(l) => {
                out.lessons.extend(l.lessons);
                out.errors.extend(l.errors);
            }
            Err(e) => out.errors.push(e),
        }
    }
    out
}

/// The lessons of [`default_dirs`]; shipped lessons that cannot be copied out of the binary
/// are one error (the teacher's still load).
#[must_use]
pub fn load_default() -> Lessons {
    let mut out = load_dirs(&default_dirs());
    if let Err(e) = crate::shipped::root() {
        out.errors
            .insert(0, Error::invalid(Path::new("lessons"), e));
    }
    out
}

fn lesson_name(file: &Path) -> String {
    file.file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
}

/// The lessons of a folder, and the files that did not load.
#[derive(Debug, Default)]
pub struct Lessons {
    /// The lessons that loaded, in file-name order.
    pub lessons: Vec<Lesson>,
    /// One error per file that did not.
    pub errors: Vec<Error>,
}

/// Loads every `*.toml` in `dir`, in file-name order; a file that fails is one entry of
/// `errors` and the rest still load.
///
/// # Errors
/// The folder cannot be read.
pub fn load_dir(dir: &Path) -> Result<Lessons> {
    let mut files: Vec<PathBuf> = crate::input::list_dir(dir)?
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    let mut out = Lessons::default();
    // Every experiment's scene is checked, not built at full cost: images by their headers
    // (their sizes against the scene's budget), displacements by their triangle counts.
    let mut cache = AssetCache::checking();
    for f in files {
        match load_with(&f, &mut cache) {
            Ok(l) => out.lessons.push(l),
            Err(e) => out.errors.push(e),
        }
    }
    Ok(out)
}

/// The lesson `name` names: its file name without `.toml` (`05-cylindrical`), that name
/// without its number (`cylindrical`), or its number (`5`), tried in that order.
///
/// # Errors
/// No lesson matches (the message lists the names), or several do at the first of these that
/// matches any (`5` for `05-a`, `05-b` and `5-a`; the same name in two folders): the message
/// lists them, with their files when the names alone are the same.
pub fn find<'a>(lessons: &'a [Lesson], name: &str) -> std::result::Result<&'a Lesson, String> {
    let name = name.trim().trim_end_matches(".toml");
    let number = |l: &Lesson| -> Option<u32> {
        let digits: String = l.name.chars().take_while(char::is_ascii_digit).collect();
        digits.parse().ok()
    };
    let bare = |l: &Lesson| {
        l.name
            .trim_start_matches(|c: char| c.is_ascii_digit())
            .trim_start_matches(['-', '_'])
            .to_owned()
    };
    let wanted: Option<u32> = name.parse().ok();
    let rules: [&dyn Fn(&Lesson) -> bool; 3] = [&|l| l.name == name, &|l| bare(l) == name, &|l| {
        wanted.is_some() && number(l) == wanted
    }];
    for rule in rules {
        let matches: Vec<&Lesson> = lessons.iter().filter(|l| rule(l)).collect();
        match matches.as_slice() {
            [] => {}
            [one] => return Ok(one),
            many => {
                let same_names = many.iter().all(|l| l.name == many[0].name);
                let listed: Vec<String> = many
                    .iter()
                    .map(|l| {
                        if same_names {
                            l.file.display().to_string()
                        } else {
                            l.name.clone()
                        }
                    })
                    .collect();
                return Err(format!(
                    "`{name}` names {} lessons: {}; give the full name",
                    many.len(),
                    listed.join(", ")
                ));
            }
        }
    }
    let names: Vec<&str> = lessons.iter().map(|l| l.name.as_str()).collect();
    Err(if names.is_empty() {
        format!("no lesson named `{name}`: no lesson loaded")
    } else {
        format!(
            "no lesson named `{name}`; the lessons are: {}",
            names.join(", ")
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lesson file beside a copy of the Earth preset's folder layout: the text is written to
    /// `lessons/x.toml` under the crate root, so `../presets/earth.ron` resolves.
    fn parse(text: &str) -> Result<Lesson> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        parse_lesson(text, &root.join("lessons/test-lesson.toml"))
    }

    const GOOD: &str = r#"
title = "Cylindrical"
preset = "../presets/earth.ron"
text = "u = phi / 2 pi"

[[experiment]]
label = "Cylinder map"
look_for = "The poles stretch."
set = { "objects[0].material.cd.mapping" = "Cylindrical", "camera.eye" = [0, 0, 3] }

[question]
ask = "Why?"
answer = "Because."
"#;

    fn message(e: &Error) -> (String, usize, String) {
        match e {
            Error::Preset {
                path,
                line,
                message,
                ..
            } => (path.display().to_string(), *line, message.clone()),
            other => panic!("not a located error: {other}"),
        }
    }

    #[test]
    fn a_lesson_loads_with_its_edits_in_ron() {
        let l = parse(GOOD).unwrap();
        assert_eq!(l.name, "test-lesson");
        assert_eq!(l.title, "Cylindrical");
        assert!(l.preset.ends_with("presets/earth.ron"));
        assert_eq!(
            l.experiments[0].edits,
            vec![
                Edit {
                    path: "objects[0].material.cd.mapping".into(),
                    value: "Cylindrical".into()
                },
                Edit {
                    path: "camera.eye".into(),
                    value: "(0, 0, 3)".into()
                }
            ]
        );
        let base = load_preset(&l.preset).unwrap();
        let d = l.experiments[0].apply(&base).unwrap();
        assert_eq!(d.camera.eye, crate::math::Vec3::new(0.0, 0.0, 3.0));
        assert_eq!(
            (l.question.as_str(), l.answer.as_str()),
            ("Why?", "Because.")
        );
    }

    #[test]
    fn every_kind_of_error_names_the_file_and_line() {
        let cases: [(String, usize, &str); 10] = [
            // TOML syntax: an unclosed string on line 3.
            (GOOD.replace("text = \"u = phi / 2 pi\"", "text = \"u = phi"), 4, "string"),
            // An unknown field.
            (GOOD.replace("look_for", "look_fro"), 8, "look_fro"),
            // A missing field.
            (GOOD.replace("answer = \"Because.\"", ""), 11, "answer"),
            // A path that is not in the preset.
            (GOOD.replace("cd.mapping", "cd.maping"), 9, "maping"),
            // A value that does not fit the field.
            (GOOD.replace("\"Cylindrical\"", "\"Cylindric\""), 9, "Cylindric"),
            // A preset that does not exist.
            (GOOD.replace("earth.ron", "mars.ron"), 3, "mars.ron"),
            // An experiment that changes nothing.
            (
                GOOD.replace("\"Cylindrical\", \"camera.eye\" = [0, 0, 3]", "\"Spherical\""),
                9,
                "changes nothing",
            ),
            // A value of the right type out of range: the scene does not build.
            (
                GOOD.replace("\"camera.eye\" = [0, 0, 3]", "\"render.spp\" = 0"),
                9,
                "does not build",
            ),
            // A missing image.
            (
                GOOD.replace(
                    "\"camera.eye\" = [0, 0, 3]",
                    "\"objects[0].material.cd.path\" = '\"nowhere.png\"'",
                ),
                9,
                "nowhere.png",
            ),
            // An empty `set`.
            (
                GOOD.replace(
                    "{ \"objects[0].material.cd.mapping\" = \"Cylindrical\", \"camera.eye\" = [0, 0, 3] }",
                    "{}",
                ),
                9,
                "`set` is empty",
            ),
        ];
        for (text, line, needle) in cases {
            let e = parse(&text).expect_err(needle);
            let (path, got_line, msg) = message(&e);
            assert!(path.ends_with("lessons/test-lesson.toml"), "{path}");
            assert_eq!(got_line, line, "{needle}: {e}");
            assert!(msg.contains(needle), "{needle}: {e}");
            assert!(
                e.to_string().contains(&format!("test-lesson.toml:{line}:")),
                "{e}"
            );
        }
    }

    #[test]
    fn experiments_start_from_the_lessons_scene_unless_they_say_after() {
        let text = format!(
            "{GOOD}\n{}",
            r#"
[[experiment]]
label = "Closer"
look_for = "Bigger."
set = { "camera.eye" = [0, 0, 2] }

[[experiment]]
label = "Closer still, cylindrical"
look_for = "Bigger still."
after = "Cylinder map"
set = { "camera.eye" = [0, 0, 1.5] }
"#
        )
        // The [question] table must come last in TOML: move it there.
        .replace("[question]\nask = \"Why?\"\nanswer = \"Because.\"\n", "")
            + "\n[question]\nask = \"Why?\"\nanswer = \"Because.\"\n";
        let l = parse(&text).unwrap();
        let base = load_preset(&l.preset).unwrap();
        assert_eq!(l.experiments[1].after, None);
        assert_eq!(l.experiments[2].after, Some(0));
        assert_eq!(l.chain(2), vec![0]);
        // "Closer" does not keep the cylinder map of the experiment before it.
        let closer = l.scene(1, &base).unwrap();
        assert_eq!(closer.objects[0].material, base.objects[0].material);
        assert_eq!(closer.camera.eye, crate::math::Vec3::new(0.0, 0.0, 2.0));
        // "Closer still" builds on "Cylinder map": its mapping, then its own eye.
        let still = l.scene(2, &base).unwrap();
        let cylinder = l.scene(0, &base).unwrap();
        assert_eq!(still.objects[0].material, cylinder.objects[0].material);
        assert_ne!(still.objects[0].material, base.objects[0].material);
        assert_eq!(still.camera.eye, crate::math::Vec3::new(0.0, 0.0, 1.5));
        // `after` must name an experiment before it.
        let e = parse(&text.replace("after = \"Cylinder map\"", "after = \"Later\"")).unwrap_err();
        assert!(
            e.to_string()
                .contains("`after` names no experiment before it: \"Later\""),
            "{e}"
        );
    }

    #[test]
    fn a_bad_lesson_does_not_stop_the_others() {
        let dir = tempfile::tempdir().unwrap();
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let preset = root.join("presets/earth.ron").display().to_string();
        let good = GOOD.replace("../presets/earth.ron", &preset);
        std::fs::write(dir.path().join("01-good.toml"), &good).unwrap();
        std::fs::write(
            dir.path().join("02-bad.toml"),
            good.replace("title", "titel"),
        )
        .unwrap();
        std::fs::write(dir.path().join("03-good.toml"), &good).unwrap();
        std::fs::write(dir.path().join("notes.txt"), "not a lesson").unwrap();
        let got = load_dir(dir.path()).unwrap();
        let names: Vec<&str> = got.lessons.iter().map(|l| l.name.as_str()).collect();
        assert_eq!(names, ["01-good", "03-good"]);
        assert_eq!(got.errors.len(), 1);
        assert!(
            got.errors[0].to_string().contains("02-bad.toml:2:"),
            "{}",
            got.errors[0]
        );
        assert_eq!(find(&got.lessons, "3").unwrap().name, "03-good");
        assert_eq!(
            find(&got.lessons, "good").unwrap_err(),
            "`good` names 2 lessons: 01-good, 03-good; give the full name"
        );
        assert_eq!(find(&got.lessons, "01-good").unwrap().name, "01-good");
        assert_eq!(
            find(&got.lessons, "mars").unwrap_err(),
            "no lesson named `mars`; the lessons are: 01-good, 03-good"
        );
    }
}
