//! The window's tests, one crate: `egui_kittest` drives the real app and draws it with wgpu
//! (Mesa's lavapipe on a machine without a GPU). `cargo test --test window NAME::` runs one
//! module. Needs the `gui` feature (on by default).
#![cfg(feature = "gui")]

#[path = "../common/formulas.rs"]
mod formulas;
#[path = "../common/gui.rs"]
mod gui_common;
#[path = "../common/layouts.rs"]
mod layouts;

mod gui;
mod gui_browse;
mod gui_class;
mod gui_displace;
mod gui_edit;
mod gui_exercise;
mod gui_files;
mod gui_formula;
mod gui_formula_typing;
mod gui_frame_time;
mod gui_hostile;
mod gui_labels;
mod gui_layout;
mod gui_lessons;
mod gui_lessons_class;
mod gui_links;
mod gui_materials;
mod gui_save;
mod gui_scene_notices;
mod gui_texture_panel;
mod gui_view;
