//! Stored window layouts that broke the window (issue 38 §1 and §3), shared by the headless
//! and the window tests: each used to abort every start (a stack overflow walking the tiles)
//! or open a window showing only its menu and status line.

// Each test crate uses a subset of these.
#![allow(dead_code)]

use egui_tiles::{Container, Tile, TileId, Tree};
use texplore::gui::{Pane, default_tree};

/// A stored arrangement, as eframe stores it.
pub fn ron_of(tree: &Tree<Pane>) -> String {
    ron::to_string(tree).expect("ron")
}

/// The container holding `pane`'s tab group.
fn group_of(tree: &Tree<Pane>, pane: Pane) -> TileId {
    let id = tree.tiles.find_pane(&pane).expect("pane");
    tree.tiles.parent_of(id).expect("its tab group")
}

fn add_child(tree: &mut Tree<Pane>, to: TileId, child: TileId) {
    match tree.tiles.get_mut(to) {
        Some(Tile::Container(c)) => c.add_child(child),
        _ => panic!("not a container"),
    }
}

fn set_share(tree: &mut Tree<Pane>, share: f32) {
    let root = tree.root().expect("root");
    let image = group_of(tree, Pane::Image);
    match tree.tiles.get_mut(root) {
        Some(Tile::Container(Container::Linear(l))) => l.shares.set_share(image, share),
        _ => panic!("the root is a row"),
    }
}

/// Every bad arrangement of the issue: what it is, the words the refusal must say, the
/// stored text.
pub fn bad_layouts() -> Vec<(&'static str, &'static str, String)> {
    let mut out = Vec::new();
    let mut t = default_tree();
    let root = t.root().expect("root");
    add_child(&mut t, root, root);
    out.push(("a container listing itself", "lists itself", ron_of(&t)));

    let mut t = default_tree();
    let column = t
        .tiles
        .parent_of(group_of(&t, Pane::Scene))
        .expect("the panels' column");
    add_child(&mut t, column, root);
    out.push((
        "a container listing the root, its parent",
        "already in it",
        ron_of(&t),
    ));

    let mut t = default_tree();
    let tabs = group_of(&t, Pane::Inspector);
    add_child(&mut t, tabs, column);
    out.push((
        "a tab group listing its parent",
        "already in it",
        ron_of(&t),
    ));

    let mut t = default_tree();
    let mut top = root;
    for _ in 0..40_000 {
        top = t.tiles.insert_vertical_tile(vec![top]);
    }
    let nested = Tree::new(t.id(), top, t.tiles);
    let text = ron_of(&nested);
    assert!(text.len() < 4 << 20, "under the memory file's bound");
    out.push(("40,000 nested one-child columns", "deeper than 32", text));

    for share in [f32::NAN, 0.0, f32::INFINITY, -1.0] {
        let mut t = default_tree();
        set_share(&mut t, share);
        let (name, words) = match share {
            s if s.is_nan() => ("a share of NaN", "the share NaN"),
            0.0 => ("a share of 0", "the share 0"),
            -1.0 => ("a share of -1", "the share -1"),
            _ => ("a share of inf", "the share inf"),
        };
        out.push((name, words, ron_of(&t)));
    }

    let plain = ron_of(&default_tree());
    for (field, value, name, words) in [
        ("width", "NaN", "a width of NaN", "its width is NaN"),
        ("width", "-1.0", "a width of -1", "its width is -1"),
        ("height", "NaN", "a height of NaN", "its height is NaN"),
        ("height", "-1.0", "a height of -1", "its height is -1"),
    ] {
        let from = format!("{field}:None");
        assert!(plain.contains(&from), "{plain}");
        let bad = plain.replace(&from, &format!("{field}:Some({value})"));
        out.push((name, words, bad));
    }

    let t = default_tree();
    out.push((
        "a root that does not exist",
        "its root, tile 999, does not exist",
        ron_of(&Tree::new(t.id(), TileId(999), t.tiles.clone())),
    ));
    let mut t = default_tree();
    let tabs = group_of(&t, Pane::Scene);
    add_child(&mut t, tabs, TileId(12_345));
    out.push((
        "a child that does not exist",
        "tile 12345, which does not exist",
        ron_of(&t),
    ));
    out
}
