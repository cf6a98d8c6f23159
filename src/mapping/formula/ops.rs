//! The operators a formula may use: exmex's float operators, narrowed to the ones texplore
//! documents, with GLSL's `fract` (x - floor(x), in [0, 1) for negative x too; Rust's and
//! exmex's `fract` keep the sign) and `sign`, and the lecture's constants `pi` and `tau`.
//!
//! Each operator is listed once ([`formula_ops!`]) and built twice: over `f64`
//! ([`FormulaOps`]: exmex evaluates with it) and over [`Sym`] ([`SymOps`]: exmex's evaluation
//! of a formula over symbols records each step it takes on a [`Tape`], in exmex's own order,
//! which [`super::program`] turns into a flat program and [`super::derive`] differentiates).
//! Both apply the same functions ([`un`], [`bin`]), so a program gives exmex's value bit for
//! bit.
//!
//! `^`, `*`, `/`, `+`, `-`, `sqrt`, `ln`, `exp`, the trigonometric functions and their inverses
//! have symbolic derivatives; the others here (`atan2`, `min`, `max`, `abs`, `floor`, `fract`,
//! `sign`, `clamp`...) do not, and a formula applying one to an input falls back to finite
//! differences.

use exmex::{BinOp, MakeOperators, Operator};
use std::f64::consts::{PI, TAU};

/// Functions of one argument, as the formulas write them.
pub const UNARY: [&str; 16] = [
    "acos", "asin", "atan", "sqrt", "abs", "floor", "fract", "sign", "clamp", "sin", "cos", "tan",
    "exp", "ln", "ceil", "round",
];

/// Functions of two arguments.
pub const BINARY: [&str; 3] = ["atan2", "min", "max"];

/// Named constants.
pub const CONSTANTS: [&str; 2] = ["pi", "tau"];

/// A function of one argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Un {
    Neg,
    Acos,
    Asin,
    Atan,
    Sqrt,
    Abs,
    Floor,
    Ceil,
    Round,
    Fract,
    Sign,
    Clamp,
    Sin,
    Cos,
    Tan,
    Exp,
    Ln,
}

/// A function of two arguments (the operators among them).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Bin {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Atan2,
    Min,
    Max,
}

/// The value of a function of one argument.
#[inline]
#[must_use]
pub fn un(op: Un, a: f64) -> f64 {
    match op {
        Un::Neg => -a,
        Un::Acos => a.acos(),
        Un::Asin => a.asin(),
        Un::Atan => a.atan(),
        Un::Sqrt => a.sqrt(),
        Un::Abs => a.abs(),
        Un::Floor => a.floor(),
        Un::Ceil => a.ceil(),
        Un::Round => a.round(),
        Un::Fract => fract(a),
        Un::Sign => sign(a),
        Un::Clamp => a.clamp(0.0, 1.0),
        Un::Sin => a.sin(),
        Un::Cos => a.cos(),
        Un::Tan => a.tan(),
        Un::Exp => a.exp(),
        Un::Ln => a.ln(),
    }
}

/// The value of a function of two arguments.
#[inline]
#[must_use]
pub fn bin(op: Bin, a: f64, b: f64) -> f64 {
    match op {
        Bin::Add => a + b,
        Bin::Sub => a - b,
        Bin::Mul => a * b,
        Bin::Div => a / b,
        Bin::Pow => a.powf(b),
        Bin::Atan2 => a.atan2(b),
        Bin::Min => a.min(b),
        Bin::Max => a.max(b),
    }
}

/// GLSL's fract: x - floor(x), in [0, 1) (an x just below a whole number can round to 1, which
/// is brought back to 0: the seam of a periodic coordinate).
fn fract(a: f64) -> f64 {
    let f = a - a.floor();
    if f < 1.0 { f } else { 0.0 }
}

/// -1, 0 or 1 (NaN stays NaN); Rust's `signum` gives 1 at 0.
fn sign(a: f64) -> f64 {
    if a > 0.0 {
        1.0
    } else if a < 0.0 {
        -1.0
    } else {
        a
    }
}

/// A formula's value as a symbol: a number, an input, or a step recorded on the [`Tape`].
/// exmex evaluating a formula over symbols records, step by step, what it computes.
///
/// A symbol is a plain index, never a tree: no recursion walks it, builds it or drops it, so
/// a formula of any shape up to the length limit costs no stack (a tree of `Arc`s, which this
/// replaced, dropped and compiled recursively).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sym {
    /// A number (numbers combined as exmex combines them, with [`un`] and [`bin`]).
    Num(f64),
    /// exmex's variable of this index (alphabetical).
    Var(usize),
    /// The result of step `i` of the tape.
    Step(u32),
}

impl Default for Sym {
    fn default() -> Self {
        Self::Num(0.0)
    }
}

impl std::str::FromStr for Sym {
    type Err = std::num::ParseFloatError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        s.parse().map(Self::Num)
    }
}

/// One step of a recorded formula: a function of earlier steps, inputs or numbers.
#[derive(Clone, Copy, Debug)]
pub enum Step {
    /// A function of one symbol.
    Un(Un, Sym),
    /// A function of two symbols.
    Bin(Bin, Sym, Sym),
}

/// The steps of one recorded formula, in the order exmex took them: each reads only earlier
/// steps, so a walk in order (or in reverse) visits every step after (or before) what it reads.
#[derive(Clone, Debug, Default)]
pub struct Tape {
    /// The steps.
    pub steps: Vec<Step>,
}

impl Tape {
    /// Appends `step`, returning its symbol.
    pub fn push(&mut self, step: Step) -> Sym {
        self.steps.push(step);
        Sym::Step((self.steps.len() - 1) as u32)
    }

