//! `texplore lesson`: list the lessons, print one, or pick one for the window to open.
//!
//! The lessons are the shipped ones (built into the binary) and the teacher's own in
//! [`crate::lesson::user_dir`], or, with `--dir`, those of that folder alone.

use crate::lesson::{Lesson, Lessons, find, load_default, load_dir};
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
    /// Print the lesson (its text, experiments and question) instead of opening the window:
    /// a handout.
    #[arg(long, requires = "name")]
    pub print: bool,
    /// Read the lessons of this folder only (default: the shipped lessons, then the teacher's
    /// own in the user folder that `texplore lesson --list` names).
    #[arg(long)]
    pub dir: Option<PathBuf>,
}

/// Lists the lessons (`--list`: returns `None`), or returns the lesson `NAME` names for the
/// window to open. Lessons that do not load are reported on stderr, one line each.
///
/// # Errors
/// The folder cannot be read; `--list` when a lesson did not load (after listing the others);
/// no lesson matches `NAME` (the message lists the names).
pub fn run(a: &LessonArgs) -> Result<Option<Lesson>> {
    let (loaded, place): (Lessons, String) = match &a.dir {
        Some(dir) => (load_dir(dir)?, dir.display().to_string()),
        None => (
            load_default(),
            "the shipped and your own lessons".to_owned(),
        ),
    };
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
        // What the check of each lesson's scenes said about their textures.
        for l in &loaded.lessons {
            for w in &l.warnings {
                eprintln!("warning: {}: {}", l.file.display(), printable(w));
            }
        }
        if loaded.lessons.is_empty() && loaded.errors.is_empty() {
            eprintln!("{place}: no lessons (*.toml) here");
        }
        if a.dir.is_none()
            && let Some(user) = crate::lesson::user_dir()
        {
            eprintln!("(your own lessons go in {})", user.display());
        }
        if !loaded.errors.is_empty() {
            bail!(
                "{} of {} lesson files in {} did not load (see above)",
                loaded.errors.len(),
                loaded.errors.len() + loaded.lessons.len(),
                place
            );
        }
        return Ok(None);
    }
    let name = a.name.as_deref().unwrap_or_default();
    match find(&loaded.lessons, name) {
        Ok(l) if a.print => {
            print!("{}", handout(l));
            Ok(None)
        }
        Ok(l) => Ok(Some(l.clone())),
        Err(m) => bail!("{place}: {m}"),
    }
}

/// The lesson as text: title, preset, text, each experiment with what it builds on and what to
/// look for, each exercise with the formulas it starts from, and the question (the answer and
/// the exercises' solutions last, after a rule), control characters escaped.
#[must_use]
pub fn handout(l: &Lesson) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let _ = writeln!(out, "# {}\n", printable(&l.title));
    let _ = writeln!(out, "Scene: {}\n", l.preset.display());
    let _ = writeln!(out, "{}\n", printable_text(&l.text));
    let _ = writeln!(out, "## Try this\n");
    for (k, x) in l.experiments.iter().enumerate() {
        let _ = writeln!(out, "{}. {}", k + 1, printable(&x.label));
        if let Some(a) = x.after {
            let _ = writeln!(
                out,
                "   (builds on {}. {})",
                a + 1,
                printable(&l.experiments[a].label)
            );
        }
        let _ = writeln!(out, "   Look for: {}", printable(&x.look_for));
    }
    for (k, x) in l.exercises.iter().enumerate() {
        let _ = writeln!(out, "\n## Exercise {}\n\n{}", k + 1, printable(&x.task));
        let _ = writeln!(out, "Checked against {}. Start from:", x.target_name());
        for (name, f) in x.fields().iter().zip(&x.start) {
            let _ = writeln!(out, "    {name} = {}", printable(f));
        }
    }
    let _ = writeln!(out, "\n## Question\n\n{}\n", printable(&l.question));
    let _ = writeln!(out, "---\nAnswer: {}", printable(&l.answer));
    for (k, x) in l.exercises.iter().enumerate() {
        let _ = writeln!(out, "Solution of exercise {}:", k + 1);
        for (name, f) in x.fields().iter().zip(&x.solution) {
            let _ = writeln!(out, "    {name} = {}", printable(f));
        }
    }
    out
}

/// [`printable`] line by line (the line breaks stay).
fn printable_text(text: &str) -> String {
    text.lines().map(printable).collect::<Vec<_>>().join("\n")
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
