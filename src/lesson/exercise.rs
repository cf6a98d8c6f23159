//! A lesson's exercise: write a mapping (or a checker texture) yourself. The lesson gives the
//! task, the formulas to start from (empty, or broken for the student to repair), the built-in
//! target and a solution:
//!
//! ```toml
//! [[exercise]]
//! task = "Write the cylindrical map."
//! target = "Cylindrical"            # a built-in mapping, or "Checker(squares: (8, 8), ...)"
//! object = 0                        # the object whose colour texture it sets; default 0
//! start = { u = "", v = "" }        # a texture exercise: { grey = "" }
//! solution = { u = "fract(atan2(x, z) / tau)", v = "clamp((y + 1) / 2)" }
//! ```
//!
//! *Check* ([`Exercise::check`]) compares the formulas with the target by the code of
//! `texplore map --compare`: a mapping on [`sample_points`] of the target's surface, within
//! one texel of a 2048 x 1024 image, u and v judged separately, with the common mistakes'
//! hints in two steps (what is wrong, then the fix); a checker texture on a grid of cell
//! centres of the (u, v) square, a colour agreeing within [`COLOUR_TOLERANCE`], with the
//! checker's common mistakes (colours exchanged, stripes, the wrong number of squares, the
//! wrong greys).

use crate::mapping::Mapping;
use crate::mapping::formula::compare::{
    CORRECT_SHARE, HINT_SHARE, Hint, Verdict, one_texel, sample_points, share_of,
};
use crate::mapping::formula::{FormulaError, FormulaMapping};
use crate::math::Rgb;
use crate::scene::{FieldPath, MappingDesc, SceneDesc, TextureDesc};
use crate::texture::{Checker, Filter, FormulaColour};
use std::fmt::Write as _;

/// The points along each side of the target mapping's surface that *Check* samples (as
/// `texplore map --compare`).
pub const CHECK_POINTS: usize = 64;

/// The image a mapping is checked for: (u, v) agree within one of its texels.
pub const CHECK_RESOLUTION: (u32, u32) = (2048, 1024);

/// The (u, v) grid a checker texture is checked on, cells along each side.
pub const CHECKER_GRID: usize = 256;

/// How far apart two colours (linear, per channel) may be and agree.
pub const COLOUR_TOLERANCE: f32 = 0.01;

/// What the student's formulas must give.
#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    /// A built-in mapping: the formulas are `u` and `v`.
    Mapping(Mapping),
    /// The built-in checker texture (over the object's mapping): the formula is `grey`.
    Checker {
        /// Squares along u and along v.
        squares: (f32, f32),
        /// The colour of the square at (0, 0), and the other.
        colors: (Rgb, Rgb),
    },
}

impl Target {
    /// The names of the formulas that must give it: `u`, `v` for a mapping, `grey` for a
    /// texture.
    #[must_use]
    pub const fn fields(&self) -> &'static [&'static str] {
        match self {
            Self::Mapping(_) => &["u", "v"],
            Self::Checker { .. } => &["grey"],
        }
    }
}

/// One exercise of a lesson.
#[derive(Clone, Debug, PartialEq)]
pub struct Exercise {
    /// What to write.
    pub task: String,
    /// The object (an index into the preset's) whose colour texture the formulas set.
    pub object: usize,
    /// What the formulas must agree with.
    pub target: Target,
    /// The formulas to start from, one per [`Exercise::fields`].
    pub start: Vec<String>,
    /// The lesson's solution, one per [`Exercise::fields`].
    pub solution: Vec<String>,
}

/// What *Check* found.
#[derive(Clone, Debug, PartialEq)]
pub struct Checked {
    /// Points compared.
    pub points: usize,
    /// Points where the formulas agree with the target.
    pub agreeing: usize,
    /// Points where a formula is NaN or infinite.
    pub non_finite: usize,
    /// A mapping's u and v judged alone: the points where each agrees.
    pub alone: Option<(usize, usize)>,
    /// The hint in two steps (what is wrong, then the fix), none for a correct answer.
    pub hint: Option<Hint>,
}

impl Checked {
    /// The share of points that agree, 0 to 1.
    #[must_use]
    pub fn share(&self) -> f64 {
        crate::mapping::formula::compare::share_of(self.agreeing, self.points)
    }

