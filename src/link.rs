//! A link that opens a scene (issue 36 §5): a teacher posts one address and every student opens
//! the same scene or lesson step, with no server involved. The scene travels in the address's
//! fragment (`#...`, which browsers never send to the server): the preset's text, deflated
//! (`miniz_oxide`, pure Rust) and written in base64url.
//!
//! - `#texplore1-s-DATA`: a scene, its preset text with asset paths relative to the shipped
//!   `presets/` folder; only shipped files may be named (a student's own image is left out,
//!   with a notice, and its texture is grey).
//! - `#texplore1-l-NAME` or `#texplore1-l-NAME~K`: lesson `NAME` (its file name without
//!   `.toml`), at experiment `K` (1 for the first).
//!
//! A link is read as strictly as a preset file: bounded ([`MAX_LINK_BYTES`] of text, at most
//! [`crate::scene::MAX_PRESET_BYTES`] once inflated), parsed and checked by the same code, and
//! every file it names must be a shipped one.

use crate::scene::{SceneDesc, TextureDesc, parse_preset, to_ron};
use base64::Engine as _;
use std::path::{Component, Path, PathBuf};

/// The longest link accepted (its fragment's text).
pub const MAX_LINK_BYTES: usize = 8 * 1024;
/// What every link starts with: the format and its version.
pub const VERSION: &str = "texplore1";
/// Where a link's asset paths are relative to: the shipped presets' folder.
pub const LINK_PRESET: &str = "presets/link.ron";

const B64: base64::engine::GeneralPurpose = base64::engine::general_purpose::URL_SAFE_NO_PAD;

/// What a link opens.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Link {
    /// A scene: its preset's text (asset paths relative to [`LINK_PRESET`]'s folder).
    Scene(String),
    /// A lesson, at one of its experiments (0 for the first), or on its own scene.
    Lesson {
        /// The lesson's name (its file name without `.toml`).
        lesson: String,
        /// The experiment (0-based).
        experiment: Option<usize>,
    },
}

/// Why a link was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("this link does not open a scene: {0}")]
pub struct LinkError(pub String);

fn refuse(why: impl Into<String>) -> LinkError {
    LinkError(why.into())
}

/// `path` with `.` dropped and `..` applied.
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::Normal(p) => out.push(p),
            Component::ParentDir => {
                out.pop();
            }
            _ => {}
        }
    }
    out
}

/// Whether `assets/NAME` is a shipped asset (in a page, one beside the page).
fn is_shipped_asset(rel: &str) -> bool {
    #[cfg(target_arch = "wasm32")]
    return crate::input::exists(Path::new(rel));
    #[cfg(not(target_arch = "wasm32"))]
    crate::shipped::get(rel).is_some()
}

/// The shipped asset the file at `file` is (`assets/NAME`), if it is one: in a page, a file of
/// the page's `assets/`; elsewhere, a file with the shipped bytes of that name.
fn shipped_asset(file: &Path) -> Option<String> {
    #[cfg(target_arch = "wasm32")]
    {
        let n = normalise(file);
        let mut parts = n.components();
        let (Some(Component::Normal(top)), Some(Component::Normal(name)), None) =
            (parts.next(), parts.next(), parts.next())
        else {
            return None;
        };
        let rel = format!("assets/{}", name.to_str()?);
        (top == "assets" && is_shipped_asset(&rel)).then_some(rel)
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let rel = format!("assets/{}", file.file_name()?.to_str()?);
        let shipped = crate::shipped::get(&rel)?;
        let bytes = crate::input::read_input(file, shipped.len() as u64 + 1).ok()?;
        (bytes == shipped).then_some(rel)
    }
}

/// The link's fragment (without `#`) for `desc`, a scene whose asset paths are relative to
/// `preset_dir`, and a notice for each file left out (a student's own image: its texture is
/// grey in the link).
///
/// # Errors
/// A mesh that is not a shipped file (a scene without it would not be the scene), or a link
/// longer than [`MAX_LINK_BYTES`].
pub fn scene_fragment(
    desc: &SceneDesc,
    preset_dir: &Path,
) -> Result<(String, Vec<String>), LinkError> {
    let mut d = desc.clone();
    let mut notices = Vec::new();
    for o in &mut d.objects {
        for (_, t) in o.textures_mut() {
            if let TextureDesc::Image { path, .. } = t {
                if let Some(rel) = shipped_asset(&preset_dir.join(&*path)) {
                    *path = format!("../{rel}");
                } else {
                    notices.push(format!(
                        "{path} is not one of the shipped files: the link leaves it out \
                         (its texture is grey there)"
                    ));
                    *t = TextureDesc::Constant(crate::math::Rgb(0.5, 0.5, 0.5));
                }
            }
        }
        if let crate::scene::ShapeDesc::Mesh { path, .. } = &mut o.shape {
            match shipped_asset(&preset_dir.join(&*path)) {
                Some(rel) => *path = format!("../{rel}"),
                None => {
                    return Err(refuse(format!(
                        "the mesh {path} is not one of the shipped files, and a link carries \
                         only their names"
                    )));
                }
            }
        }
    }
    let text = to_ron(&d);
    let deflated = miniz_oxide::deflate::compress_to_vec(text.as_bytes(), 9);
    let fragment = format!("{VERSION}-s-{}", B64.encode(deflated));
    if fragment.len() > MAX_LINK_BYTES {
        return Err(refuse(format!(
            "the scene's link would be {} bytes; links stop at {MAX_LINK_BYTES} (save the \
             preset and share the file instead)",
            fragment.len()
        )));
    }
    Ok((fragment, notices))
}

