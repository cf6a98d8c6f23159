//! Formulas a student writes: a mapping `u = ..., v = ...` over the local hit point, or a
//! texture's colour over (u, v). Parsed and evaluated by exmex (`ops.rs` lists the operators);
//! exmex's evaluation over symbols is recorded on a tape once when the scene is built, and
//! compiled into a flat program (`program.rs`), never per ray.
//!
//! A formula is at most [`MAX_FORMULA_BYTES`] long and nested at most [`MAX_NESTING`] deep;
//! its mistakes come back as a [`FormulaError`] with the column (`check.rs` scans the tokens
//! before exmex parses). A point where it gives NaN or an infinity is counted
//! ([`FormulaMapping::non_finite_count`]) and the texture marks the pixel
//! ([`NON_FINITE_MARK`]). Nothing here recurses on the formula's shape (exmex's parser and
//! evaluator are flat; the tape is walked in order), so every formula up to the limit compiles
//! on a small stack.
//!
//! The mapping's derivatives, which the ray differentials need (mip maps, EWA, the footprint
//! filter), are symbolic, built along the tape (`derive.rs`), where every function has one;
//! central finite differences otherwise ([`DerivativeKind`]); a difference that jumps by a
//! whole number is the seam of `fract` or `floor`, which a repeating texture reads as
//! continuous, so the jump is taken out.

mod check;
pub mod compare;
mod derive;
mod ops;
mod program;

pub use check::MAX_NESTING;
pub use ops::{BINARY, CONSTANTS, FormulaOps, UNARY};

use super::TexCoord;
use crate::math::{Vec2, Vec3A};
use check::{Name, Token};
use exmex::prelude::*;
use glam::{DVec2, DVec3};
use ops::{Sym, SymOps, Tape};
use program::Program;
use std::sync::atomic::{AtomicU64, Ordering};

/// The longest formula, in bytes.
pub const MAX_FORMULA_BYTES: usize = 4096;

/// The inputs of a mapping formula, in the order [`FormulaMapping`] takes them.
pub const MAPPING_VARS: [&str; 5] = ["x", "y", "z", "mesh_u", "mesh_v"];

/// The inputs of a texture formula, in the order [`Expr::eval`] takes them there.
pub const TEXTURE_VARS: [&str; 5] = ["u", "v", "x", "y", "z"];

/// The colour a texture gives where its formula is NaN or infinite: magenta, which no lecture
/// texture holds, so the student sees where.
pub const NON_FINITE_MARK: [f32; 3] = [1.0, 0.0, 1.0];

/// A formula that did not compile: which field, where and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FormulaError {
    /// The formula's name (`u`, `v`, `r`, `grey`...).
    pub field: String,
    /// The formula as written (empty when it was too long to keep).
    pub text: String,
    /// The column of the mistake (1-based, in characters), when known.
    pub column: Option<usize>,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for FormulaError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.column {
            Some(c) => write!(f, "{}: column {c}: {}", self.field, self.message),
            None => write!(f, "{}: {}", self.field, self.message),
        }
    }
}

impl std::error::Error for FormulaError {}

impl FormulaError {
    /// The formula and a line with `^` under the mistake, for a terminal or a text field
    /// (control characters shown as U+FFFD).
    #[must_use]
    pub fn pointer(&self) -> Option<String> {
        let c = self.column?;
        if self.text.is_empty() {
            return None;
        }
        // A control character shows as U+FFFD (one character, so the `^` stays under it).
        let shown: String = self
            .text
            .chars()
            .map(|c| if c.is_control() { '\u{fffd}' } else { c })
            .collect();
        Some(format!("{shown}\n{}^", " ".repeat(c - 1)))
    }
}

/// One compiled formula over a fixed list of inputs.
#[derive(Clone)]
pub struct Expr {
    text: String,
    flat: FlatEx<f64, FormulaOps>,
    /// For each of exmex's variables (alphabetical), the index of the input it reads.
    slots: Vec<usize>,
    /// What the renderer runs: exmex's evaluation, compiled.
    program: Program,
    /// exmex's evaluation as recorded (the derivatives are built from it), and its value.
    recorded: std::sync::Arc<(Tape, Sym)>,
    tokens: Vec<Token>,
}

