//! What the panels ask the app to do. A panel never changes the app itself: the menus, dialogs
//! and drops, the Lessons panel, the Edit menu and its keys, and the viewport's pointer push a
//! [`Command`], and the app carries the frame's commands out in one place ([`ExplorerApp::run`]).
//! Commands that change the scene only change its description: the scene is rebuilt once, at
//! the end of the frame, whatever changed it.

use super::app::{ExplorerApp, absolute_display};
use super::document::Purpose;
use super::viewport;
use crate::math::Vec2;
use crate::scene::{SceneDesc, read_preset_or_png};
use std::path::{Path, PathBuf};

/// Something a panel asks for.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Replace the scene with this preset or texplore PNG.
    Open(PathBuf),
    /// Save the scene as a RON preset here.
    Save(PathBuf),
    /// Save the image here as a PNG with the scene embedded.
    Screenshot(PathBuf),
    /// Put this image on the selected object.
    UseImage(PathBuf),
    /// Make the selected object this mesh (PLY or OBJ).
    UseMesh(PathBuf),
    /// Set the scene's description (typed in the *Save as* dialog).
    Describe(String),
    /// Open this lesson's preset (through the unsaved-changes prompt unless `force`), then
    /// make it the active lesson.
    OpenLesson {
        /// The preset.
        preset: PathBuf,
        /// Skip the prompt: the only changes are the lesson's own experiments.
        force: bool,
    },
    /// Replace the scene with this description (a lesson's experiment, or its undo).
    Apply(SceneDesc),
    /// Undo the last step.
    Undo,
    /// Redo the last undone step.
    Redo,
    /// Orbit the camera by this drag (points).
    Orbit(Vec2),
    /// Pan by this drag, as a fraction of the image height.
    Pan(Vec2),
    /// Move toward the look-at point by this factor of the distance.
    Zoom(f32),
    /// Back to the camera the scene was opened with.
    ResetView,
    /// Show this message.
    Error(String),
    /// Close the window.
    Quit,
}

impl ExplorerApp {
    /// Carries out `command`.
    pub(super) fn run(&mut self, ctx: &egui::Context, command: Command) {
        if self.doc.opening() && command.edits_the_scene() {
            // The scene is being replaced: an edit of the old one would be lost.
            return;
        }
        match command {
            Command::Open(p) => self.open_file(&p),
            Command::Save(p) => self.save(&p),
            Command::Screenshot(p) => match self.save_screenshot(&p) {
                Ok(()) => {
                    self.error = None;
                    self.notify(format!("Screenshot saved to {}", absolute_display(&p)));
                }
                Err(e) => self.error = Some(e.to_string()),
            },
            Command::Describe(d) => {
                if let Some(desc) = &mut self.doc.desc {
                    desc.description = d;
                }
            }
            Command::UseImage(p) => {
                let rel = crate::scene::relative_asset_path(&p, self.doc.folder());
                if let Some(desc) = &mut self.doc.desc {
                    self.scene_panel.use_image(desc, rel);
                }
            }
            Command::UseMesh(p) => {
                let rel = crate::scene::relative_asset_path(&p, self.doc.folder());
                if let Some(desc) = &mut self.doc.desc {
                    self.scene_panel.use_mesh(desc, rel);
                }
            }
            Command::OpenLesson {
                preset,
                force: true,
            } => self.open_file(&preset),
            Command::OpenLesson { preset, .. } => {
                self.files.request_open(preset);
                ctx.request_repaint();
            }
            Command::Apply(d) => self.doc.desc = Some(d),
            Command::Undo | Command::Redo => self.step(&command),
            Command::Orbit(_) | Command::Pan(_) | Command::Zoom(_) | Command::ResetView => {
                self.move_camera(&command);
            }
            Command::Error(e) => self.error = Some(e),
            Command::Quit => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
        }
    }

    /// Opens a preset or a texplore PNG: its scene builds, and replaces the open one when it
    /// lands; on an error the current scene stays and the message shows.
    pub fn open_file(&mut self, path: &Path) {
        match read_preset_or_png(path) {
            Ok(desc) => {
                let recipe = self.recipe(&desc);
                self.doc.open(path, desc, recipe);
            }
            Err(e) => {
                self.error = Some(e.to_string());
                self.lessons.opened(path, false, self.doc.desc.as_ref());
            }
        }
    }

