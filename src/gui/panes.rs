//! What each tile of the [`Layout`](super::layout::Layout) draws: the image, the scene panel,
//! the Lessons panel, the inspector and the texture panel, as `egui_tiles` asks for them; and
//! presentation mode's strip and captions over the image.

use super::app::ExplorerApp;
use super::command::Command;
use super::layout::{Open, Pane};
use super::lessons::captions;
use super::viewport;
use crate::math::Vec2;

/// The width of presentation mode's strip (points).
const STRIP_WIDTH: f32 = 84.0;

/// A pane's name in presentation mode's strip (short: the strip is narrow).
fn strip_name(pane: Pane) -> &'static str {
    match pane {
        Pane::Image => "Image",
        Pane::Scene => "Scene",
        Pane::Lessons => "Lesson",
        Pane::Inspector => "Inspect",
        Pane::Texture => "Texture",
    }
}

/// The body text of the panels in presentation mode, in pixels of a 720-row window (a larger
/// window scales it with its height): read from the back of a classroom.
pub const PRESENT_BODY_PX: f32 = 20.0;

/// Presentation mode's panel text: every text style of `ui` scaled so that body text is at
/// least [`PRESENT_BODY_PX`] pixels high at 720 rows (more on a taller window; a UI scale that
/// already makes it larger is kept).
fn presentation_text(ui: &mut egui::Ui) {
    let ctx = ui.ctx().clone();
    let ppp = ctx.pixels_per_point();
    let rows = ctx.content_rect().height() * ppp;
    let target = PRESENT_BODY_PX * (rows / 720.0).max(1.0);
    let style = ui.style_mut();
    let body = style
        .text_styles
        .get(&egui::TextStyle::Body)
        .map_or(13.0, |f| f.size);
    let factor = (target / (body * ppp)).max(1.0);
    for font in style.text_styles.values_mut() {
        font.size *= factor;
    }
}

/// The tiles' behaviour: draws each pane from the app, collects the commands its panels push
/// and the tabs closed by their close buttons.
pub(super) struct Panes<'a> {
    pub app: &'a mut ExplorerApp,
    pub commands: &'a mut Vec<Command>,
    /// Panes whose tab's close button was pressed this frame.
    pub closed: Vec<Pane>,
}

impl egui_tiles::Behavior<Pane> for Panes<'_> {
    fn pane_ui(
        &mut self,
        ui: &mut egui::Ui,
        _tile_id: egui_tiles::TileId,
        pane: &mut Pane,
    ) -> egui_tiles::UiResponse {
        if *pane != Pane::Image && self.app.layout.presenting() {
            presentation_text(ui);
        }
        // Each pane inside a margin, so its content never touches the tab bar or a neighbour.
        egui::Frame::new()
            .inner_margin(egui::Margin::same(6))
            .show(ui, |ui| match *pane {
                Pane::Image => self.app.image_pane(ui, self.commands),
                Pane::Scene => self.app.scene_pane(ui),
                Pane::Lessons => self.app.lessons_pane(ui, self.commands),
                Pane::Inspector => self.app.inspector_pane(ui),
                Pane::Texture => self.app.texture_pane(ui),
            });
        egui_tiles::UiResponse::None
    }

    fn tab_title_for_pane(&mut self, pane: &Pane) -> egui::WidgetText {
        pane.title().into()
    }

    fn is_tab_closable(
        &self,
        tiles: &egui_tiles::Tiles<Pane>,
        tile_id: egui_tiles::TileId,
    ) -> bool {
        !matches!(tiles.get_pane(&tile_id), Some(Pane::Image) | None)
    }

    fn on_tab_close(
        &mut self,
        tiles: &mut egui_tiles::Tiles<Pane>,
        tile_id: egui_tiles::TileId,
    ) -> bool {
        // The tile stays (hidden) so the panel reopens where it was.
        if let Some(p) = tiles.get_pane(&tile_id) {
            self.closed.push(*p);
        }
        false
    }

    fn is_tab_bar_visible(&self, _tile_id: egui_tiles::TileId, tabs: &egui_tiles::Tabs) -> bool {
        // In presentation mode the image alone needs no tab: its pixels go to the image.
        !(self.app.layout.presenting() && tabs.children.len() == 1)
    }

    fn simplification_options(&self) -> egui_tiles::SimplificationOptions {
        // Every pane keeps a tab: its title is the handle that drags it elsewhere.
        egui_tiles::SimplificationOptions {
            all_panes_must_have_tabs: true,
            ..Default::default()
        }
    }
}