impl std::fmt::Debug for Expr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Expr({:?})", self.text)
    }
}

impl PartialEq for Expr {
    fn eq(&self, other: &Self) -> bool {
        self.text == other.text
    }
}

impl Expr {
    /// Compiles `text`, a formula named `field` over the inputs `vars`.
    ///
    /// # Errors
    /// Too long, a mistake the token scan finds (with its column), or one exmex finds.
    pub fn compile(field: &str, text: &str, vars: &[&str]) -> Result<Self, FormulaError> {
        let error = |column, message| FormulaError {
            field: field.to_owned(),
            text: text.to_owned(),
            column,
            message,
        };
        if text.len() > MAX_FORMULA_BYTES {
            return Err(FormulaError {
                text: String::new(),
                ..error(
                    None,
                    format!(
                        "{} bytes long; a formula may have at most {MAX_FORMULA_BYTES}",
                        text.len()
                    ),
                )
            });
        }
        let tokens = check::scan(text, vars).map_err(|(c, m)| error(Some(c), m))?;
        let flat = FlatEx::<f64, FormulaOps>::parse(text)
            .map_err(|e| error(None, format!("exmex cannot parse it: {}", e.msg())))?;
        Self::from_flat(text, flat, tokens, vars).map_err(|m| error(None, m))
    }

    fn from_flat(
        text: &str,
        flat: FlatEx<f64, FormulaOps>,
        tokens: Vec<Token>,
        vars: &[&str],
    ) -> Result<Self, String> {
        let slots = slots_of(flat.var_names(), vars)?;
        // exmex evaluating the formula over symbols records the tree it evaluates.
        let symbolic = FlatEx::<Sym, SymOps>::parse(text)
            .map_err(|e| format!("exmex cannot parse it: {}", e.msg()))?;
        let sym_slots = slots_of(symbolic.var_names(), vars)?;
        let inputs: Vec<Sym> = (0..sym_slots.len()).map(Sym::Var).collect();
        let (root, tape) = ops::record(|| symbolic.eval(&inputs));
        let root = root.map_err(|e| format!("exmex cannot evaluate it: {}", e.msg()))?;
        let program = Program::compile(&tape, root, &sym_slots);
        Ok(Self {
            text: text.to_owned(),
            flat,
            slots,
            program,
            recorded: std::sync::Arc::new((tape, root)),
            tokens,
        })
    }

    /// The formula as written.
    #[must_use]
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The value at `inputs` (in the order of the `vars` it was compiled with); NaN where exmex
    /// fails (it does not, once compiled).
    #[must_use]
    #[inline]
    pub fn eval(&self, inputs: &[f64]) -> f64 {
        self.program.eval(inputs)
    }

    /// The value as exmex itself evaluates it (the program's reference).
    #[must_use]
    pub fn eval_exmex(&self, inputs: &[f64]) -> f64 {
        let mut values = [0.0; MAPPING_VARS.len()];
        for (value, &slot) in values.iter_mut().zip(&self.slots) {
            *value = inputs.get(slot).copied().unwrap_or(f64::NAN);
        }
        self.flat
            .eval(&values[..self.slots.len()])
            .unwrap_or(f64::NAN)
    }

    /// Whether the formula reads input `slot`.
    #[must_use]
    pub fn reads(&self, slot: usize) -> bool {
        self.slots.contains(&slot)
    }

    /// The formula with each variable replaced by its value at `inputs`, as the worked
    /// formulas print numbers.
    #[must_use]
    pub fn substituted(&self, inputs: &[f64]) -> String {
        let mut out = String::with_capacity(self.text.len() + 16);
        let mut at = 0;
        for t in &self.tokens {
            if let Some(Name::Var(slot)) = t.name {
                out.push_str(&self.text[at..t.span.0]);
                let value = inputs.get(slot).copied().unwrap_or(f64::NAN);
                let n = super::explain_number(value);
                if value < 0.0 {
                    out.push('(');
                    out.push_str(&n);
                    out.push(')');
                } else {
                    out.push_str(&n);
                }
                at = t.span.1;
            }
        }
        out.push_str(&self.text[at..]);
        out
    }

