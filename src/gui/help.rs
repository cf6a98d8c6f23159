//! *Help → Keyboard shortcuts*: every key and pointer gesture the window answers, in one list
//! (the keys themselves are defined here too, so the list cannot drift from what is handled).

use egui::{Key, KeyboardShortcut, Modifiers};

/// Undo the last change of the scene.
pub const UNDO: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Z);
/// Redo what was undone.
pub const REDO: KeyboardShortcut =
    KeyboardShortcut::new(Modifiers::COMMAND.plus(Modifiers::SHIFT), Key::Z);
/// Redo, the other usual key.
pub const REDO_Y: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Y);
/// Open the path dialog.
pub const OPEN: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::O);
/// Save over the preset (after asking), or ask where.
pub const SAVE: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::S);
/// Show or hide the shortcuts window.
pub const SHORTCUTS_KEY: KeyboardShortcut = KeyboardShortcut::new(Modifiers::NONE, Key::F1);

/// Presentation mode on or off.
pub const PRESENT: KeyboardShortcut = KeyboardShortcut::new(Modifiers::NONE, Key::F5);
/// Presentation mode on or off, the key no browser takes (F5 reloads a page).
pub const PRESENT_P: KeyboardShortcut = KeyboardShortcut::new(Modifiers::NONE, Key::P);
/// Show or hide the inspector (one key away in presentation mode).
pub const INSPECTOR: KeyboardShortcut = KeyboardShortcut::new(Modifiers::NONE, Key::I);
/// A larger UI.
pub const SCALE_UP: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Equals);
/// A larger UI, the key with the plus sign.
pub const SCALE_UP_PLUS: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Plus);
/// A smaller UI.
pub const SCALE_DOWN: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Minus);
/// The UI at its own size.
pub const SCALE_RESET: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Num0);

/// The keys, in the order the window lists them, with what they do.
pub const KEYS: [(KeyboardShortcut, &str); 13] = [
    (OPEN, "Open a preset or a texplore PNG"),
    (
        SAVE,
        "Save the scene over its preset (asks first), or save as",
    ),
    (UNDO, "Undo the last change of the scene"),
    (REDO, "Redo"),
    (REDO_Y, "Redo"),
    (SHORTCUTS_KEY, "Show or hide this list"),
    (
        PRESENT,
        "Presentation mode: the image alone, with the lesson's captions",
    ),
    (
        PRESENT_P,
        "Presentation mode (in the page too, where F5 reloads)",
    ),
    (INSPECTOR, "Show or hide the inspector"),
    (SCALE_UP, "Larger UI (for a projector)"),
    (SCALE_UP_PLUS, "Larger UI"),
    (SCALE_DOWN, "Smaller UI"),
    (SCALE_RESET, "UI at its own size"),
];

/// The pointer gestures over the image and in dialogs.
pub const POINTER: [(&str, &str); 7] = [
    ("Drag", "Orbit the camera around the point looked at"),
    ("Right-drag, Shift+drag", "Pan the camera"),
    ("Wheel", "Zoom (slows near the surface, stops short of it)"),
    ("Click", "Pin the inspector to that pixel and show it"),
    (
        "Drag the A/B divider",
        "Move the split between the two renders",
    ),
    ("Enter", "Load a typed path; confirm a dialog"),
    ("Esc", "Close a dialog or menu"),
];

/// The shortcuts window, while `open`.
pub fn shortcuts_window(ctx: &egui::Context, open: &mut bool) {
    egui::Window::new("Keyboard shortcuts")
        .open(open)
        .collapsible(false)
        .resizable(false)
        .show(ctx, |ui| {
            egui::Grid::new("shortcuts")
                .num_columns(2)
                .striped(true)
                .show(ui, |ui| {
                    for (key, what) in KEYS {
                        ui.strong(ctx.format_shortcut(&key));
                        ui.label(what);
                        ui.end_row();
                    }
                    for (gesture, what) in POINTER {
                        ui.strong(gesture);
                        ui.label(what);
                        ui.end_row();
                    }
                });
            ui.weak(
                "Undo covers every change of the scene; a drag, a run of wheel clicks or the \
                 typing in one field is one step.",
            );
        });
}