/// The link's fragment (without `#`) for lesson `lesson` at `experiment` (0-based).
#[must_use]
pub fn lesson_fragment(lesson: &str, experiment: Option<usize>) -> String {
    match experiment {
        Some(k) => format!("{VERSION}-l-{lesson}~{}", k + 1),
        None => format!("{VERSION}-l-{lesson}"),
    }
}

/// The fragment of `link` (a whole address or its fragment, with or without `#`), without
/// the `#`.
///
/// # Errors
/// It is longer than [`MAX_LINK_BYTES`].
pub fn fragment(link: &str) -> Result<&str, LinkError> {
    let link = link.trim();
    let fragment = link.rsplit_once('#').map_or(link, |(_, f)| f);
    if fragment.len() > MAX_LINK_BYTES {
        return Err(refuse(format!(
            "it is {} bytes long; links stop at {MAX_LINK_BYTES}",
            fragment.len()
        )));
    }
    Ok(fragment)
}

/// What `link` opens: a whole address (`https://.../#texplore1-...`), or its fragment with or
/// without `#`.
///
/// # Errors
/// Too long, not a texplore link, another version, damaged (base64, deflate, UTF-8), a preset
/// that does not parse as a preset file would not, or a file named that is not a shipped one.
pub fn parse(link: &str) -> Result<Link, LinkError> {
    let fragment = fragment(link)?;
    let Some(rest) = fragment.strip_prefix("texplore") else {
        return Err(refuse(
            "it is not a texplore link (it should end in #texplore1-...)",
        ));
    };
    let Some(rest) = rest.strip_prefix("1-") else {
        let version: String = rest.chars().take_while(char::is_ascii_digit).collect();
        return Err(refuse(format!(
            "it is a texplore{version} link; this texplore reads {VERSION} links"
        )));
    };
    if let Some(data) = rest.strip_prefix("s-") {
        return scene(data).map(Link::Scene);
    }
    if let Some(l) = rest.strip_prefix("l-") {
        let (name, k) = l.split_once('~').map_or((l, None), |(n, k)| (n, Some(k)));
        if name.is_empty()
            || !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        {
            return Err(refuse(format!("{name:?} is not a lesson's name")));
        }
        let experiment = match k {
            None => None,
            Some(k) => match k.parse::<usize>() {
                Ok(n) if n >= 1 => Some(n - 1),
                _ => return Err(refuse(format!("{k:?} is not an experiment's number"))),
            },
        };
        return Ok(Link::Lesson {
            lesson: name.to_owned(),
            experiment,
        });
    }
    Err(refuse("it names neither a scene (s-) nor a lesson (l-)"))
}

/// A scene link's preset text, checked.
fn scene(data: &str) -> Result<String, LinkError> {
    let bytes = B64
        .decode(data)
        .map_err(|e| refuse(format!("it is damaged (cut short or changed): {e}")))?;
    let limit = usize::try_from(crate::scene::MAX_PRESET_BYTES).unwrap_or(usize::MAX);
    let text = miniz_oxide::inflate::decompress_to_vec_with_limit(&bytes, limit).map_err(|e| {
        refuse(format!(
            "it is damaged (cut short or changed): its scene does not inflate ({:?})",
            e.status
        ))
    })?;
    let text = String::from_utf8(text).map_err(|_| refuse("its scene is not text"))?;
    let desc = parse_preset(&text, Path::new(LINK_PRESET)).map_err(|e| refuse(e.to_string()))?;
    let dir = Path::new(LINK_PRESET).parent().unwrap_or(Path::new(""));
    // The files it names, from the description itself (nothing is read before the check).
    let mut named: Vec<&str> = Vec::new();
    for o in &desc.objects {
        for (_, t) in o.textures() {
            if let TextureDesc::Image { path, .. } = t {
                named.push(path);
            }
        }
        if let crate::scene::ShapeDesc::Mesh { path, .. } = &o.shape {
            named.push(path);
        }
    }
    for file in named {
        let n = normalise(&dir.join(file));
        let rel = n.to_string_lossy().replace('\\', "/");
        let inside = rel.starts_with("assets/") && rel.matches('/').count() == 1;
        if !inside || !is_shipped_asset(&rel) {
            return Err(refuse(format!(
                "it names {file}, which is not one of the shipped files"
            )));
        }
    }
    Ok(text)
}