    /// The symbolic partial derivative with respect to input `slot`, compiled: `None` when the
    /// formula does not read it (the derivative is zero). NaN through a function with no
    /// symbolic derivative ([`Expr::plain_functions`]).
    fn partial(&self, slot: usize) -> Option<Program> {
        let index = self.slots.iter().position(|&s| s == slot)?;
        let (tape, root) = &*self.recorded;
        let mut tape = tape.clone();
        let d = derive::derivative(&mut tape, *root, index);
        Some(Program::compile(&tape, d, &self.slots))
    }

    /// The functions the formula applies to an input with no symbolic derivative (`atan2`,
    /// `fract`...), sorted.
    fn plain_functions(&self) -> Vec<&'static str> {
        derive::blocked(&self.recorded.0)
    }

    /// How many instructions the compiled formula runs.
    #[must_use]
    pub fn instructions(&self) -> usize {
        self.program.len()
    }
}

/// How a formula mapping's derivatives are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DerivativeKind {
    /// exmex's symbolic partial derivatives: exact.
    Symbolic,
    /// Central finite differences: the formula uses a function exmex cannot differentiate.
    FiniteDifferences,
}

/// d/d(input) of u and of v, `None` for an input the formula does not read.
type Gradients = Box<[[Option<Program>; 5]; 2]>;

#[derive(Debug)]
enum Derivatives {
    /// Built by [`FormulaMapping::new`], or the first time they are needed.
    Symbolic(std::sync::OnceLock<Gradients>),
    /// Why not symbolic.
    FiniteDifferences(String),
}

/// A mapping written as two formulas over x, y, z (the local hit point), mesh_u and mesh_v
/// (the shape's own (u, v): a mesh's vertex coordinates, or the shape's natural mapping).
#[derive(Debug)]
pub struct FormulaMapping {
    u: Expr,
    v: Expr,
    derivatives: Derivatives,
    non_finite: AtomicU64,
}

impl PartialEq for FormulaMapping {
    fn eq(&self, other: &Self) -> bool {
        self.u == other.u && self.v == other.v
    }
}

impl FormulaMapping {
    /// Compiles the two formulas and their derivatives: what a scene's build does, off the
    /// window's UI thread.
    ///
    /// # Errors
    /// The first formula's mistake, naming `u` or `v`.
    pub fn new(u: &str, v: &str) -> Result<Self, FormulaError> {
        let f = Self::checked(u, v)?;
        if let Derivatives::Symbolic(g) = &f.derivatives {
            g.get_or_init(|| f.build_gradients());
        }
        Ok(f)
    }

    /// Compiles the two formulas and decides how their derivatives will be had, without
    /// building them (the first use does): what a check of the formulas needs (the Scene
    /// panel's note, an exercise's Check), cheap enough for the UI thread.
    ///
    /// # Errors
    /// The first formula's mistake, naming `u` or `v`.
    pub fn checked(u: &str, v: &str) -> Result<Self, FormulaError> {
        let u = Expr::compile("u", u, &MAPPING_VARS)?;
        let v = Expr::compile("v", v, &MAPPING_VARS)?;
        let mut plain = u.plain_functions();
        plain.extend(v.plain_functions());
        plain.sort_unstable();
        plain.dedup();
        let derivatives = if plain.is_empty() {
            Derivatives::Symbolic(std::sync::OnceLock::new())
        } else {
            Derivatives::FiniteDifferences(format!(
                "no symbolic derivative of {}",
                plain.join(", ")
            ))
        };
        Ok(Self {
            u,
            v,
            derivatives,
            non_finite: AtomicU64::new(0),
        })
    }

