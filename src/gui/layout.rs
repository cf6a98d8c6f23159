//! The window's arrangement: the image and the side panels are tiles (`egui_tiles`) the user
//! drags into tabs, columns or rows, resizes and closes; the arrangement is kept between runs.
//! The default gives the image 68% of the width whatever is open: right of it one column holds
//! the Lessons and scene panels as tabs above, the inspector and the texture panel as tabs
//! below, so opening another panel adds a tab or a row instead of taking width from the image.
//!
//! Presentation mode (F5) closes every panel but the image and remembers which were open;
//! leaving it opens them again.

use super::layout_check::check_stored;
use egui_tiles::{Container, Tile, TileId, Tiles, Tree};

/// One tile's content.
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Hash,
    serde::Serialize,
    serde::Deserialize
)]
pub enum Pane {
    /// The rendered image and its toolbar (never closed).
    Image,
    /// The scene panel: objects, materials, textures, render settings.
    Scene,
    /// The Lessons panel.
    Lessons,
    /// The inspector.
    Inspector,
    /// The texture panel.
    Texture,
}

impl Pane {
    /// Every pane, in the order the View menu lists them.
    pub const ALL: [Self; 5] = [
        Self::Image,
        Self::Scene,
        Self::Lessons,
        Self::Inspector,
        Self::Texture,
    ];

    /// The tab's title (and the View menu's entry).
    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Self::Image => "Viewport",
            Self::Scene => "Scene",
            Self::Lessons => "Lessons",
            Self::Inspector => "Inspector",
            Self::Texture => "Texture panel",
        }
    }
}

/// The image's share of the width in the default arrangement: at least 60% of the window
/// whatever is open (the tab bars and gaps take a few points of it).
const IMAGE_SHARE: f32 = 0.68;
/// The panels' column's share of the width.
const PANELS_SHARE: f32 = 0.32;
/// The share of the panels' column's height the upper group (the lesson and the scene) takes.
const UPPER_SHARE: f32 = 0.6;

/// Which panels are open (the image always is): one bit per [`Pane`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Open(u8);

impl Open {
    /// Whether `pane` is open.
    #[must_use]
    pub fn get(self, pane: Pane) -> bool {
        pane == Pane::Image || self.0 & (1 << pane as u8) != 0
    }

    /// Opens or closes `pane` (the image stays open).
    pub fn set(&mut self, pane: Pane, open: bool) {
        if open {
            self.0 |= 1 << pane as u8;
        } else {
            self.0 &= !(1 << pane as u8);
        }
    }

    /// `self` with `pane` opened or closed.
    #[must_use]
    pub fn with(mut self, pane: Pane, open: bool) -> Self {
        self.set(pane, open);
        self
    }
}

/// The arrangement and presentation mode.
pub struct Layout {
    /// The tiles.
    pub tree: Tree<Pane>,
    /// In presentation mode: the panels that were open before it.
    presenting: Option<Open>,
    /// Whether the scene panel is open (*View → Scene*; the other panels keep their own flag).
    pub scene_open: bool,
    /// In presentation mode: the lesson's captions over the image.
    pub captions: bool,
    /// The panels open at the last [`Layout::sync`] (a panel opened since becomes its tab
    /// group's active tab; `None` before the first).
    shown: Option<Open>,
}

impl Default for Layout {
    fn default() -> Self {
        Self {
            tree: default_tree(),
            presenting: None,
            scene_open: true,
            captions: true,
            shown: None,
        }
    }
}

/// The id of the tree (egui keeps its drag state under it).
const TREE_ID: &str = "texplore-tiles";

