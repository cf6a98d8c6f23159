//! A texture written as formulas over (u, v) and the local hit point: one grey expression, or
//! one per channel (linear RGB). Point-sampled (it has no texels to filter); where a channel
//! is NaN or infinite the pixel is [`NON_FINITE_MARK`] and counted.

use super::TextureContext;
use crate::mapping::formula::{Expr, FormulaError, NON_FINITE_MARK, TEXTURE_VARS};
use crate::mapping::{AnyMapping, TexCoord, UvAffine};
use crate::math::{Rgb, Vec2};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// The compiled colour formulas and their count of non-finite results.
#[derive(Debug)]
pub struct FormulaColour {
    /// One formula (grey) or three (red, green, blue).
    exprs: Vec<Expr>,
    non_finite: AtomicU64,
}

impl FormulaColour {
    /// One grey formula over u, v, x, y, z.
    ///
    /// # Errors
    /// Its mistake, named `grey`.
    pub fn grey(grey: &str) -> Result<Self, FormulaError> {
        Ok(Self::of(vec![Expr::compile("grey", grey, &TEXTURE_VARS)?]))
    }

    /// One formula per channel.
    ///
    /// # Errors
    /// The first mistake, named `r`, `g` or `b`.
    pub fn rgb(r: &str, g: &str, b: &str) -> Result<Self, FormulaError> {
        Ok(Self::of(vec![
            Expr::compile("r", r, &TEXTURE_VARS)?,
            Expr::compile("g", g, &TEXTURE_VARS)?,
            Expr::compile("b", b, &TEXTURE_VARS)?,
        ]))
    }

    fn of(exprs: Vec<Expr>) -> Self {
        Self {
            exprs,
            non_finite: AtomicU64::new(0),
        }
    }

    /// The formulas (one for grey, else red, green, blue).
    #[must_use]
    pub fn exprs(&self) -> &[Expr] {
        &self.exprs
    }

    /// How many evaluations gave NaN or an infinity.
    #[must_use]
    pub fn non_finite_count(&self) -> u64 {
        self.non_finite.load(Ordering::Relaxed)
    }

    /// The colour at the inputs (u, v, x, y, z); negative values are 0 (a colour is light).
    /// `None` where a channel is not finite (counted).
    #[must_use]
    pub fn eval(&self, inputs: &[f64; 5]) -> Option<Rgb> {
        let mut c = [0.0f32; 3];
        for (i, e) in self.exprs.iter().enumerate() {
            let x = e.eval(inputs);
            if !x.is_finite() {
                self.non_finite.fetch_add(1, Ordering::Relaxed);
                return None;
            }
            c[i] = (x as f32).max(0.0);
        }
        if self.exprs.len() == 1 {
            c = [c[0]; 3];
        }
        Some(Rgb(c[0], c[1], c[2]))
    }
}

/// A formula texture: a mapping, then the colour formulas at (u, v).
#[derive(Clone, Debug)]
pub struct FormulaTexture {
    /// How hit points become (u, v).
    pub mapping: AnyMapping,
    /// The colour formulas, shared.
    pub colour: Arc<FormulaColour>,
    /// The (u, v) transform after the mapping; `None` for none.
    pub transform: Option<UvAffine>,
}

impl FormulaTexture {
    /// Texture coordinates of a hit: the mapping's, then the (u, v) transform if any.
    #[must_use]
    pub fn tex_coord(&self, ctx: &TextureContext) -> TexCoord {
        ctx.transformed_tex_coord(&self.mapping, self.transform.as_ref())
    }

    /// The colour at a hit.
    #[must_use]
    pub fn eval(&self, ctx: &TextureContext) -> Rgb {
        let tc = self.tex_coord(ctx);
        let p = ctx.p.as_dvec3();
        self.at(tc.uv, [p.x, p.y, p.z])
    }

    /// The colour at (u, v) of the hit point `p`; the mark where not finite.
    #[must_use]
    pub fn at(&self, uv: Vec2, p: [f64; 3]) -> Rgb {
        if !uv.is_finite() {
            return mark();
        }
        let inputs = [f64::from(uv.x), f64::from(uv.y), p[0], p[1], p[2]];
        self.colour.eval(&inputs).unwrap_or_else(mark)
    }
}

/// [`NON_FINITE_MARK`] as a colour.
#[must_use]
pub fn mark() -> Rgb {
    Rgb(NON_FINITE_MARK[0], NON_FINITE_MARK[1], NON_FINITE_MARK[2])
}