    /// `op(a)`, folded when `a` is a number.
    pub fn un(&mut self, op: Un, a: Sym) -> Sym {
        match a {
            Sym::Num(x) => Sym::Num(un(op, x)),
            a => self.push(Step::Un(op, a)),
        }
    }

    /// `op(a, b)`, folded when both are numbers.
    pub fn bin(&mut self, op: Bin, a: Sym, b: Sym) -> Sym {
        match (a, b) {
            (Sym::Num(x), Sym::Num(y)) => Sym::Num(bin(op, x, y)),
            (a, b) => self.push(Step::Bin(op, a, b)),
        }
    }
}

thread_local! {
    /// The tape exmex's evaluation over symbols records on. exmex's operators are plain `fn`s
    /// with no state of their own, so the steps they take can only be kept beside them; one
    /// recording runs at a time on a thread ([`record`] takes the tape whole before returning).
    static RECORDING: std::cell::RefCell<Tape> = std::cell::RefCell::new(Tape::default());
}

/// Runs `f` (exmex's evaluation over symbols) on a fresh tape and returns the tape it recorded.
pub fn record<T>(f: impl FnOnce() -> T) -> (T, Tape) {
    RECORDING.with(|t| t.borrow_mut().steps.clear());
    let out = f();
    let tape = RECORDING.with(|t| std::mem::take(&mut *t.borrow_mut()));
    (out, tape)
}

impl Sym {
    fn un(op: Un, a: Self) -> Self {
        RECORDING.with(|t| t.borrow_mut().un(op, a))
    }

    fn bin(op: Bin, a: Self, b: Self) -> Self {
        RECORDING.with(|t| t.borrow_mut().bin(op, a, b))
    }
}

/// Every operator over `$t`, applying `$un` and `$bin`; `$num` makes a constant. Priorities
/// as exmex's own float operators (`FloatOpsFactory`), so its derivative rules, which rebuild
/// expressions from these names, read them the same way.
macro_rules! formula_ops {
    ($t:ty, $un:path, $bin:path, $num:path) => {{
        let b = |repr, prio, is_commutative, apply: fn($t, $t) -> $t| {
            Operator::make_bin(
                repr,
                BinOp {
                    apply,
                    prio,
                    is_commutative,
                },
            )
        };
        vec![
            b("^", 4, false, |x, y| $bin(Bin::Pow, x, y)),
            b("*", 2, true, |x, y| $bin(Bin::Mul, x, y)),
            b("/", 3, false, |x, y| $bin(Bin::Div, x, y)),
            Operator::make_bin_unary(
                "+",
                BinOp {
                    apply: |x, y| $bin(Bin::Add, x, y),
                    prio: 0,
                    is_commutative: true,
                },
                |x| x,
            ),
            Operator::make_bin_unary(
                "-",
                BinOp {
                    apply: |x, y| $bin(Bin::Sub, x, y),
                    prio: 1,
                    is_commutative: false,
                },
                |x| $un(Un::Neg, x),
            ),
            b("atan2", 0, false, |x, y| $bin(Bin::Atan2, x, y)),
            b("min", 0, false, |x, y| $bin(Bin::Min, x, y)),
            b("max", 0, false, |x, y| $bin(Bin::Max, x, y)),
            Operator::make_unary("acos", |x| $un(Un::Acos, x)),
            Operator::make_unary("asin", |x| $un(Un::Asin, x)),
            Operator::make_unary("atan", |x| $un(Un::Atan, x)),
            Operator::make_unary("sqrt", |x| $un(Un::Sqrt, x)),
            Operator::make_unary("abs", |x| $un(Un::Abs, x)),
            Operator::make_unary("floor", |x| $un(Un::Floor, x)),
            Operator::make_unary("ceil", |x| $un(Un::Ceil, x)),
            Operator::make_unary("round", |x| $un(Un::Round, x)),
            Operator::make_unary("fract", |x| $un(Un::Fract, x)),
            Operator::make_unary("sign", |x| $un(Un::Sign, x)),
            Operator::make_unary("clamp", |x| $un(Un::Clamp, x)),
            Operator::make_unary("sin", |x| $un(Un::Sin, x)),
            Operator::make_unary("cos", |x| $un(Un::Cos, x)),
            Operator::make_unary("tan", |x| $un(Un::Tan, x)),
            Operator::make_unary("exp", |x| $un(Un::Exp, x)),
            Operator::make_unary("ln", |x| $un(Un::Ln, x)),
            Operator::make_constant("pi", $num(PI)),
            Operator::make_constant("tau", $num(TAU)),
        ]
    }};
}

/// The operators over `f64`: what exmex parses, evaluates and differentiates with.
#[derive(Clone, Debug)]
pub struct FormulaOps;

impl MakeOperators<f64> for FormulaOps {
    fn make<'a>() -> Vec<Operator<'a, f64>> {
        formula_ops!(f64, un, bin, std::convert::identity)
    }
}

/// The operators over [`Sym`]: exmex's evaluation records the tree.
#[derive(Clone, Debug)]
pub struct SymOps;

impl MakeOperators<Sym> for SymOps {
    fn make<'a>() -> Vec<Operator<'a, Sym>> {
        formula_ops!(Sym, Sym::un, Sym::bin, Sym::Num)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fract_and_sign_follow_glsl() {
        assert_eq!(fract(-0.25), 0.75);
        assert_eq!(fract(1.25), 0.25);
        assert_eq!(fract(-1e-20), 0.0);
        assert_eq!(sign(0.0), 0.0);
        assert_eq!(sign(-3.0), -1.0);
        assert!(sign(f64::NAN).is_nan());
    }
}
