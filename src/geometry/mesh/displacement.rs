//! How a displaced mesh was made, for the inspector: kept with the mesh, so a mesh needs
//! nothing of the displacement code.

/// How a mesh was displaced, for the inspector.
#[derive(Clone, Debug, PartialEq)]
pub struct Displacement {
    /// The height texture in a few words (an image's file name).
    pub height: String,
    /// How far a height of 1 moved the surface, in the mesh's units.
    pub scale: f32,
    /// Subdivision levels.
    pub levels: u32,
    /// Triangles in the file, before subdivision.
    pub file_triangles: usize,
    /// Triangles after subdivision.
    pub triangles: usize,
    /// Vertices where the height texture's formula gave NaN or an infinity (read there as
    /// magenta's value, as every texture reads it).
    pub non_finite: usize,
}

impl Displacement {
    /// In short lines (the inspector's panel is narrow): the height texture and scale, the
    /// levels, the triangles.
    #[must_use]
    pub fn lines(&self) -> Vec<String> {
        vec![
            format!("displaced at load by {},", self.height),
            format!(
                "scale {}, {} subdivision level{}:",
                self.scale,
                self.levels,
                if self.levels == 1 { "" } else { "s" }
            ),
            format!(
                "{} triangles from the file's {}",
                self.triangles, self.file_triangles
            ),
        ]
        .into_iter()
        .chain((self.non_finite > 0).then(|| {
            format!(
                "at {} vertices the height's formula was NaN or infinite",
                self.non_finite
            )
        }))
        .collect()
    }
}

impl std::fmt::Display for Displacement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.lines().join(" "))
    }
}
