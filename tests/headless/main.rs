//! The headless tests, one crate (one binary to link): the library, the CLI and the renders,
//! no window. Each module was a test file of its own; `cargo test --test headless NAME::`
//! runs one of them.

#[path = "../common/mod.rs"]
mod common;
#[path = "../common/formulas.rs"]
mod formulas;
#[cfg(feature = "gui")]
#[path = "../common/layouts.rs"]
mod layouts;

mod antialiasing;
mod cli;
mod closed_ends;
mod displacement;
mod exercises;
mod field_paths;
mod footprint;
mod formula;
mod fuzz;
mod hard_cases;
mod hostile;
mod hostile_accept;
mod hostile_budget;
mod hostile_cache;
mod hostile_formula;
#[cfg(feature = "gui")]
mod hostile_layout;
mod hostile_read;
#[cfg(feature = "gui")]
mod hostile_storage;
mod hostile_values;
mod images;
mod layering;
mod lesson_tables;
mod lessons;
mod lessons_claims;
mod link;
mod materials;
mod memory;
mod meshes;
mod peer;
mod presets;
mod real_files;
mod report;
mod simd;
mod snapshots;
mod texture_panel;
