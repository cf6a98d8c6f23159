//! Symbolic partial derivatives of a recorded formula: forward along its [`Tape`], each step's
//! derivative built from the derivatives of what it reads (the chain rule, one step at a time),
//! and appended to the same tape, so [`super::program::Program`] compiles it as it compiles a
//! value.
//!
//! This replaced exmex's own `partial`, which differentiates its recursive expression tree:
//! its frames take tens of kilobytes each, so a product or quotient of a few dozen operands
//! overflowed the stack and aborted the process (`x/x/.../x` of 12 operands on a worker
//! thread's 2 MiB). Here nothing recurses, and the work is bounded by the formula: each step
//! adds at most [`STEPS_PER_STEP`] steps, so a formula of the longest length (4096 bytes, at
//! most a few thousand steps) has a derivative of at most a few tens of thousands.
//!
//! Sums and products whose derivative is zero are folded away as they are built (`0 * a`,
//! `a + 0`, `1 * a`), and numbers are combined, so the lecture's formulas give programs no
//! longer than exmex's simplified derivatives.

use super::ops::{Bin, Step, Sym, Tape, Un};

/// The most steps one step's derivative appends (`a ^ b` with both read: a log, three
/// products, a quotient and a sum).
pub const STEPS_PER_STEP: usize = 6;

/// The functions with no symbolic derivative here that `tape` applies to something that is
/// not a number (numbers are folded as they are recorded, so such a step reads an input): a
/// formula calling one takes finite differences. Sorted, each once.
#[must_use]
pub fn blocked(tape: &Tape) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = tape
        .steps
        .iter()
        .filter_map(|s| match *s {
            Step::Un(op, _) => plain_unary(op),
            Step::Bin(op, _, _) => plain_binary(op),
        })
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// The name of a function of one argument with no derivative here.
const fn plain_unary(op: Un) -> Option<&'static str> {
    match op {
        Un::Abs => Some("abs"),
        Un::Floor => Some("floor"),
        Un::Ceil => Some("ceil"),
        Un::Round => Some("round"),
        Un::Fract => Some("fract"),
        Un::Sign => Some("sign"),
        Un::Clamp => Some("clamp"),
        Un::Neg
        | Un::Acos
        | Un::Asin
        | Un::Atan
        | Un::Sqrt
        | Un::Sin
        | Un::Cos
        | Un::Tan
        | Un::Exp
        | Un::Ln => None,
    }
}

/// The name of a function of two arguments with no derivative here.
const fn plain_binary(op: Bin) -> Option<&'static str> {
    match op {
        Bin::Atan2 => Some("atan2"),
        Bin::Min => Some("min"),
        Bin::Max => Some("max"),
        Bin::Add | Bin::Sub | Bin::Mul | Bin::Div | Bin::Pow => None,
    }
}

/// The derivative of `root`, recorded on `tape`, with respect to exmex's variable `var`; the
/// steps it needs are appended to `tape`. A step of a function [`blocked`] names has no
/// derivative: it is NaN where its argument changes with `var` (a formula calling one takes
/// finite differences instead, so this is never evaluated).
pub fn derivative(tape: &mut Tape, root: Sym, var: usize) -> Sym {
    let n = match root {
        Sym::Step(i) => i as usize + 1,
        _ => 0,
    };
    let before = tape.steps.len();
    // The derivative of each step up to the root, in the tape's order.
    let mut d: Vec<Sym> = Vec::with_capacity(n);
    for i in 0..n {
        let of = |s: Sym, d: &[Sym]| match s {
            Sym::Num(_) => ZERO,
            Sym::Var(k) => Sym::Num(if k == var { 1.0 } else { 0.0 }),
            Sym::Step(k) => d.get(k as usize).copied().unwrap_or(ZERO),
        };
        let value = Sym::Step(i as u32);
        let di = match tape.steps[i] {
            Step::Un(op, a) => {
                let da = of(a, &d);
                if is_zero(da) {
                    ZERO
                } else {
                    unary(tape, op, a, da, value)
                }
            }
            Step::Bin(op, a, b) => {
                let (da, db) = (of(a, &d), of(b, &d));
                if is_zero(da) && is_zero(db) {
                    ZERO
                } else {
                    binary(tape, op, (a, da), (b, db), value)
                }
            }
        };
        d.push(di);
        debug_assert!(tape.steps.len() <= before + STEPS_PER_STEP * (i + 1));
    }
    match root {
        Sym::Num(_) => ZERO,
        Sym::Var(k) => Sym::Num(if k == var { 1.0 } else { 0.0 }),
        Sym::Step(i) => d[i as usize],
    }
}