    /// The verdict in a sentence: the share and what it was measured on.
    #[must_use]
    pub fn summary(&self, target: &Target) -> String {
        let what = match target {
            Target::Mapping(m) => format!(
                "of {} points of the {} map's surface agree with it within one texel of a {} x {} image",
                self.points,
                crate::names::Named::name(*m),
                CHECK_RESOLUTION.0,
                CHECK_RESOLUTION.1
            ),
            Target::Checker { .. } => format!(
                "of {} points of the (u, v) square have the built-in checker's colour (within {COLOUR_TOLERANCE} per channel)",
                self.points
            ),
        };
        let mut s = format!("{:.1} % {what}", 100.0 * self.share());
        if let Some((u, v)) = self.alone
            && self.share() < CORRECT_SHARE
        {
            let _ = write!(
                s,
                " (u alone agrees at {:.1} %, v at {:.1} %)",
                100.0 * share_of(u, self.points),
                100.0 * share_of(v, self.points)
            );
        }
        if self.non_finite > 0 {
            let _ = write!(s, "; {} give NaN or infinity", self.non_finite);
        }
        s
    }

    /// Whether the answer is correct (agrees on [`CORRECT_SHARE`] of the points).
    #[must_use]
    pub fn correct(&self) -> bool {
        self.share() >= CORRECT_SHARE
    }
}

impl Exercise {
    /// The names of the formulas: `u`, `v` for a mapping, `grey` for a texture.
    #[must_use]
    pub const fn fields(&self) -> &'static [&'static str] {
        self.target.fields()
    }

    /// The target in words (`the cylindrical mapping`).
    #[must_use]
    pub fn target_name(&self) -> String {
        match &self.target {
            Target::Mapping(m) => format!("the {} mapping", crate::names::Named::name(*m)),
            Target::Checker { squares, .. } => format!(
                "the built-in checker ({} x {} squares)",
                squares.0, squares.1
            ),
        }
    }

    /// `formulas` against the target.
    ///
    /// # Errors
    /// A formula that does not compile (its field and column), or the wrong number of them.
    pub fn check(&self, formulas: &[String]) -> Result<Checked, FormulaError> {
        let field = |i: usize| formulas.get(i).map_or("", String::as_str);
        match &self.target {
            Target::Mapping(m) => {
                let f = FormulaMapping::checked(field(0), field(1))?;
                let points = sample_points(*m, CHECK_POINTS);
                let tol = one_texel(CHECK_RESOLUTION.0, CHECK_RESOLUTION.1);
                let verdict = Verdict::judge(&f, *m, &points, tol);
                let mut hint = verdict.hint(*m);
                // Nothing recognised: the fix is the lesson's own solution for what is wrong.
                if let Some(h) = hint.as_mut()
                    && verdict.findings.is_empty()
                {
                    let wrong = [
                        (!verdict.u_agrees(), "u", &self.solution[0]),
                        (!verdict.v_agrees(), "v", &self.solution[1]),
                    ];
                    let parts: Vec<String> = wrong
                        .iter()
                        .filter(|w| w.0)
                        .map(|(_, name, f)| format!("{name} = {f}"))
                        .collect();
                    if !parts.is_empty() {
                        h.fix = Some(format!(
                            "the lesson's solution writes {}",
                            parts.join(" and ")
                        ));
                    }
                }
                let a = verdict.agreement;
                Ok(Checked {
                    points: a.points,
                    agreeing: a.agreeing,
                    non_finite: a.non_finite,
                    alone: Some((verdict.u_agreeing, verdict.v_agreeing)),
                    hint,
                })
            }
            Target::Checker { squares, colors } => {
                let f = FormulaColour::grey(field(0))?;
                Ok(check_checker(&f, *squares, *colors))
            }
        }
    }

    /// The exercise's scene `desc` (the lesson's own, as its preset opened: not whatever an
    /// experiment left showing) with `formulas` on the exercise's object: its colour texture's mapping becomes
    /// the formulas (a mapping), or the texture becomes the grey formula over the texture's
    /// mapping and (u, v) transform (a texture).
    ///
    /// # Errors
    /// The scene has no such object, or its colour texture has no mapping.
    pub fn apply(&self, desc: &SceneDesc, formulas: &[String]) -> Result<SceneDesc, String> {
        let mut d = desc.clone();
        let field = |i: usize| formulas.get(i).cloned().unwrap_or_default();
        let obj = d
            .objects
            .get_mut(self.object)
            .ok_or_else(|| format!("the scene has no objects[{}]", self.object))?;
        let colour = FieldPath::field("objects")
            .at(self.object)
            .then("material")
            .then(obj.material.kind().colour_name());
        let tex = obj.material.texture_mut();
        let mapping = tex
            .mapping()
            .cloned()
            .ok_or_else(|| format!("{}: has no mapping", desc.name_field(&colour)))?;
        match self.target {
            Target::Mapping(_) => tex.set_mapping(MappingDesc::Formula {
                u: field(0),
                v: field(1),
            }),
            Target::Checker { .. } => {
                *tex = TextureDesc::Formula {
                    mapping,
                    grey: field(0),
                    r: String::new(),
                    g: String::new(),
                    b: String::new(),
                    uv: tex.uv_transform().unwrap_or_default(),
                };
            }
        }
        Ok(d)
    }

    /// The formulas `desc` holds for this exercise, if its object carries formulas of the
    /// exercise's kind.
    #[must_use]
    pub fn formulas_in(&self, desc: &SceneDesc) -> Option<Vec<String>> {
        let tex = desc.objects.get(self.object)?.material.texture();
        match (&self.target, tex) {
            (Target::Checker { .. }, TextureDesc::Formula { grey, .. }) => Some(vec![grey.clone()]),
            (Target::Mapping(_), t) => match t.mapping()? {
                MappingDesc::Formula { u, v } => Some(vec![u.clone(), v.clone()]),
                MappingDesc::Builtin(_) => None,
            },
            (Target::Checker { .. }, _) => None,
        }
    }
}

