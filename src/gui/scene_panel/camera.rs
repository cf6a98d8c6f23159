//! The camera editor: the projection and its angles, the eye and the point looked at.

use crate::gui::widgets::{enum_combo, number, vec3};
use crate::scene::{ProjectionDesc, ProjectionKind, SceneDesc};
use std::collections::HashMap;

/// The camera settings. Returns whether any changed. `earlier` holds each projection as it
/// was when the user switched away from it: switching back restores its angles (Pinhole ->
/// Fisheye -> Pinhole gives the preset's 40 degrees back, not the default 45).
pub(super) fn camera_ui(
    ui: &mut egui::Ui,
    desc: &mut SceneDesc,
    earlier: &mut HashMap<ProjectionKind, ProjectionDesc>,
) -> bool {
    let mut changed = false;
    ui.heading("Camera");
    let c = &mut desc.camera;
    let before = c.projection.kind();
    let mut kind = before;
    if enum_combo(ui, "Camera", &mut kind) {
        earlier.insert(before, c.projection);
        c.projection = earlier
            .get(&kind)
            .copied()
            .unwrap_or_else(|| kind.default_desc());
        changed = true;
    }
    match &mut c.projection {
        ProjectionDesc::Pinhole { fov } => {
            changed |= number(ui, "field of view (deg)", fov, 1.0..=179.0, 0.2);
        }
        ProjectionDesc::Fisheye { fov } => {
            changed |= number(ui, "field of view (deg)", fov, 1.0..=360.0, 0.5);
        }
        ProjectionDesc::Spherical { h_fov, v_fov } => {
            changed |= number(ui, "horizontal fov (deg)", h_fov, 1.0..=360.0, 0.5);
            changed |= number(ui, "vertical fov (deg)", v_fov, 1.0..=180.0, 0.5);
        }
        ProjectionDesc::Orthographic { height } => {
            changed |= number(ui, "view height (world units)", height, 1e-3..=1e6, 0.02);
        }
    }
    let mut eye = c.eye;
    if vec3(ui, "eye", &mut eye, 0.02) && eye != c.look_at {
        c.eye = eye;
        changed = true;
    }
    let mut at = c.look_at;
    if vec3(ui, "look at", &mut at, 0.02) && at != c.eye {
        c.look_at = at;
        changed = true;
    }
    changed
}