    /// Both formulas' symbolic derivatives along each input.
    fn build_gradients(&self) -> Gradients {
        let mut out: Gradients = Box::default();
        for (row, e) in out.iter_mut().zip([&self.u, &self.v]) {
            for (k, slot) in row.iter_mut().enumerate() {
                *slot = e.partial(k);
            }
        }
        out
    }

    /// The u formula.
    #[must_use]
    pub const fn u(&self) -> &Expr {
        &self.u
    }

    /// The v formula.
    #[must_use]
    pub const fn v(&self) -> &Expr {
        &self.v
    }

    /// How the derivatives are computed.
    #[must_use]
    pub const fn derivative_kind(&self) -> DerivativeKind {
        match self.derivatives {
            Derivatives::Symbolic(_) => DerivativeKind::Symbolic,
            Derivatives::FiniteDifferences(_) => DerivativeKind::FiniteDifferences,
        }
    }

    /// The derivatives in a sentence, for the inspector and `texplore map`.
    #[must_use]
    pub fn derivative_note(&self) -> String {
        match &self.derivatives {
            Derivatives::Symbolic(_) => {
                "derivatives: symbolic (both formulas differentiated exactly)".into()
            }
            Derivatives::FiniteDifferences(why) => {
                format!("derivatives: central finite differences ({why})")
            }
        }
    }

    /// Whether either formula reads mesh_u or mesh_v.
    #[must_use]
    pub fn reads_mesh(&self) -> bool {
        [3, 4].iter().any(|&s| self.u.reads(s) || self.v.reads(s))
    }

    /// How many evaluations gave NaN or an infinity since the mapping was compiled.
    #[must_use]
    pub fn non_finite_count(&self) -> u64 {
        self.non_finite.load(Ordering::Relaxed)
    }

    /// (u, v) at the inputs (x, y, z, mesh_u, mesh_v), in f64, not counted.
    #[must_use]
    #[inline]
    pub fn eval(&self, inputs: &[f64; 5]) -> DVec2 {
        DVec2::new(self.u.eval(inputs), self.v.eval(inputs))
    }

    /// The gradients of u and v with respect to the five inputs at `inputs`: symbolic, or
    /// central differences along each input.
    #[must_use]
    pub fn gradients(&self, inputs: &[f64; 5]) -> [[f64; 5]; 2] {
        let mut out = [[0.0; 5]; 2];
        for k in 0..5 {
            let mut d = [0.0; 5];
            d[k] = 1.0;
            let (du, dv) = self.directional(inputs, &d);
            out[0][k] = du;
            out[1][k] = dv;
        }
        out
    }

    /// The change of (u, v) along the input offset `d` (a pixel's step in x, y, z, mesh_u,
    /// mesh_v).
    fn directional(&self, inputs: &[f64; 5], d: &[f64; 5]) -> (f64, f64) {
        match &self.derivatives {
            Derivatives::Symbolic(g) => {
                let g = g.get_or_init(|| self.build_gradients());
                let dot = |g: &[Option<Program>; 5]| {
                    g.iter()
                        .zip(d)
                        .filter(|(_, dk)| **dk != 0.0)
                        .map(|(gk, dk)| gk.as_ref().map_or(0.0, |e| e.eval(inputs) * dk))
                        .sum::<f64>()
                };
                (dot(&g[0]), dot(&g[1]))
            }
            Derivatives::FiniteDifferences(_) => {
                let len = d.iter().map(|x| x * x).sum::<f64>().sqrt();
                if len == 0.0 || !len.is_finite() {
                    return (0.0, 0.0);
                }
                // An absolute step of 1e-5 (points are of size 1): rounding stays near 1e-11.
                let h = (FD_STEP / len).min(0.5);
                let mut plus = *inputs;
                let mut minus = *inputs;
                for k in 0..5 {
                    plus[k] += h * d[k];
                    minus[k] -= h * d[k];
                }
                let (a, b) = (self.eval(&plus), self.eval(&minus));
                let diff = |x: f64, y: f64| {
                    let t = x - y;
                    (t - t.round()) / (2.0 * h)
                };
                (diff(a.x, b.x), diff(a.y, b.y))
            }
        }
    }

