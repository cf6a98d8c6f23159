//! Scenes: presets on disk ([`SceneDesc`]), asset loading, and the immutable runtime [`Scene`]
//! that the renderer traces.
//!
//! One file (or folder) per concept, each holding its description type, its kind enum, its
//! defaults, its validation and its build step: `preset` (the whole scene, its text, its PNG
//! chunk, loading and saving), `texture`, `material`, `object`, `camera`, `light`, render
//! `settings` and the `assets` cache; `trace` is the runtime scene.

mod assets;
mod camera;
mod kernel;
mod light;
mod mapping;
mod material;
mod non_finite;
mod object;
mod preset;
mod settings;
mod stand_in;
mod texture;
mod trace;
mod values;

pub use crate::field::{FieldPath, Refusal, Step, field_name};
pub use assets::{
    AssetCache, DISPLACED_KEPT, MAX_SCENE_DISPLACED_TRIANGLES, MAX_SCENE_TEXEL_BYTES, UV_GRID_SIZE,
};
pub use camera::{CameraDesc, ProjectionDesc, ProjectionKind};
pub use kernel::{Diffs, Rays, Traced};
pub use light::{AmbientDesc, LightDesc, LightKind};
pub use mapping::MappingDesc;
pub use material::{
    ChannelDesc, ColorDesc, MaterialDesc, MaterialKind, ParamMut, ParamRef, ScalarDesc,
};
pub use non_finite::{Counted, NonFinite, non_finite_fields};
pub use object::{
    BumpDesc, DEFAULT_SUBDIVIDE, DisplaceDesc, NormalMapDesc, ObjectDesc, ShapeDesc, ShapeKind,
    TransformDesc,
};
pub use preset::{
    LECTURE_ORDER, MAX_PNG_ANCILLARY_BYTES, MAX_PRESET_BYTES, PRESET_CHUNK, PRESET_VERSION,
    SceneDesc, asset_paths, build_scene, check_numbers, list_presets, load_preset, parse_preset,
    presets_in_lecture_order, read_png_preset, read_preset_or_png, rebase_assets,
    relative_asset_path, save_preset, save_render_png, save_render_png_checked, to_ron,
};
pub use settings::{
    AdaptiveDesc, DEFAULT_ADAPTIVE_THRESHOLD, DEFAULT_REFLECTION_DEPTH, MAX_REFLECTION_DEPTH,
    MAX_RENDER_BYTES, MAX_RESOLUTION, MAX_SPP, Overrides, RENDER_BYTES_PER_PIXEL, RenderDesc,
    RenderSettings, SimdMode, SnapshotDesc, apply_overrides,
};
pub use texture::{TextureDesc, TextureKind, check_checker};
pub use trace::{
    MAX_CLIP_LAYERS, Perturbation, SHADOW_OFFSET_RELATIVE, Scene, Surface, SurfaceHit,
    natural_mapping,
};

#[cfg(test)]
mod tests {
    use super::*;
    use strum::VariantArray;

    /// What a menu pick makes is of the kind picked.
    #[test]
    fn every_kind_defaults_to_a_desc_of_that_kind() {
        for &k in ShapeKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
        for &k in TextureKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
        for &k in MaterialKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
        for &k in LightKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
        for &k in ProjectionKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
    }

    /// A kind's defaults are what a preset that leaves every optional field out reads as.
    #[test]
    fn kind_defaults_match_the_preset_defaults() {
        let checker: TextureDesc = ron::from_str("Checker()").expect("checker");
        assert_eq!(checker, TextureKind::Checker.default_desc());
        let grid: TextureDesc = ron::from_str("UvGrid()").expect("uv grid");
        assert_eq!(grid, TextureKind::UvGrid.default_desc());
        let mesh: TextureDesc = ron::from_str("MeshMaterial()").expect("mesh material");
        assert_eq!(mesh, TextureKind::MeshMaterial.default_desc());
        let image: TextureDesc = ron::from_str(r#"Image(path: "")"#).expect("image");
        assert_eq!(image, TextureKind::Image.default_desc());
        let phong: MaterialDesc =
            ron::from_str("Phong(cd: Constant((0.7, 0.7, 0.7)))").expect("phong");
        assert_eq!(phong, MaterialKind::Phong.default_desc());
    }
}