impl ExplorerApp {
    /// Which panels are open.
    pub(super) fn open_panels(&self) -> Open {
        Open::default()
            .with(Pane::Scene, self.layout.scene_open)
            .with(Pane::Lessons, self.lessons.open)
            .with(Pane::Inspector, self.inspector.open)
            .with(Pane::Texture, self.texture_panel.open)
    }

    /// Opens and closes the panels as `open` says.
    pub(super) fn set_open_panels(&mut self, open: Open) {
        self.layout.scene_open = open.get(Pane::Scene);
        self.lessons.open = open.get(Pane::Lessons);
        self.inspector.open = open.get(Pane::Inspector);
        self.texture_panel.open = open.get(Pane::Texture);
    }

    /// The tiles, filling what the menu bar and the status line leave.
    pub(super) fn tiles(&mut self, ui: &mut egui::Ui, commands: &mut Vec<Command>) {
        let open = self.open_panels();
        self.layout.sync(open);
        let mut tree = std::mem::replace(
            &mut self.layout.tree,
            egui_tiles::Tree::empty(egui::Id::unique("texplore-tiles-swap")),
        );
        let closed = egui::CentralPanel::default()
            .frame(egui::Frame::central_panel(ui.style()).inner_margin(2.0))
            .show(ui, |ui| {
                let mut panes = Panes {
                    app: self,
                    commands,
                    closed: Vec::new(),
                };
                tree.ui(&mut panes, ui);
                panes.closed
            })
            .inner;
        self.layout.tree = tree;
        if std::mem::take(&mut self.show_inspector) {
            self.layout
                .tree
                .make_active(|_, tile| matches!(tile, egui_tiles::Tile::Pane(Pane::Inspector)));
        }
        let mut open = self.open_panels();
        for p in closed {
            open.set(p, false);
        }
        self.set_open_panels(open);
    }

    /// The scene panel: it edits the description in place (disabled while another scene is
    /// opening).
    fn scene_pane(&mut self, ui: &mut egui::Ui) {
        let opening = self.doc.opening();
        // Scrolls both ways inside the pane's own width: wide content (large numbers, long
        // paths) scrolls instead of pushing on the image.
        egui::ScrollArea::both()
            .auto_shrink([false, false])
            .show(ui, |ui| {
                ui.add_enabled_ui(!opening, |ui| {
                    let Self {
                        doc,
                        scene_panel,
                        resolution,
                        ..
                    } = self;
                    doc.sync_ids();
                    scene_panel.show_scene(self.viewer.scene_arc().cloned());
                    if let Some(desc) = &mut doc.desc {
                        // Whether it changed anything is seen at the end of the frame.
                        let ids = &mut doc.ids;
                        let _ = scene_panel.ui(ui, desc, ids, resolution, &doc.path);
                    } else {
                        ui.label("No scene: open a preset from the Presets menu.");
                    }
                });
            });
    }

    /// The Lessons panel: its buttons push commands (open a lesson's preset, apply an
    /// experiment's scene, show an error).
    fn lessons_pane(&mut self, ui: &mut egui::Ui, commands: &mut Vec<Command>) {
        let dirty = self.is_dirty();
        commands.extend(self.lessons.ui(ui, self.doc.desc.as_ref(), dirty));
    }

    /// The inspector: its content changes with every pixel hovered, and scrolls within the
    /// pane.
    fn inspector_pane(&mut self, ui: &mut egui::Ui) {
        // In presentation mode its large text wraps in the narrow pane instead of running off.
        let mut area = if self.layout.presenting() {
            egui::ScrollArea::vertical()
        } else {
            egui::ScrollArea::both()
        }
        .auto_shrink([false, false]);
        if self.inspector.take_scroll_to_top() {
            // A new pixel pinned: its answer, at the top, in view.
            area = area.vertical_scroll_offset(0.0);
        }
        area.show(ui, |ui| self.inspector.ui(ui));
    }

    /// The texture panel.
    fn texture_pane(&mut self, ui: &mut egui::Ui) {
        self.texture_panel.ui(ui, self.inspector.shown());
    }