/// The grey formula against the checker on the cell centres of a [`CHECKER_GRID`] grid over
/// the (u, v) square; for a wrong one, the first of the checker's common mistakes that it
/// follows at [`HINT_SHARE`] of the points: the colours exchanged, the squares along u and v
/// exchanged, stripes along one of them, another number of squares, or the right pattern in
/// the wrong greys.
fn check_checker(f: &FormulaColour, squares: (f32, f32), colors: (Rgb, Rgb)) -> Checked {
    let n = CHECKER_GRID;
    let cell = |i: usize| (i as f32 + 0.5) / n as f32;
    let values: Vec<((f32, f32), Option<Rgb>)> = (0..n * n)
        .map(|k| {
            let (u, v) = (cell(k / n), cell(k % n));
            let got = f.eval(&[f64::from(u), f64::from(v), 0.0, 0.0, 0.0]);
            ((u, v), got)
        })
        .collect();
    let points = values.len();
    let non_finite = values.iter().filter(|(_, got)| got.is_none()).count();
    // The share of points where the formula gives `want(u, v)`.
    let share = |want: Pattern<'_>| {
        let k = values
            .iter()
            .filter(|&&((u, v), got)| got.is_some_and(|g| close(g, want(u, v))))
            .count();
        share_of(k, points)
    };
    let agreeing = values
        .iter()
        .filter(|&&((u, v), got)| got.is_some_and(|g| close(g, checker(squares, colors, u, v))))
        .count();
    let hint = if share_of(agreeing, points) >= CORRECT_SHARE {
        None
    } else {
        Some(checker_hint(squares, colors, &share, &values))
    };
    Checked {
        points,
        agreeing,
        non_finite,
        alone: None,
        hint,
    }
}

/// The built-in checker's own colour at (u, v).
fn checker(squares: (f32, f32), colors: (Rgb, Rgb), u: f32, v: f32) -> Rgb {
    Checker {
        mapping: Mapping::Rectangular.into(),
        squares,
        colors,
        filter: Filter::Nearest,
        transform: None,
    }
    .point(crate::math::Vec2::new(u, v))
}

/// Whether two colours agree within [`COLOUR_TOLERANCE`] per channel.
fn close(a: Rgb, b: Rgb) -> bool {
    (a.0 - b.0).abs() <= COLOUR_TOLERANCE
        && (a.1 - b.1).abs() <= COLOUR_TOLERANCE
        && (a.2 - b.2).abs() <= COLOUR_TOLERANCE
}