const ZERO: Sym = Sym::Num(0.0);

/// The derivative of a function [`blocked`] names.
const NO: Sym = Sym::Num(f64::NAN);

fn is_zero(s: Sym) -> bool {
    matches!(s, Sym::Num(x) if x == 0.0)
}

fn is_one(s: Sym) -> bool {
    matches!(s, Sym::Num(x) if x == 1.0)
}

fn add(t: &mut Tape, a: Sym, b: Sym) -> Sym {
    if is_zero(a) {
        b
    } else if is_zero(b) {
        a
    } else {
        t.bin(Bin::Add, a, b)
    }
}

fn sub(t: &mut Tape, a: Sym, b: Sym) -> Sym {
    if is_zero(b) {
        a
    } else if is_zero(a) {
        t.un(Un::Neg, b)
    } else {
        t.bin(Bin::Sub, a, b)
    }
}

fn mul(t: &mut Tape, a: Sym, b: Sym) -> Sym {
    if is_zero(a) || is_zero(b) {
        ZERO
    } else if is_one(a) {
        b
    } else if is_one(b) {
        a
    } else {
        t.bin(Bin::Mul, a, b)
    }
}

fn div(t: &mut Tape, a: Sym, b: Sym) -> Sym {
    if is_zero(a) {
        ZERO
    } else if is_one(b) {
        a
    } else {
        t.bin(Bin::Div, a, b)
    }
}

/// d op(a) from a, da and the step's own value.
fn unary(t: &mut Tape, op: Un, a: Sym, da: Sym, value: Sym) -> Sym {
    let one = Sym::Num(1.0);
    match op {
        Un::Neg => t.un(Un::Neg, da),
        Un::Sqrt => {
            let twice = mul(t, Sym::Num(2.0), value);
            div(t, da, twice)
        }
        Un::Exp => mul(t, da, value),
        Un::Ln => div(t, da, a),
        Un::Sin => {
            let c = t.un(Un::Cos, a);
            mul(t, da, c)
        }
        Un::Cos => {
            let s = t.un(Un::Sin, a);
            let m = mul(t, da, s);
            t.un(Un::Neg, m)
        }
        Un::Tan => {
            let c = t.un(Un::Cos, a);
            let c2 = mul(t, c, c);
            div(t, da, c2)
        }
        Un::Asin | Un::Acos => {
            let a2 = mul(t, a, a);
            let rest = sub(t, one, a2);
            let root = t.un(Un::Sqrt, rest);
            let q = div(t, da, root);
            if op == Un::Acos { t.un(Un::Neg, q) } else { q }
        }
        Un::Atan => {
            let a2 = mul(t, a, a);
            let below = add(t, one, a2);
            div(t, da, below)
        }
        Un::Abs | Un::Floor | Un::Ceil | Un::Round | Un::Fract | Un::Sign | Un::Clamp => NO,
    }
}

/// d op(a, b) from a, da, b, db and the step's own value.
fn binary(t: &mut Tape, op: Bin, (a, da): (Sym, Sym), (b, db): (Sym, Sym), value: Sym) -> Sym {
    match op {
        Bin::Add => add(t, da, db),
        Bin::Sub => sub(t, da, db),
        Bin::Mul => {
            let l = mul(t, da, b);
            let r = mul(t, a, db);
            add(t, l, r)
        }
        Bin::Div => {
            // (da b - a db) / b^2
            let l = mul(t, da, b);
            let r = mul(t, a, db);
            let top = sub(t, l, r);
            let b2 = mul(t, b, b);
            div(t, top, b2)
        }
        Bin::Pow if is_zero(db) => {
            // b a^(b - 1) da: a constant power, defined for negative a too.
            let lower = sub(t, b, Sym::Num(1.0));
            let p = t.bin(Bin::Pow, a, lower);
            let bp = mul(t, b, p);
            mul(t, bp, da)
        }
        Bin::Pow => {
            // a^b (db ln a + b da / a)
            let ln = t.un(Un::Ln, a);
            let l = mul(t, db, ln);
            let bda = mul(t, b, da);
            let r = div(t, bda, a);
            let s = add(t, l, r);
            mul(t, value, s)
        }
        Bin::Atan2 | Bin::Min | Bin::Max => NO,
    }
}
