//! What the last scene build said about its textures, in the status line until the next build
//! lands: each texture whose footprint filter reads EWA because its image's summed-area tables
//! did not fit what was left of the scene's texture budget, or cannot sum its texels exactly
//! (`AssetCache::notices`, what `texplore render` prints as warnings).

use super::app::ExplorerApp;

/// Shows `notices`, if any, at the end of the status line: how many, and the first one (cut to
/// the space left); all of them on hover.
pub(super) fn status(ui: &mut egui::Ui, notices: &[String]) {
    let Some(first) = notices.first() else {
        return;
    };
    ui.separator();
    // The count first: the text is cut to the space left.
    let head = match notices.len() {
        1 => "warning".to_owned(),
        n => format!("{n} warnings"),
    };
    let text = egui::RichText::new(format!("{head}: {first}")).color(ui.visuals().warn_fg_color);
    ui.add(egui::Label::new(text).truncate())
        .on_hover_text(notices.join("\n\n"));
}

impl ExplorerApp {
    /// Reopens the scene under a texture budget of `bytes` instead of 1 GiB, from a fresh asset
    /// cache: tests reach the budget's limits (the summed-area tables' warnings) with small
    /// images.
    pub fn set_texture_budget(&mut self, bytes: u64) {
        self.doc.set_texture_budget(bytes);
        let path = self.doc.path.clone();
        self.open_file(&path);
    }

    /// What the last scene build said about its textures (shown in the status line).
    #[must_use]
    pub fn scene_notices(&self) -> &[String] {
        &self.scene_notices
    }
}
