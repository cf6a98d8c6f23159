//! `texplore lesson`: list the lessons, or pick one for the window to open.

use crate::lesson::{LESSON_DIR, Lesson, find, load_dir};
use anyhow::{Result, bail};
use std::path::PathBuf;

/// `texplore lesson`.
#[derive(Debug, clap::Args)]
pub struct LessonArgs {
    /// The lesson to open: its file name without `.toml` (`05-cylindrical-mapping`), that name
    /// without the number (`cylindrical-mapping`), or the number (`5`).
    #[arg(required_unless_present = "list")]
    pub name: Option<String>,
    /// List the lessons (name and title) and any that do not load, then exit.
    #[arg(long, conflicts_with = "name")]
    pub list: bool,
    /// Where the lessons are.
    #[arg(long, default_value = LESSON_DIR)]
    pub dir: PathBuf,
}

/// Lists the lessons (`--list`: returns `None`), or returns the lesson `NAME` names for the
/// window to open. Lessons that do not load are reported on stderr, one line each.
///
/// # Errors
/// The folder cannot be read; `--list` when a lesson did not load (after listing the others);
/// no lesson matches `NAME` (the message lists the names).
pub fn run(a: &LessonArgs) -> Result<Option<Lesson>> {
    let loaded = load_dir(&a.dir)?;
    for e in &loaded.errors {
        eprintln!("error: {e}");
    }
    if a.list {
        // A lesson file is text from anywhere: its name and title are printed with control
        // characters escaped, so a title cannot clear or recolour the terminal.
        let lessons: Vec<(String, String)> = loaded
            .lessons
            .iter()
            .map(|l| (printable(&l.name), printable(&l.title)))
            .collect();
        let width = lessons
            .iter()
            .map(|(n, _)| n.chars().count())
            .max()
            .unwrap_or(0);
        for (name, title) in &lessons {
            println!("{name:width$}  {title}");
        }
        if loaded.lessons.is_empty() && loaded.errors.is_empty() {
            eprintln!("{}: no lessons (*.toml) here", a.dir.display());
        }
        if !loaded.errors.is_empty() {
            bail!(
                "{} of {} lesson files in {} did not load (see above)",
                loaded.errors.len(),
                loaded.errors.len() + loaded.lessons.len(),
                a.dir.display()
            );
        }
        return Ok(None);
    }
    let name = a.name.as_deref().unwrap_or_default();
    match find(&loaded.lessons, name) {
        Ok(l) => Ok(Some(l.clone())),
        Err(m) => bail!("{}: {m}", a.dir.display()),
    }
}

/// `text` with every control character (escape codes, carriage returns, bells) written as its
/// Rust escape (`\u{1b}`), the rest as it is.
fn printable(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}
