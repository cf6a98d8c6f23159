//! Material parameters that may vary over the surface: a coefficient ([`Scalar`]) or a colour
//! ([`Colour`]), each either a constant or a texture.
//!
//! A constant is stored as the plain number or colour and costs one predictable branch: no
//! texture is evaluated, no footprint is needed ([`Scalar::needs_differentials`] is false), so
//! a scene that textures nothing but `cd` renders as fast as before these existed.

use crate::math::Rgb;
use crate::texture::{Channel, Texture, TextureContext};

/// A coefficient of a material (`ka`, `kd`, `ks`, `exp`, `ls`, `kr`).
#[derive(Clone, Debug)]
pub enum Scalar {
    /// The same number everywhere.
    Const(f32),
    /// One channel of a texture (boxed: rare, and keeps the constant case small).
    Texture(Box<ScalarTexture>),
}

/// A texture read as one number.
#[derive(Clone, Debug)]
pub struct ScalarTexture {
    /// The texture, with its own mapping, filter and wrap.
    pub texture: Texture,
    /// Which number of its colour is read.
    pub channel: Channel,
}

impl ScalarTexture {
    /// The channel's value at a hit.
    #[must_use]
    #[inline(never)]
    pub fn eval(&self, ctx: &TextureContext) -> f32 {
        self.channel.of(self.texture.eval(ctx))
    }
}

impl Scalar {
    /// The value at a hit. Always inlined: a constant is then a load, and the texture read
    /// stays out of line ([`ScalarTexture::eval`]).
    #[must_use]
    #[inline(always)]
    pub fn eval(&self, ctx: &TextureContext) -> f32 {
        match self {
            Self::Const(v) => *v,
            Self::Texture(t) => t.eval(ctx),
        }
    }

    /// Whether evaluating needs the hit's footprint (a texture with a footprint filter).
    #[must_use]
    pub fn needs_differentials(&self) -> bool {
        match self {
            Self::Const(_) => false,
            Self::Texture(t) => t.texture.needs_differentials(),
        }
    }

    /// The texture read, if this is not a constant.
    #[must_use]
    pub fn texture(&self) -> Option<&Texture> {
        match self {
            Self::Const(_) => None,
            Self::Texture(t) => Some(&t.texture),
        }
    }
}

/// A colour of a material other than `cd` and `ce` (`cs`, `cr`).
#[derive(Clone, Debug)]
pub enum Colour {
    /// The same linear colour everywhere.
    Const(Rgb),
    /// A texture (boxed: rare, and keeps the constant case small).
    Texture(Box<Texture>),
}

impl Colour {
    /// The linear colour at a hit (always inlined: a constant is a load; the texture read
    /// stays out of line).
    #[must_use]
    #[inline(always)]
    pub fn eval(&self, ctx: &TextureContext) -> Rgb {
        match self {
            Self::Const(c) => *c,
            Self::Texture(t) => eval_colour_texture(t, ctx),
        }
    }

    /// Whether evaluating needs the hit's footprint.
    #[must_use]
    pub fn needs_differentials(&self) -> bool {
        match self {
            Self::Const(_) => false,
            Self::Texture(t) => t.needs_differentials(),
        }
    }

    /// The texture read, if this is not a constant.
    #[must_use]
    pub fn texture(&self) -> Option<&Texture> {
        match self {
            Self::Const(_) => None,
            Self::Texture(t) => Some(t),
        }
    }
}

/// A textured colour's value at a hit, kept out of line.
#[inline(never)]
fn eval_colour_texture(t: &Texture, ctx: &TextureContext) -> Rgb {
    t.eval(ctx)
}

/// A parameter's value at one hit, as the inspector shows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamValue {
    /// A coefficient.
    Scalar(f32),
    /// A linear colour.
    Colour(Rgb),
}

impl std::fmt::Display for ParamValue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Scalar(v) => write!(f, "{v:.4}"),
            Self::Colour(c) => write!(f, "({:.4}, {:.4}, {:.4})", c.0, c.1, c.2),
        }
    }
}