    /// (u, v) at the object-space point `p` with the shape's own (u, v) `mesh`, without
    /// derivatives; NaN (and counted) where not finite.
    #[must_use]
    #[inline]
    pub fn map_uv(&self, p: Vec3A, mesh: Vec2) -> Vec2 {
        let inputs = [
            f64::from(p.x),
            f64::from(p.y),
            f64::from(p.z),
            f64::from(mesh.x),
            f64::from(mesh.y),
        ];
        let uv = self.eval(&inputs);
        if uv.is_finite() {
            uv.as_vec2()
        } else {
            self.non_finite.fetch_add(1, Ordering::Relaxed);
            Vec2::NAN
        }
    }

    /// Texture coordinates with their screen-space derivatives. `mesh` is the shape's own
    /// (u, v) with its change to the pixel on the right and below.
    #[must_use]
    pub fn tex_coord(
        &self,
        p: Vec3A,
        dpdx: Vec3A,
        dpdy: Vec3A,
        mesh: (Vec2, Vec2, Vec2),
    ) -> TexCoord {
        let inputs = [
            f64::from(p.x),
            f64::from(p.y),
            f64::from(p.z),
            f64::from(mesh.0.x),
            f64::from(mesh.0.y),
        ];
        let uv = self.eval(&inputs);
        if !uv.is_finite() {
            self.non_finite.fetch_add(1, Ordering::Relaxed);
            return TexCoord {
                uv: Vec2::NAN,
                duvdx: Vec2::ZERO,
                duvdy: Vec2::ZERO,
            };
        }
        let step = |dp: Vec3A, dm: Vec2| {
            [
                f64::from(dp.x),
                f64::from(dp.y),
                f64::from(dp.z),
                f64::from(dm.x),
                f64::from(dm.y),
            ]
        };
        let (dx, dy) = if dpdx == Vec3A::ZERO && dpdy == Vec3A::ZERO {
            ((0.0, 0.0), (0.0, 0.0))
        } else {
            (
                self.directional(&inputs, &step(dpdx, mesh.1)),
                self.directional(&inputs, &step(dpdy, mesh.2)),
            )
        };
        TexCoord {
            uv: uv.as_vec2(),
            duvdx: Vec2::new(dx.0 as f32, dx.1 as f32),
            duvdy: Vec2::new(dy.0 as f32, dy.1 as f32),
        }
        .bounded()
    }

    /// The worked formulas at `inputs`: each with the numbers substituted and its value.
    #[must_use]
    pub fn explain(&self, inputs: &[f64; 5]) -> (Vec<String>, DVec2) {
        let uv = self.eval(inputs);
        let n = super::explain_number;
        let mut lines = vec![
            format!(
                "u = {} = {} = {}",
                self.u.text(),
                self.u.substituted(inputs),
                n(uv.x)
            ),
            format!(
                "v = {} = {} = {}",
                self.v.text(),
                self.v.substituted(inputs),
                n(uv.y)
            ),
        ];
        if !uv.is_finite() {
            lines.push(
                "(u, v) is not a finite number here: the pixel is marked magenta and counted"
                    .into(),
            );
        }
        lines.push(self.derivative_note());
        (lines, uv)
    }
}

/// The absolute step of the finite differences, in object-space units.
const FD_STEP: f64 = 1e-5;

/// Where each of a formula's variables `names` sits among the inputs `vars`.
fn slots_of(names: &[String], vars: &[&str]) -> Result<Vec<usize>, String> {
    names
        .iter()
        .map(|n| {
            vars.iter()
                .position(|v| v == n)
                .ok_or_else(|| format!("unknown name `{n}`"))
        })
        .collect()
}

/// The inputs of a mapping formula: the point, then mesh_u and mesh_v.
#[must_use]
pub fn inputs_of(p: DVec3, mesh: DVec2) -> [f64; 5] {
    [p.x, p.y, p.z, mesh.x, mesh.y]
}

#[cfg(test)]
mod tests;