    /// Saves the scene as a preset at `p`, its asset paths rewritten for `p`'s folder.
    fn save(&mut self, p: &Path) {
        let from = self.doc.folder().to_path_buf();
        let Some(desc) = &mut self.doc.desc else {
            return;
        };
        if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) {
            self.error = Some(format!(
                "{}: a preset is saved as .ron; use Save screenshot for a PNG",
                p.display()
            ));
            return;
        }
        let mut out = desc.clone();
        let to = p.parent().unwrap_or(Path::new("."));
        crate::scene::rebase_assets(&mut out, &from, to);
        match crate::scene::save_preset(&out, p) {
            Ok(()) => {
                // The steps to undo hold paths relative to the old folder too.
                self.doc
                    .history
                    .rewrite(|v| crate::scene::rebase_assets(&mut v.desc, &from, to));
                *desc = out.clone();
                self.doc.saved = Some(out);
                self.doc.path = p.to_path_buf();
                self.files.add_recent(p);
                self.error = None;
                self.notify(format!("Saved {}", absolute_display(p)));
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// Undoes or redoes one step: the description and its objects' ids go back, and its build
    /// starts.
    fn step(&mut self, command: &Command) {
        self.doc.record();
        let Some(current) = self.doc.version() else {
            return;
        };
        let kept = self.doc.history.clone();
        let restored = if *command == Command::Undo {
            self.doc.history.undo(&current)
        } else {
            self.doc.history.redo(&current)
        };
        let Some(restored) = restored else { return };
        // The object that came back or went away is the one to look at.
        let (now, before) = (&restored.desc.objects, &current.desc.objects);
        if now.len() != before.len() {
            self.scene_panel.selected = restored
                .ids
                .iter()
                .zip(&current.ids)
                .position(|(a, b)| a != b)
                .unwrap_or(now.len().min(before.len()));
        }
        self.scene_panel.selected = self.scene_panel.selected.min(now.len().saturating_sub(1));
        let recipe = self.recipe(&restored.desc);
        self.doc.restore(restored);
        self.doc.step(kept, recipe);
    }

    /// Moves the camera as the viewport's pointer asked.
    fn move_camera(&mut self, command: &Command) {
        let Some(desc) = &mut self.doc.desc else {
            return;
        };
        let c = &mut desc.camera;
        match *command {
            Command::Orbit(d) => {
                c.eye = crate::camera::orbit(c.eye, c.look_at, c.up, -d.x * 0.01, d.y * 0.01);
            }
            Command::Pan(d) => {
                let shift = crate::camera::pan_offset(c.eye, c.look_at, c.up, -d.x, d.y);
                c.eye += shift;
                c.look_at += shift;
            }
            Command::Zoom(f) => {
                c.eye = viewport::zoomed_eye(self.viewer.scene(), c.eye, c.look_at, f);
            }
            Command::ResetView => {
                if let Some(home) = self.doc.home_camera {
                    *c = home;
                }
            }
            _ => {}
        }
    }

    /// Collects the build that landed, if any: its scene is rendered (an opened file replaces
    /// the panels' state), or its error shows.
    pub(super) fn collect_build(&mut self) {
        let Some(landed) = self.doc.poll() else {
            return;
        };
        match landed.outcome {
            Ok(built) => {
                if let Purpose::Open(path) = &landed.purpose {
                    self.scene_panel.scene_replaced();
                    self.inspector.clear();
                    self.files.add_recent(path);
                    self.lessons.opened(path, true, self.doc.desc.as_ref());
                    // The lessons' scenes are read-only, as the shipped files are.
                    self.files.protect(self.lessons.scenes());
                }
                self.error = None;
                self.scene_notices = built.notices;
                if let Some(split) = built.split {
                    self.viewer.stop();
                    self.ab.start_built(split, self.viewer.generation());
                } else {
                    self.ab.stop();
                    if let Err(e) = self.viewer.start(built.scene.clone()) {
                        self.error = Some(e);
                    }
                }
                self.viewer.show(built.scene);
                self.inspector.refresh(self.viewer.scene());
            }
            Err(e) => {
                if let Purpose::Open(path) = &landed.purpose {
                    self.lessons.opened(path, false, self.doc.desc.as_ref());
                }
                self.error = Some(e);
            }
        }
    }
}

impl Command {
    /// Whether the command changes the open scene (refused while another scene is opening).
    const fn edits_the_scene(&self) -> bool {
        matches!(
            self,
            Self::UseImage(_)
                | Self::UseMesh(_)
                | Self::Describe(_)
                | Self::Apply(_)
                | Self::Undo
                | Self::Redo
                | Self::Orbit(_)
                | Self::Pan(_)
                | Self::Zoom(_)
                | Self::ResetView
                | Self::Save(_)
        )
    }
}
