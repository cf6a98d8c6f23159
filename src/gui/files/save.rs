//! Where a save may go (issue 37 §4): never over a shipped file or a lesson's scene, and never
//! into the folder of texplore's own copy of the shipped files (`shipped::root`, which it
//! checks and rewrites at every start), a new name there included. A refused path is said at
//! the Save button, with the user's own folder offered instead.

use super::{DialogKind, canonical, read_only_reason, stem};
use std::path::{Path, PathBuf};

/// Whether `path`, existing or not, lies in the folder of texplore's copy of the shipped files
/// (its nearest existing folder is looked up, so a new file's name and a new folder's count).
#[must_use]
pub(super) fn inside_shipped(path: &Path) -> bool {
    let Ok(root) = crate::shipped::root() else {
        return false;
    };
    // In a page the shipped files are mounted in memory, not a folder a save could reach.
    if root.as_os_str().is_empty() {
        return false;
    }
    let root = canonical(root);
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    absolute
        .ancestors()
        .find(|a| a.exists())
        .is_some_and(|a| canonical(a).starts_with(&root))
}

/// Why `path` is refused as a save's target for lying in texplore's copy of the shipped files.
#[must_use]
pub(super) fn shipped_folder_reason(path: &Path) -> Option<String> {
    inside_shipped(path).then(|| {
        format!(
            "{} is texplore's own copy of its shipped files, checked and rewritten at every \
             start: save in a folder of yours",
            crate::shipped::root().map_or_else(|_| String::new(), |r| r.display().to_string())
        )
    })
}

/// Why a save of kind `kind` to `path` is refused, if it is (`protected`: the lessons' scenes).
#[must_use]
pub(super) fn refusal(kind: DialogKind, path: &Path, protected: &[PathBuf]) -> Option<String> {
    if !matches!(kind, DialogKind::SaveAs | DialogKind::Screenshot) {
        return None;
    }
    read_only_reason(path, protected)
}

/// The file a refused save is offered instead: the same name (or the scene's, `current`) in
/// the user's Documents folder for a preset, Pictures for a screenshot (else the home folder),
/// numbered so that it replaces nothing.
#[must_use]
pub(super) fn your_folder(kind: DialogKind, typed: &Path, current: &Path) -> PathBuf {
    let (dir, ext) = if kind == DialogKind::Screenshot {
        (dirs::picture_dir(), "png")
    } else {
        (dirs::document_dir(), "ron")
    };
    let dir = dir
        .or_else(dirs::home_dir)
        .unwrap_or_else(|| PathBuf::from("."));
    let named = typed.file_name().is_some() && !typed.as_os_str().is_empty();
    let stem = stem(if named { typed } else { current });
    let mut p = dir.join(format!("{stem}.{ext}"));
    let mut n = 2;
    while p.exists() && n < 10_000 {
        p = dir.join(format!("{stem}-{n}.{ext}"));
        n += 1;
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_folder_refuses_new_names_and_others_do_not() {
        let root = crate::shipped::root().expect("the shipped copy");
        for p in [
            root.join("pr"),
            root.join("presets/new.ron"),
            root.join("new-folder/deeper/x.ron"),
        ] {
            assert!(inside_shipped(&p), "{}", p.display());
            let why = refusal(DialogKind::SaveAs, &p, &[]).expect("refused");
            assert!(why.contains("own copy of its shipped files"), "{why}");
            assert!(refusal(DialogKind::Screenshot, &p, &[]).is_some());
            assert!(
                refusal(DialogKind::Open, &p, &[]).is_none(),
                "opening is fine"
            );
        }
        let dir = tempfile::tempdir().expect("temp dir");
        assert!(!inside_shipped(&dir.path().join("mine.ron")));
        assert_eq!(
            refusal(DialogKind::SaveAs, &dir.path().join("mine.ron"), &[]),
            None
        );
        // Over a shipped file: the read-only reason.
        let earth = root.join("presets/earth.ron");
        let why = refusal(DialogKind::SaveAs, &earth, &[]).expect("refused");
        assert!(why.contains("ships with texplore"), "{why}");
    }

    #[test]
    fn the_offer_is_in_the_users_folder_and_replaces_nothing() {
        let offer = your_folder(
            DialogKind::SaveAs,
            Path::new("/somewhere/shipped/pr"),
            Path::new("earth.ron"),
        );
        assert_eq!(offer.extension().and_then(|e| e.to_str()), Some("ron"));
        assert!(
            offer
                .file_stem()
                .is_some_and(|s| s.to_string_lossy().starts_with("pr"))
        );
        assert!(!offer.exists());
        assert!(!inside_shipped(&offer));
        let shot = your_folder(
            DialogKind::Screenshot,
            Path::new(""),
            Path::new("earth.ron"),
        );
        assert!(
            shot.file_stem()
                .is_some_and(|s| s.to_string_lossy().starts_with("earth"))
        );
        assert_eq!(shot.extension().and_then(|e| e.to_str()), Some("png"));
    }
}