/// The lesson a lesson link names, among the shipped lessons and the teacher's own, and its
/// experiment checked against the lesson's.
fn lesson_of(
    lesson: &str,
    experiment: Option<usize>,
) -> Result<(crate::lesson::Lesson, Option<usize>), LinkError> {
    let loaded = crate::lesson::load_default();
    let l = crate::lesson::find(&loaded.lessons, lesson).map_err(refuse)?;
    if let Some(k) = experiment.filter(|&k| k >= l.experiments.len()) {
        return Err(refuse(format!(
            "lesson {lesson} has {} experiments, not {}",
            l.experiments.len(),
            k + 1
        )));
    }
    Ok((l.clone(), experiment))
}

/// The text of the scene `link` opens: a scene link's, or a lesson link's lesson scene at its
/// experiment (asset paths relative to the shipped presets' folder either way).
///
/// # Errors
/// The link is refused ([`parse`]), or names a lesson or experiment there is not.
pub fn scene_text(link: &str) -> Result<String, LinkError> {
    match parse(link)? {
        Link::Scene(text) => Ok(text),
        Link::Lesson { lesson, experiment } => {
            let (l, experiment) = lesson_of(&lesson, experiment)?;
            let base = crate::scene::load_preset(&l.preset).map_err(|e| refuse(e.to_string()))?;
            let desc = match experiment {
                Some(k) => l.scene(k, &base).map_err(refuse)?,
                None => base,
            };
            Ok(to_ron(&desc))
        }
    }
}

/// What the window opens for a link.
#[derive(Clone, Debug)]
pub enum Target {
    /// A preset file holding the link's scene ([`materialise`]).
    Scene(PathBuf),
    /// A lesson, with the Lessons panel open on it, at one of its experiments (0-based).
    Lesson(Box<crate::lesson::Lesson>, Option<usize>),
}

/// What the window opens for `link`: a scene link's scene as a preset file ([`materialise`]),
/// or a lesson link's lesson (checked: it exists, and so does its experiment).
///
/// # Errors
/// The link is refused, names a lesson or experiment there is not, or its scene's file cannot
/// be written.
pub fn resolve(link: &str) -> Result<Target, LinkError> {
    match parse(link)? {
        Link::Scene(_) => materialise(link).map(Target::Scene),
        Link::Lesson { lesson, experiment } => {
            let (l, k) = lesson_of(&lesson, experiment)?;
            Ok(Target::Lesson(Box::new(l), k))
        }
    }
}

/// A name for a link's scene file, the same for the same scene.
fn file_name(text: &str) -> String {
    // FNV-1a: a name, not a security measure (the text is checked on reading).
    let hash = text.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("link-{hash:016x}.ron")
}

/// Opens what `link` names as a preset file the window can open like any other, and returns
/// its path: in a page, mounted under `links/` (beside `presets/`, so its asset paths read the
/// same); elsewhere, written (atomically) into `texplore/links` in the user's cache folder, its
/// asset paths pointing into the copy of the shipped files.
///
/// # Errors
/// The link is refused, or the file cannot be written.
pub fn materialise(link: &str) -> Result<PathBuf, LinkError> {
    let text = scene_text(link)?;
    #[cfg(target_arch = "wasm32")]
    {
        let path = Path::new("links").join(file_name(&text));
        crate::input::mount(&path, text.into_bytes());
        Ok(path)
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let presets = crate::shipped::presets_dir().map_err(refuse)?;
        let dir = dirs::cache_dir()
            .ok_or_else(|| refuse("there is no cache folder to open it from"))?
            .join("texplore")
            .join("links");
        std::fs::create_dir_all(&dir)
            .map_err(|e| refuse(format!("cannot make {}: {e}", dir.display())))?;
        let mut desc =
            parse_preset(&text, Path::new(LINK_PRESET)).map_err(|e| refuse(e.to_string()))?;
        crate::scene::rebase_assets(&mut desc, &presets, &dir);
        let path = dir.join(file_name(&text));
        crate::output::write_own_file(&path, to_ron(&desc).as_bytes())
            .map_err(|e| refuse(e.to_string()))?;
        Ok(path)
    }
}
