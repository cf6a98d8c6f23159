//! The messages between the page and its render workers, as bytes (`postcard`): one
//! `ArrayBuffer` a message, transferred without a copy. Bulk data (files, film rows) travels as
//! byte strings, so a tile's film costs a copy, not a value-by-value walk.

use crate::render::Film;
use serde::{Deserialize, Serialize};

/// A file a worker mounts (in the page, files live in memory: `input::mount`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SentFile {
    /// The path every loader reads it by.
    pub path: String,
    /// Its bytes.
    #[serde(with = "serde_bytes")]
    pub bytes: Vec<u8>,
}

/// A run of tiles of one pass for a worker to render.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Chunk {
    /// The render it belongs to.
    pub job: u64,
    /// The scene it renders (built by an earlier [`ToWorker::Build`]).
    pub scene: u64,
    /// The pass (the sample index of every pixel).
    pub pass: u32,
    /// The first tile.
    pub first: u32,
    /// How many tiles.
    pub tiles: u32,
    /// An adaptive pass's mask over the chunk's rows (true: sample the pixel), none when every
    /// pixel is sampled.
    pub mask: Option<Vec<bool>>,
}

/// What the page asks of a worker.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum ToWorker {
    /// Mount these files (a scene's images and meshes), replacing what was at their paths.
    Files(Vec<SentFile>),
    /// Build scene `scene` from a preset's text (`ron`), read as if from `path`, with primary
    /// rays on the path `simd` names (`SimdMode`'s name).
    Build {
        /// The scene's number.
        scene: u64,
        /// The preset's path (its assets are relative to its folder).
        path: String,
        /// The preset's text.
        ron: String,
        /// `SimdMode`'s name.
        simd: String,
    },
    /// Drop scene `scene` (no render uses it any more).
    Forget {
        /// The scene's number.
        scene: u64,
    },
    /// Render these tiles.
    Render(Chunk),
    /// Drop the queued tiles of render `job` (an edit replaced it).
    Cancel {
        /// The render.
        job: u64,
    },
}

/// What a worker answers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum FromWorker {
    /// Scene `scene` is built (or why not); `memory` is the worker's memory in bytes after.
    Built {
        /// The scene's number.
        scene: u64,
        /// Why it did not build.
        error: Option<String>,
        /// The worker's memory (its WebAssembly memory's size), in bytes.
        memory: u64,
    },
    /// A chunk's samples: its rows of a film that held nothing before (see [`TileRows`]).
    Rendered {
        /// The chunk rendered (its mask left out).
        job: u64,
        /// The pass.
        pass: u32,
        /// The first tile.
        first: u32,
        /// How many tiles.
        tiles: u32,
        /// The samples.
        rows: TileRows,
        /// The time the chunk took in the worker, in microseconds.
        micros: u64,
        /// The worker's memory after it, in bytes.
        memory: u64,
    },
    /// A chunk the worker could not render (its scene was dropped or did not build).
    Skipped {
        /// The render.
        job: u64,
        /// The pass.
        pass: u32,
        /// The first tile.
        first: u32,
        /// How many tiles.
        tiles: u32,
    },
}

/// Film rows as bytes (little-endian): the sums `[r, g, b, weight]`, and for adaptive renders
/// the luminance statistics and edge keys (empty otherwise).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TileRows {
    /// Pixels in the rows.
    pub pixels: u32,
    /// `[f32; 4]` per pixel.
    #[serde(with = "serde_bytes")]
    pub sums: Vec<u8>,
    /// `[f32; 2]` per pixel, or nothing.
    #[serde(with = "serde_bytes")]
    pub stats: Vec<u8>,
    /// `u32` per pixel, or nothing.
    #[serde(with = "serde_bytes")]
    pub keys: Vec<u8>,
}

impl TileRows {
    /// Pixels `range` of `film`, with the statistics and keys when `stats` is set.
    #[must_use]
    pub fn read(film: &Film, range: std::ops::Range<usize>, stats: bool) -> Self {
        let sums = film.pixels()[range.clone()]
            .iter()
            .flat_map(|p| p.iter().flat_map(|v| v.to_le_bytes()))
            .collect();
        let (st, keys) = if stats {
            (
                film.stats()[range.clone()]
                    .iter()
                    .flat_map(|p| p.iter().flat_map(|v| v.to_le_bytes()))
                    .collect(),
                film.keys()[range.clone()]
                    .iter()
                    .flat_map(|k| k.to_le_bytes())
                    .collect(),
            )
        } else {
            (Vec::new(), Vec::new())
        };
        Self {
            pixels: u32::try_from(range.len()).unwrap_or(u32::MAX),
            sums,
            stats: st,
            keys,
        }
    }

    /// Whether the byte strings hold `pixels` pixels each (a message from a worker of another
    /// build would not).
    #[must_use]
    pub fn is_whole(&self) -> bool {
        let n = self.pixels as usize;
        self.sums.len() == n * 16
            && (self.stats.is_empty() && self.keys.is_empty()
                || self.stats.len() == n * 8 && self.keys.len() == n * 4)
    }

    /// Adds these samples to `film`'s pixels from `start`, as the renderer would have added them
    /// there: where a pixel took a sample, its sums and statistics grow by the sample's (a sum
    /// that held nothing before is the sample itself, so the film is the same to the bit) and
    /// a pixel's first sample sets its edge key.
    pub fn add_to(&self, film: &mut Film, start: usize) {
        let (sums, stats, keys) = film.buffers_mut();
        let n = (self.pixels as usize).min(sums.len().saturating_sub(start));
        let with_stats = !self.stats.is_empty();
        for i in 0..n {
            let w = f32s::<4>(&self.sums, i);
            if w[3] == 0.0 {
                continue;
            }
            let px = &mut sums[start + i];
            if with_stats {
                if px[3] == 0.0 {
                    keys[start + i] = u32::from_le_bytes(bytes4(&self.keys, i * 4));
                }
                let s = f32s::<2>(&self.stats, i);
                stats[start + i][0] += s[0];
                stats[start + i][1] += s[1];
            }
            for (p, v) in px.iter_mut().zip(w) {
                *p += v;
            }
        }
    }
}

fn bytes4(b: &[u8], at: usize) -> [u8; 4] {
    [b[at], b[at + 1], b[at + 2], b[at + 3]]
}

/// Pixel `i`'s `N` floats.
fn f32s<const N: usize>(b: &[u8], i: usize) -> [f32; N] {
    std::array::from_fn(|k| f32::from_le_bytes(bytes4(b, (i * N + k) * 4)))
}

/// `message` as bytes.
#[must_use]
pub fn encode<T: Serialize>(message: &T) -> Vec<u8> {
    // Serialising plain data into a growing vector cannot fail.
    postcard::to_allocvec(message).unwrap_or_default()
}

/// The message in `bytes`.
///
/// # Errors
/// The bytes are not such a message (postcard's reason).
pub fn decode<'a, T: Deserialize<'a>>(bytes: &'a [u8]) -> Result<T, String> {
    postcard::from_bytes(bytes).map_err(|e| format!("a message the page cannot read: {e}"))
}
