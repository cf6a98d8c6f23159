//! The `texplore` binary: no subcommand opens the window; subcommands run headless.

use clap::Parser;
use texplore::cli::{Cli, Command, run};
use texplore::scene::SimdMode;

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let simd = cli.simd;
    let result = match cli.command {
        Some(Command::Lesson(a)) => {
            texplore::cli::lesson::run(&a).and_then(|l| l.map_or(Ok(()), |l| open_lesson(l, simd)))
        }
        Some(command) => run(command, simd),
        None => open_window(cli.open, simd),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}

#[cfg(feature = "gui")]
fn open_window(open: Option<std::path::PathBuf>, simd: SimdMode) -> anyhow::Result<()> {
    // A link to a scene (`texplore 'https://.../#texplore1-...'`) opens its scene, or its
    // lesson at its experiment.
    if let Some(link) = open.as_ref().map(|p| p.to_string_lossy().into_owned())
        && link.contains("#texplore")
    {
        return match texplore::link::resolve(&link)? {
            texplore::link::Target::Scene(path) => texplore::gui::run(Some(path), simd),
            texplore::link::Target::Lesson(lesson, k) => {
                texplore::gui::run_lesson_at(*lesson, k, simd)
            }
        };
    }
    texplore::gui::run(open, simd)
}

#[cfg(feature = "gui")]
fn open_lesson(lesson: texplore::lesson::Lesson, simd: SimdMode) -> anyhow::Result<()> {
    texplore::gui::run_lesson(lesson, simd)
}

#[cfg(not(feature = "gui"))]
fn open_lesson(lesson: texplore::lesson::Lesson, _simd: SimdMode) -> anyhow::Result<()> {
    anyhow::bail!(
        "{}: this texplore was built without the `gui` feature, so it cannot open a lesson",
        lesson.file.display()
    )
}

#[cfg(not(feature = "gui"))]
fn open_window(_open: Option<std::path::PathBuf>, _simd: SimdMode) -> anyhow::Result<()> {
    anyhow::bail!(
        "this texplore was built without the `gui` feature; see `texplore --help` for the headless commands"
    )
}