/// A grey (or a colour) as the lesson writes it: `0.9`, or `(0.9, 0.5, 0.1)`.
fn grey(c: Rgb) -> String {
    if c.0 == c.1 && c.1 == c.2 {
        format!("{}", c.0)
    } else {
        format!("({}, {}, {})", c.0, c.1, c.2)
    }
}

/// A colour at each (u, v): the checker, or one of its common mistakes.
type Pattern<'a> = &'a dyn Fn(f32, f32) -> Rgb;

/// The checker's two-step hint: the first common mistake the formula follows, else none.
fn checker_hint(
    squares: (f32, f32),
    colors: (Rgb, Rgb),
    share: &dyn Fn(Pattern<'_>) -> f64,
    values: &[((f32, f32), Option<Rgb>)],
) -> Hint {
    let (a, b) = (grey(colors.0), grey(colors.1));
    let (n, m) = squares;
    let pattern = format!("floor({n} u) + floor({m} v)");
    let rule = format!("{a} where {pattern} is even and {b} where it is odd");
    let follows = |want: Pattern<'_>| share(want) >= HINT_SHARE;
    // A stripe's colour: the first where floor(k t) is even.
    let stripe = |k: f32, t: f32| {
        if (k * t).floor().rem_euclid(2.0) == 0.0 {
            colors.0
        } else {
            colors.1
        }
    };
    let (what, fix) = if follows(&|u, v| checker(squares, (colors.1, colors.0), u, v)) {
        (
            "the squares are right but their colours are the wrong way round".to_owned(),
            format!("the square at u, v = 0 has the first colour: {rule}"),
        )
    } else if n != m && follows(&|u, v| checker((m, n), colors, u, v)) {
        (
            "the squares along u and v are exchanged".to_owned(),
            format!("{n} squares along u and {m} along v: {pattern}"),
        )
    } else if follows(&|u, _| stripe(n, u)) || follows(&|_, v| stripe(m, v)) {
        let along = if follows(&|u, _| stripe(n, u)) {
            "u"
        } else {
            "v"
        };
        let other = if along == "u" { "v" } else { "u" };
        (
            format!("the colour changes along {along} only: these are stripes, not squares"),
            format!("add {other}'s term: {rule}"),
        )
    } else if let Some(k) = (1..=32)
        .map(|k| k as f32)
        .find(|&k| (k, k) != squares && follows(&|u, v| checker((k, k), colors, u, v)))
    {
        (
            format!("the squares are the wrong size: {k} x {k} of them, not {n} x {m}"),
            format!("multiply u by {n} and v by {m}: {rule}"),
        )
    } else if let Some((c0, c1)) = two_greys(squares, values)
        && !(close(c0, colors.0) && close(c1, colors.1))
    {
        (
            format!(
                "the pattern is right but the greys are not: {} and {}",
                grey(c0),
                grey(c1)
            ),
            rule.clone(),
        )
    } else {
        (
            "the formula fits no common mistake".to_owned(),
            format!("the checker is {rule}"),
        )
    };
    Hint {
        what,
        fix: Some(fix),
    }
}

/// The two colours the formula gives on the checker's even and odd squares, when it gives one
/// colour on each (at [`HINT_SHARE`] of its points): the right pattern in other greys.
fn two_greys(squares: (f32, f32), values: &[((f32, f32), Option<Rgb>)]) -> Option<(Rgb, Rgb)> {
    let odd =
        |u: f32, v: f32| ((squares.0 * u).floor() + (squares.1 * v).floor()).rem_euclid(2.0) != 0.0;
    let mut found = [None::<Rgb>; 2];
    for (parity, slot) in found.iter_mut().enumerate() {
        let class: Vec<Rgb> = values
            .iter()
            .filter(|((u, v), _)| usize::from(odd(*u, *v)) == parity)
            .filter_map(|(_, got)| *got)
            .collect();
        let first = *class.first()?;
        let same = class.iter().filter(|&&c| close(c, first)).count();
        if share_of(same, class.len()) < HINT_SHARE {
            return None;
        }
        *slot = Some(first);
    }
    Some((found[0]?, found[1]?))
}

/// An exercise as the lesson file writes it.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ExerciseFile {
    task: String,
    target: toml::Spanned<String>,
    #[serde(default)]
    object: usize,
    start: toml::Spanned<FormulasFile>,
    solution: toml::Spanned<FormulasFile>,
}