    /// The image: the render (or the A/B split), its pointer's camera commands, the inspector
    /// following the pointer (a click pins a pixel and shows the inspector); in presentation
    /// mode the lesson's captions beside or over it.
    fn image_pane(&mut self, ui: &mut egui::Ui, commands: &mut Vec<Command>) {
        let size = self
            .viewer
            .scene()
            .map(|s| Vec2::new(s.settings.width as f32, s.settings.height as f32));
        let hint = self.doc.desc.as_ref().and_then(viewport::edge_on_hint);
        let aspect = self
            .doc
            .desc
            .as_ref()
            .map(|d| egui::vec2(d.render.width as f32, d.render.height as f32));
        let caption = if self.layout.presenting() && self.layout.captions {
            self.lessons.caption(self.doc.desc.as_ref())
        } else {
            None
        };
        let ctx = ui.ctx().clone();
        let scale = captions::Scale::of(&ctx);
        let mut placed = None;
        let mut area = |avail: egui::Rect| match (&caption, aspect) {
            (Some(c), Some(a)) => {
                let measure = |text: &str, size: f32, width: f32| {
                    ctx.fonts_mut(|f| {
                        f.layout(
                            text.to_owned(),
                            egui::FontId::proportional(size),
                            egui::Color32::WHITE,
                            width,
                        )
                        .size()
                    })
                };
                let l = captions::place(avail, a, c, scale, &measure);
                let image = l.image;
                placed = Some(l);
                image
            }
            _ => avail,
        };
        let view = self.doc.desc.as_mut().map(|d| &mut d.render.view);
        let out = if self.ab.enabled {
            viewport::show_split(ui, &mut self.ab, size, view, hint.as_deref(), &mut area)
        } else {
            let texture = self.viewer.live.texture();
            viewport::show(ui, texture, size, view, hint.as_deref(), &mut area)
        };
        self.image_space = Some(out.avail);
        self.image_rect = (out.image != egui::Rect::NOTHING).then_some(out.image);
        if let Some(aspect) = aspect {
            let ppp = ctx.pixels_per_point();
            let held = ctx.input(|i| i.pointer.any_down());
            let aspect = Vec2::new(aspect.x, aspect.y);
            self.resolution.viewport(out.area, aspect, ppp, held, &ctx);
        }
        if let (Some(l), Some(a)) = (&placed, aspect) {
            captions::draw(ui, l, a, out.avail);
        }
        commands.extend(out.edit);
        if let Some(scene) = self.viewer.scene() {
            self.inspector.pointer(scene, out.hover, out.click);
        }
        if out.click.is_some() {
            // The pinned pixel's inspector: opened, its tab brought forward (once the tiles
            // are drawn).
            self.inspector.open = true;
            self.show_inspector = true;
        }
    }

    /// Presentation mode's strip: a button per panel (each opens it beside the image), the
    /// captions' switch, and the way out. Words, not pictures: egui's bundled fonts have no
    /// icons, and a word is read from the back of the room.
    pub(super) fn strip(&mut self, ui: &mut egui::Ui) {
        egui::Panel::left("strip")
            .exact_size(STRIP_WIDTH)
            .resizable(false)
            .show(ui, |ui| {
                ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
                ui.add_space(4.0);
                let mut open = self.open_panels();
                let full = egui::vec2(ui.available_width(), 0.0);
                for (pane, tip) in [
                    (Pane::Scene, "The scene panel"),
                    (Pane::Lessons, "The Lessons panel"),
                    (Pane::Inspector, "The inspector (I)"),
                    (Pane::Texture, "The texture panel"),
                ] {
                    let on = open.get(pane);
                    let button = egui::Button::selectable(on, strip_name(pane)).min_size(full);
                    if ui.add(button).on_hover_text(tip).clicked() {
                        open.set(pane, !on);
                    }
                }
                self.set_open_panels(open);
                ui.separator();
                let button =
                    egui::Button::selectable(self.layout.captions, "Captions").min_size(full);
                if ui
                    .add(button)
                    .on_hover_text("The experiment's Look for and the question over the image")
                    .clicked()
                {
                    self.layout.captions = !self.layout.captions;
                }
                ui.add_space(8.0);
                if ui
                    .add(egui::Button::new("Exit").min_size(full))
                    .on_hover_text("Leave presentation mode (F5)")
                    .clicked()
                {
                    self.toggle_presentation();
                }
            });
    }

    /// Enters or leaves presentation mode.
    pub(super) fn toggle_presentation(&mut self) {
        let mut open = self.open_panels();
        self.layout.toggle_presentation(&mut open);
        self.set_open_panels(open);
        // The render follows the image in presentation mode, at once.
        self.resolution.presenting = self.layout.presenting();
    }
}
