//! The one walk over every texture an object reads: its material's (the colour, then each
//! textured coefficient and colour), then its clip, bump, normal and displacement maps.

use super::super::material::{ParamRef, ScalarDesc};
use super::super::texture::TextureDesc;
use super::ObjectDesc;
use crate::field::FieldPath;

/// The walk, written once for shared and mutable borrows: `$textures` is the material's list
/// (`textures` or `textures_mut`), `$texture` the clip map's accessor (`texture` or
/// `texture_mut`), `$mut` the borrow.
macro_rules! walk {
    ($o:expr, $textures:ident, $texture:ident, $($mut:tt)?) => {{
        let o = $o;
        // A texture read through one channel, `(texture: ..., channel: Red)`, is one step
        // deeper in the preset than a bare texture: its path says `texture` as the file does.
        let channels: Vec<&'static str> = o
            .material
            .params()
            .into_iter()
            .filter(|(_, p)| matches!(p, ParamRef::Scalar(ScalarDesc::Channel(_))))
            .map(|(name, _)| name)
            .collect();
        let within = |path: FieldPath, channel: bool| if channel { path.then("texture") } else { path };
        let alpha_channel = matches!(o.alpha, Some(ScalarDesc::Channel(_)));
        let mut v: Vec<(FieldPath, & $($mut)? TextureDesc)> = o
            .material
            .$textures()
            .into_iter()
            .map(|(name, t)| {
                (within(FieldPath::field("material").then(name), channels.contains(&name)), t)
            })
            .collect();
        if let Some(a) = & $($mut)? o.alpha
            && let Some(t) = a.$texture()
        {
            v.push((within(FieldPath::field("alpha"), alpha_channel), t));
        }
        if let Some(b) = & $($mut)? o.bump {
            v.push((FieldPath::field("bump").then("height"), & $($mut)? b.height));
        }
        if let Some(n) = & $($mut)? o.normal {
            v.push((FieldPath::field("normal").then("map"), & $($mut)? n.map));
        }
        if let Some(d) = & $($mut)? o.displace {
            v.push((FieldPath::field("displace").then("height"), & $($mut)? d.height));
        }
        v
    }};
}

impl ObjectDesc {
    /// Every texture the object reads, with its path below the object (`material.cd`,
    /// `material.ks`, `alpha`, `bump.height`, `normal.map`, `displace.height`; one channel of a
    /// texture adds `.texture`, as in the preset: `alpha.texture`), in that order.
    #[must_use]
    pub fn textures(&self) -> Vec<(FieldPath, &TextureDesc)> {
        walk!(self, textures, texture,)
    }

    /// The textures of [`ObjectDesc::textures`], mutably.
    pub fn textures_mut(&mut self) -> Vec<(FieldPath, &mut TextureDesc)> {
        walk!(self, textures_mut, texture_mut, mut)
    }
}