/// `{ u = "...", v = "..." }` or `{ grey = "..." }`.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct FormulasFile {
    u: Option<String>,
    v: Option<String>,
    grey: Option<String>,
}

/// The share of the target's points a lesson's solution must agree on.
pub const SOLUTION_SHARE: f64 = 0.999;

/// What a mistake in an exercise says, and where (a byte offset into the lesson's text).
pub(super) type Fault = (usize, String);

impl ExerciseFile {
    /// The exercise, checked against the lesson's scene `base`: the target is a built-in
    /// mapping or a checker, the formulas are those of its kind, the object exists and its
    /// colour texture has a mapping, the solution agrees with the target on at least
    /// [`SOLUTION_SHARE`] of the points and the starting formulas do not already agree.
    pub(super) fn build(self, base: &SceneDesc) -> Result<Exercise, Fault> {
        let target_at = self.target.span().start;
        let target = parse_target(self.target.get_ref()).map_err(|m| (target_at, m))?;
        let fields = target.fields();
        let start = formulas(&self.start, "start", fields)?;
        let solution = formulas(&self.solution, "solution", fields)?;
        let ex = Exercise {
            task: self.task.trim().to_owned(),
            object: self.object,
            target,
            start,
            solution,
        };
        ex.apply(base, &ex.solution)
            .map_err(|m| (target_at, format!("`object` = {}: {m}", self.object)))?;
        let solution_at = self.solution.span().start;
        let checked = ex
            .check(&ex.solution)
            .map_err(|e| (solution_at, format!("`solution.{e}")))?;
        if checked.share() < SOLUTION_SHARE {
            return Err((
                solution_at,
                format!(
                    "`solution` does not solve it: {} (at least {:.1} % must)",
                    checked.summary(&ex.target),
                    100.0 * SOLUTION_SHARE
                ),
            ));
        }
        if let Ok(c) = ex.check(&ex.start)
            && c.share() >= crate::mapping::formula::compare::CORRECT_SHARE
        {
            return Err((
                self.start.span().start,
                format!(
                    "`start` already agrees with {}: there is nothing to write ({})",
                    ex.target_name(),
                    c.summary(&ex.target)
                ),
            ));
        }
        Ok(ex)
    }
}

/// A built-in mapping's name (`Cylindrical`), or a checker texture in RON.
fn parse_target(text: &str) -> Result<Target, String> {
    if let Ok(m) = ron::from_str::<Mapping>(text) {
        return Ok(Target::Mapping(m));
    }
    match ron::from_str::<TextureDesc>(text) {
        Ok(TextureDesc::Checker {
            squares, colors, ..
        }) => match crate::scene::check_checker(squares, &colors) {
            Ok(()) => Ok(Target::Checker { squares, colors }),
            Err(r) => {
                let r = r.under(&FieldPath::field("target"));
                Err(format!("`{}`: {}", r.field, r.message))
            }
        },
        Ok(_) => Err(format!(
            "`target` = {text:?}: a texture target must be a Checker"
        )),
        Err(e) => Err(format!(
            "`target` = {text:?} is neither a built-in mapping ({}) nor a Checker texture: {e}",
            <Mapping as strum::VariantArray>::VARIANTS
                .iter()
                .map(|m| format!("{m:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// The formulas of `table` (`start` or `solution`), one per field, or what is missing or extra.
fn formulas(
    table: &toml::Spanned<FormulasFile>,
    name: &str,
    fields: &[&str],
) -> Result<Vec<String>, Fault> {
    let at = table.span().start;
    let t = table.get_ref();
    let given = [("u", &t.u), ("v", &t.v), ("grey", &t.grey)];
    for (key, value) in given {
        if value.is_some() && !fields.contains(&key) {
            return Err((
                at,
                format!(
                    "`{name}.{key}`: this exercise's formulas are {}",
                    fields.join(" and ")
                ),
            ));
        }
    }
    fields
        .iter()
        .map(|f| {
            given
                .iter()
                .find(|(k, _)| k == f)
                .and_then(|(_, v)| (*v).clone())
                .ok_or_else(|| (at, format!("`{name}.{f}` is missing (write \"\" for none)")))
        })
        .collect()
}
