//! The stored arrangement (`texplore-layout` in eframe's `app.ron`, or the page's local
//! storage) checked before `egui_tiles` walks it.
//!
//! egui_tiles trusts the tree it is given and walks it recursively every frame: a container
//! listing itself, its parent or the root recursed until the stack overflowed, and so did
//! 40,000 nested one-child columns (3 MB, under the memory file's 4 MiB bound), at every start;
//! shares of NaN, 0 or infinity, an exact width or height of NaN or -1 and a root that does
//! not exist left the window blank but for its menu and status line. So before use the tree
//! must have a root that exists, list each tile once (no cycle, no tile in two places), list
//! only tiles that exist, nest at most [`MAX_DEPTH`] deep with at most [`MAX_TILES`] tiles,
//! hold every panel exactly once, and have finite positive shares and sizes. Otherwise the
//! window takes the default arrangement and says why.

use super::layout::Pane;
use egui_tiles::{Container, GridLayout, Tile, TileId, Tree};
use std::collections::HashSet;

/// The deepest nesting of containers a stored arrangement may have (the default has 3; five
/// panels dragged anywhere need far fewer than this).
pub const MAX_DEPTH: usize = 32;

/// The most tiles a stored arrangement may have (the default has 11).
pub const MAX_TILES: usize = 1024;

/// The largest share a container may give a child (shares are relative: 1e6 to 1 is already
/// far past anything a pointer can drag).
const MAX_SHARE: f32 = 1e6;

/// The stored arrangement `text` (RON), checked; or what is wrong with it, in words.
///
/// # Errors
/// Not an arrangement, or one of the faults the module lists.
pub fn check_stored(text: &str) -> Result<Tree<Pane>, String> {
    let mut tree: Tree<Pane> =
        ron::from_str(text).map_err(|e| format!("not an arrangement this version reads: {e}"))?;
    check_sizes(text)?;
    check(&tree)?;
    // Never set by texplore; whatever was stored, the tree fills the window.
    tree.set_width(f32::INFINITY);
    tree.set_height(f32::INFINITY);
    tree.tiles.recompute_next_tile_id();
    Ok(tree)
}

/// The tree's exact size, which egui_tiles keeps private: absent (null: the whole window), or
/// finite and positive.
fn check_sizes(text: &str) -> Result<(), String> {
    #[derive(serde::Deserialize)]
    struct Sizes {
        #[serde(default)]
        width: Option<f32>,
        #[serde(default)]
        height: Option<f32>,
    }
    let sizes: Sizes = ron::from_str(text).map_err(|e| format!("unreadable sizes: {e}"))?;
    for (name, size) in [("width", sizes.width), ("height", sizes.height)] {
        if let Some(s) = size
            && !(s.is_finite() && s > 0.0)
        {
            return Err(format!("its {name} is {s}"));
        }
    }
    Ok(())
}

/// What is wrong with the tree's structure, shares and panels, if anything. Walks the tree with
/// a stack of its own (no recursion), visiting each tile at most once.
///
/// # Errors
/// The first fault found, in words.
pub fn check(tree: &Tree<Pane>) -> Result<(), String> {
    let root = tree.root().ok_or("it has no root tile")?;
    let mut seen: HashSet<TileId> = HashSet::from([root]);
    let mut stack = vec![(root, 1)];
    let mut panes = [0usize; Pane::ALL.len()];
    while let Some((id, depth)) = stack.pop() {
        if depth > MAX_DEPTH {
            return Err(format!("its containers nest deeper than {MAX_DEPTH}"));
        }
        let tile = tree.tiles.get(id).ok_or_else(|| {
            if id == root {
                format!("its root, tile {}, does not exist", id.0)
            } else {
                format!("it lists tile {}, which does not exist", id.0)
            }
        })?;
        let container = match tile {
            Tile::Pane(p) => {
                panes[*p as usize] += 1;
                continue;
            }
            Tile::Container(c) => c,
        };
        check_shares(container, id)?;
        for &child in container.children() {
            if child == id {
                return Err(format!("container {} lists itself", id.0));
            }
            if !seen.insert(child) {
                return Err(format!(
                    "container {} lists tile {}, which is already in it (a cycle, or one tile in two places)",
                    id.0, child.0
                ));
            }
            if seen.len() > MAX_TILES {
                return Err(format!("it has more than {MAX_TILES} tiles"));
            }
            stack.push((child, depth + 1));
        }
    }
    for (pane, n) in Pane::ALL.iter().zip(panes) {
        if n != 1 {
            return Err(format!(
                "it holds the {} panel {n} times (once is right)",
                pane.title()
            ));
        }
    }
    Ok(())
}

/// Each share finite, positive and at most [`MAX_SHARE`]; a grid's column count sane.
fn check_shares(c: &Container, id: TileId) -> Result<(), String> {
    let bad = |s: f32| !(s.is_finite() && s > 0.0 && s <= MAX_SHARE);
    let share = |s: f32| {
        Err(format!(
            "container {} gives a child the share {s} (finite and positive, at most {MAX_SHARE})",
            id.0
        ))
    };
    match c {
        Container::Linear(l) => {
            if let Some((_, &s)) = l.shares.iter().find(|(_, s)| bad(**s)) {
                return share(s);
            }
        }
        Container::Grid(g) => {
            if let Some(&s) = g.col_shares.iter().chain(&g.row_shares).find(|s| bad(**s)) {
                return share(s);
            }
            if let GridLayout::Columns(n) = g.layout
                && !(1..=MAX_TILES).contains(&n)
            {
                return Err(format!("grid {} has {n} columns", id.0));
            }
        }
        Container::Tabs(_) => {}
    }
    Ok(())
}