/// The default arrangement: the image left, and right of it one column of two tab groups,
/// the Lessons and scene panels above, the inspector and the texture panel below (a group
/// with nothing open gives its height to the other).
#[must_use]
pub fn default_tree() -> Tree<Pane> {
    let mut tiles = Tiles::default();
    let mut tabs = |panes: &[Pane]| {
        let children = panes.iter().map(|&p| tiles.insert_pane(p)).collect();
        tiles.insert_tab_tile(children)
    };
    let image = tabs(&[Pane::Image]);
    let upper = tabs(&[Pane::Lessons, Pane::Scene]);
    let lower = tabs(&[Pane::Inspector, Pane::Texture]);
    let mut column = egui_tiles::Linear::new(egui_tiles::LinearDir::Vertical, vec![upper, lower]);
    column.shares.set_share(upper, UPPER_SHARE);
    column.shares.set_share(lower, 1.0 - UPPER_SHARE);
    let column = tiles.insert_container(Container::Linear(column));
    let mut row = egui_tiles::Linear::new(egui_tiles::LinearDir::Horizontal, vec![image, column]);
    row.shares.set_share(image, IMAGE_SHARE);
    row.shares.set_share(column, PANELS_SHARE);
    let root = tiles.insert_container(Container::Linear(row));
    Tree::new(egui::Id::unique(TREE_ID), root, tiles)
}

impl Layout {
    /// The key the arrangement is stored under in eframe's storage.
    pub const KEY: &str = "texplore-layout";

    /// The arrangement kept in `storage`, or the default one: when none is kept, or when the
    /// one kept fails [`check_stored`] (then also why, for the window to say once; the next
    /// save keeps the default).
    #[must_use]
    pub fn restore(storage: Option<&dyn eframe::Storage>) -> (Self, Option<String>) {
        let (tree, why) = match storage.and_then(|s| s.get_string(Self::KEY)) {
            None => (default_tree(), None),
            Some(text) => match check_stored(&text) {
                Ok(tree) => (tree, None),
                Err(why) => (
                    default_tree(),
                    Some(format!(
                        "The stored window layout was not used ({why}): the default layout is shown"
                    )),
                ),
            },
        };
        (
            Self {
                tree,
                ..Self::default()
            },
            why,
        )
    }

    /// Keeps the arrangement in `storage`.
    pub fn save(&self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, Self::KEY, &self.tree);
    }

    /// Back to the default arrangement (*View → Reset layout*).
    pub fn reset(&mut self) {
        self.tree = default_tree();
        self.shown = None;
    }

    /// Whether presentation mode is on.
    #[must_use]
    pub fn presenting(&self) -> bool {
        self.presenting.is_some()
    }

    /// Enters presentation mode (every panel closes, `open` remembered) or leaves it (the
    /// panels open before it open again).
    pub fn toggle_presentation(&mut self, open: &mut Open) {
        if let Some(before) = self.presenting.take() {
            *open = before;
        } else {
            self.presenting = Some(*open);
            *open = Open::default();
        }
    }

    /// Shows the panes `open` says, hides the others (and containers left with nothing to
    /// show); a pane opened since the last call becomes the active tab of its group. At the
    /// first call the tabs stay as they were kept, but an open Lessons panel comes first (the
    /// window started on a lesson).
    pub fn sync(&mut self, open: Open) {
        let ids: Vec<(TileId, Pane)> = self
            .tree
            .tiles
            .iter()
            .filter_map(|(id, t)| match t {
                Tile::Pane(p) => Some((*id, *p)),
                Tile::Container(_) => None,
            })
            .collect();
        for &(id, pane) in &ids {
            self.tree.tiles.set_visible(id, open.get(pane));
        }
        if let Some(root) = self.tree.root() {
            container_visibility(&mut self.tree.tiles, root);
        }
        for &(id, pane) in &ids {
            let opened = match self.shown {
                Some(shown) => open.get(pane) && !shown.get(pane),
                None => pane == Pane::Lessons && open.get(pane),
            };
            if opened && pane != Pane::Image {
                self.tree.make_active(|tile, _| tile == id);
            }
        }
        self.shown = Some(open);
    }
}

