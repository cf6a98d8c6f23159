//! texplore's own file chooser, for a *Browse…* where the system has no file dialog (on Linux,
//! no XDG desktop portal): the folder of the path typed, its folders and its files of the kind
//! asked for, listed under the path field. A folder clicked is opened (a save keeps the file
//! name typed); a file clicked goes into the field.

use std::path::{MAIN_SEPARATOR, Path, PathBuf};

/// The most entries listed (a folder of thousands of photographs lists the first ones).
const MAX_ENTRIES: usize = 400;

/// The folder the path `typed` names or lies in (the nearest existing one; the working folder
/// for nothing typed), and the file name typed after it.
fn folder_and_name(typed: &str) -> (PathBuf, String) {
    let t = typed.trim();
    let path = Path::new(t);
    let (dir, name) = if t.is_empty() || t.ends_with(['/', MAIN_SEPARATOR]) || path.is_dir() {
        (path.to_path_buf(), String::new())
    } else {
        (
            path.parent().map(Path::to_path_buf).unwrap_or_default(),
            path.file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
        )
    };
    let dir = if dir.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        dir
    };
    let absolute = std::path::absolute(&dir).unwrap_or(dir);
    let existing = absolute
        .ancestors()
        .find(|a| a.is_dir())
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    (existing, name)
}

/// The sub-folders (not hidden) and the files with one of `extensions`, each sorted by name.
fn entries(dir: &Path, extensions: &[&str]) -> (Vec<PathBuf>, Vec<PathBuf>) {
    let mut folders = Vec::new();
    let mut files = Vec::new();
    for p in crate::input::list_dir(dir).unwrap_or_default() {
        let hidden = p
            .file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with('.'));
        if hidden {
            continue;
        }
        if p.is_dir() {
            folders.push(p);
        } else if p
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| extensions.contains(&e.to_ascii_lowercase().as_str()))
        {
            files.push(p);
        }
    }
    folders.sort();
    files.sort();
    (folders, files)
}

/// The chooser under a path field holding `text`: clicking changes `text`. `extensions` are the
/// files listed; `saving` keeps the typed file name when a folder is opened.
pub(super) fn folder_view(ui: &mut egui::Ui, text: &mut String, extensions: &[&str], saving: bool) {
    let (dir, name) = folder_and_name(text);
    let (folders, files) = entries(&dir, extensions);
    ui.label(format!("In {}:", dir.display()));
    let mut chosen = None;
    egui::ScrollArea::vertical()
        .id_salt("folder-view")
        .max_height(200.0)
        .show(ui, |ui| {
            if let Some(up) = dir.parent()
                && ui
                    .selectable_label(false, "../")
                    .on_hover_text(up.display().to_string())
                    .clicked()
            {
                chosen = Some((up.to_path_buf(), true));
            }
            let listed = folders
                .iter()
                .map(|f| (f, true))
                .chain(files.iter().map(|f| (f, false)))
                .take(MAX_ENTRIES);
            for (p, folder) in listed {
                let shown = p
                    .file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
                let shown = if folder {
                    format!("{shown}{MAIN_SEPARATOR}")
                } else {
                    shown
                };
                if ui.selectable_label(false, shown).clicked() {
                    chosen = Some((p.clone(), folder));
                }
            }
            if folders.len() + files.len() > MAX_ENTRIES {
                ui.weak(format!(
                    "… and {} more: type the start of the name",
                    folders.len() + files.len() - MAX_ENTRIES
                ));
            }
        });
    match chosen {
        Some((folder, true)) => {
            *text = if saving && !name.is_empty() {
                folder.join(&name).display().to_string()
            } else {
                format!("{}{MAIN_SEPARATOR}", folder.display())
            };
        }
        Some((file, false)) => *text = file.display().to_string(),
        None => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_folder_of_what_is_typed_and_its_files_of_the_kind() {
        let dir = tempfile::tempdir().expect("temp dir");
        std::fs::create_dir(dir.path().join("sub")).expect("sub");
        std::fs::create_dir(dir.path().join(".hidden")).expect("hidden");
        for f in ["b.ron", "a.ron", "c.png", "notes.txt"] {
            std::fs::write(dir.path().join(f), "x").expect("file");
        }
        let typed = dir.path().join("mine.ron").display().to_string();
        let (folder, name) = folder_and_name(&typed);
        assert_eq!(canonical(&folder), canonical(dir.path()));
        assert_eq!(name, "mine.ron");
        // A folder that does not exist yet: its nearest existing one.
        let typed = dir.path().join("new/deeper/x.ron").display().to_string();
        assert_eq!(canonical(&folder_and_name(&typed).0), canonical(dir.path()));
        let (folders, files) = entries(dir.path(), &["ron"]);
        let names = |v: &[PathBuf]| -> Vec<String> {
            v.iter()
                .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
                .collect()
        };
        assert_eq!(names(&folders), ["sub"]);
        assert_eq!(names(&files), ["a.ron", "b.ron"]);
    }

    fn canonical(p: &Path) -> PathBuf {
        std::fs::canonicalize(p).unwrap()
    }
}
