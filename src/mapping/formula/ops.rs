//! The operators a formula may use: exmex's float operators, narrowed to the ones texplore
//! documents, with GLSL's `fract` (x - floor(x), in [0, 1) for negative x too; Rust's and
//! exmex's `fract` keep the sign) and `sign`, and the lecture's constants `pi` and `tau`.
//!
//! exmex differentiates an expression by the operator names it knows (`^`, `*`, `/`, `+`, `-`,
//! `sqrt`, `ln`, `exp`, the trigonometric functions and their inverses); the others here
//! (`atan2`, `min`, `max`, `abs`, `floor`, `fract`, `sign`, `clamp`) have no symbolic derivative
//! there, and a formula using one falls back to finite differences.

use exmex::{BinOp, MakeOperators, Operator};

/// The operator set of formula mappings and textures (see the module docs).
#[derive(Clone, Debug)]
pub struct FormulaOps;

/// Functions of one argument, as the formulas write them.
pub const UNARY: [&str; 16] = [
    "acos", "asin", "atan", "sqrt", "abs", "floor", "fract", "sign", "clamp", "sin", "cos", "tan",
    "exp", "ln", "ceil", "round",
];

/// Functions of two arguments.
pub const BINARY: [&str; 3] = ["atan2", "min", "max"];

/// Named constants.
pub const CONSTANTS: [&str; 2] = ["pi", "tau"];

impl MakeOperators<f64> for FormulaOps {
    fn make<'a>() -> Vec<Operator<'a, f64>> {
        // Priorities as exmex's own float operators (`FloatOpsFactory`), so its derivative rules,
        // which rebuild expressions from these names, read them the same way.
        let bin = |repr: &'a str, prio: i64, is_commutative: bool, apply: fn(f64, f64) -> f64| {
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
            bin("^", 4, false, f64::powf),
            bin("*", 2, true, |a, b| a * b),
            bin("/", 3, false, |a, b| a / b),
            Operator::make_bin_unary(
                "+",
                BinOp {
                    apply: |a, b| a + b,
                    prio: 0,
                    is_commutative: true,
                },
                |a| a,
            ),
            Operator::make_bin_unary(
                "-",
                BinOp {
                    apply: |a, b| a - b,
                    prio: 1,
                    is_commutative: false,
                },
                |a| -a,
            ),
            bin("atan2", 0, false, f64::atan2),
            bin("min", 0, false, f64::min),
            bin("max", 0, false, f64::max),
            Operator::make_unary("acos", f64::acos),
            Operator::make_unary("asin", f64::asin),
            Operator::make_unary("atan", f64::atan),
            Operator::make_unary("sqrt", f64::sqrt),
            Operator::make_unary("abs", f64::abs),
            Operator::make_unary("floor", f64::floor),
            Operator::make_unary("ceil", f64::ceil),
            Operator::make_unary("round", f64::round),
            Operator::make_unary("fract", fract),
            Operator::make_unary("sign", sign),
            Operator::make_unary("clamp", |a| a.clamp(0.0, 1.0)),
            Operator::make_unary("sin", f64::sin),
            Operator::make_unary("cos", f64::cos),
            Operator::make_unary("tan", f64::tan),
            Operator::make_unary("exp", f64::exp),
            Operator::make_unary("ln", f64::ln),
            Operator::make_constant("pi", std::f64::consts::PI),
            Operator::make_constant("tau", std::f64::consts::TAU),
        ]
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