/// Hides the containers under `id` with no visible pane under them; returns whether `id`
/// shows anything.
fn container_visibility(tiles: &mut Tiles<Pane>, id: TileId) -> bool {
    let children = match tiles.get(id) {
        Some(Tile::Container(c)) => c.children_vec(),
        Some(Tile::Pane(_)) => return tiles.is_visible(id),
        None => return false,
    };
    let mut any = false;
    for child in children {
        any |= container_visibility(tiles, child);
    }
    tiles.set_visible(id, any);
    any
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_arrangement_holds_every_pane_once_and_gives_the_image_at_least_60_percent() {
        let tree = default_tree();
        assert_eq!(super::super::layout_check::check(&tree), Ok(()));
        const { assert!(IMAGE_SHARE / (IMAGE_SHARE + PANELS_SHARE) >= 0.6) };
    }

    #[test]
    fn presentation_closes_every_panel_and_gives_them_back() {
        let mut layout = Layout::default();
        let before = Open::default()
            .with(Pane::Scene, true)
            .with(Pane::Lessons, true)
            .with(Pane::Texture, true);
        let mut open = before;
        layout.toggle_presentation(&mut open);
        assert!(layout.presenting());
        assert_eq!(open, Open::default());
        open.set(Pane::Inspector, true);
        layout.toggle_presentation(&mut open);
        assert!(!layout.presenting());
        assert_eq!(open, before);
    }

    #[test]
    fn closed_panes_and_their_empty_groups_are_hidden() {
        let mut layout = Layout::default();
        layout.sync(Open::default().with(Pane::Scene, true));
        let tiles = &layout.tree.tiles;
        for p in Pane::ALL {
            let id = tiles.find_pane(&p).expect("every pane");
            assert_eq!(
                tiles.is_visible(id),
                matches!(p, Pane::Image | Pane::Scene),
                "{p:?}"
            );
            let parent = tiles.parent_of(id).expect("a tab group");
            assert_eq!(
                tiles.is_visible(parent),
                matches!(p, Pane::Image | Pane::Scene | Pane::Lessons),
                "the group of {p:?}"
            );
        }
    }

    /// eframe's storage in memory.
    #[derive(Default)]
    struct Memory(std::collections::HashMap<String, String>);

    impl eframe::Storage for Memory {
        fn get_string(&self, key: &str) -> Option<String> {
            self.0.get(key).cloned()
        }
        fn set_string(&mut self, key: &str, value: String) {
            self.0.insert(key.to_owned(), value);
        }
        fn remove_string(&mut self, key: &str) {
            self.0.remove(key);
        }
        fn flush(&mut self) {}
    }

    #[test]
    fn an_arrangement_is_kept_and_a_broken_one_falls_back_to_the_default() {
        // The user's arrangement: the inspector moved out of its tabs, beside the image.
        let mut layout = Layout::default();
        let tiles = &mut layout.tree.tiles;
        let inspector = tiles.find_pane(&Pane::Inspector).expect("inspector");
        let side = tiles.parent_of(inspector).expect("side tabs");
        if let Some(Tile::Container(c)) = tiles.get_mut(side) {
            c.remove_child(inspector);
        }
        let root = layout.tree.root().expect("root");
        if let Some(Tile::Container(c)) = layout.tree.tiles.get_mut(root) {
            c.add_child(inspector);
        }
        let mut storage = Memory::default();
        layout.save(&mut storage);
        let (kept, why) = Layout::restore(Some(&storage));
        assert_eq!(why, None);
        let tiles = &kept.tree.tiles;
        let moved = tiles.find_pane(&Pane::Inspector).expect("inspector");
        assert_eq!(
            tiles.parent_of(moved),
            kept.tree.root(),
            "the arrangement is kept"
        );

        // Unreadable, or missing a pane: the default, the inspector a tab beside the texture
        // panel.
        let saved = storage.0[Layout::KEY].clone();
        for bad in [
            "not ron at all".to_owned(),
            saved.replace("Texture", "Image"),
        ] {
            let mut broken = Memory::default();
            eframe::Storage::set_string(&mut broken, Layout::KEY, bad.clone());
            let (restored, why) = Layout::restore(Some(&broken));
            assert!(why.is_some(), "{bad}");
            let tiles = &restored.tree.tiles;
            let inspector = tiles.find_pane(&Pane::Inspector).expect("inspector");
            let texture = tiles.find_pane(&Pane::Texture).expect("texture panel");
            assert_eq!(
                tiles.parent_of(inspector),
                tiles.parent_of(texture),
                "{bad}"
            );
        }
    }
}
