//! Hostile formulas (issue 38 §1), shared by the headless and the window tests: every operator
//! chained to the 4096-byte limit, every function nested to the bracket limit and repeated,
//! brackets nested to the limit, unary signs piled up, and the worst mixes. Before texplore
//! differentiated along a tape, exmex's recursive derivative overflowed the stack on the
//! shortest of them (12 operands of `/` on a worker thread) and aborted the process.

// Each test crate uses a subset of these.
#![allow(dead_code)]

use texplore::mapping::formula::{BINARY, MAX_FORMULA_BYTES, MAX_NESTING, UNARY};

/// `unit sep unit sep ... last`, as long as fits in the length limit.
#[must_use]
pub fn fill(unit: &str, sep: &str, last: &str) -> String {
    let mut s = String::from(last);
    while s.len() + unit.len() + sep.len() <= MAX_FORMULA_BYTES {
        s = format!("{unit}{sep}{s}");
    }
    s
}

/// `n` operands of `x` joined by `op`: `x/x/x` for 3.
#[must_use]
pub fn chain(op: &str, n: usize) -> String {
    vec!["x"; n].join(op)
}

fn nest(open: &str, inner: &str, close: &str, depth: usize) -> String {
    format!("{}{inner}{}", open.repeat(depth), close.repeat(depth))
}

/// The issue's own cases: what aborted each path (the window at 12 operands, `map formula` at
/// 64, `render` at 48, a lesson's solution at 100), and a 4096-byte sum.
#[must_use]
pub fn reported() -> Vec<(String, String)> {
    vec![
        ("12 quotients".into(), chain("/", 12)),
        ("20 sums".into(), chain("+", 20)),
        ("20 products".into(), chain("*", 20)),
        ("48 quotients".into(), chain("/", 48)),
        ("64 quotients".into(), chain("/", 64)),
        ("72 products".into(), chain("*", 72)),
        ("150 sums".into(), chain("+", 150)),
        ("a 4096-byte sum".into(), fill("x", "+", "x")),
    ]
}

/// Every shape: (what it is, the formula), each at most [`MAX_FORMULA_BYTES`] long.
#[must_use]
pub fn hostile_formulas() -> Vec<(String, String)> {
    let n = MAX_NESTING;
    let mut out = reported();
    for op in ["+", "-", "*", "/", "^"] {
        out.push((format!("x {op} x ... to the limit"), fill("x", op, "x")));
        out.push((
            format!("mesh_u {op} ... y to the limit"),
            fill("mesh_u", op, "y"),
        ));
    }
    for f in UNARY {
        let one = nest(&format!("{f}("), "x", ")", n);
        out.push((
            format!("{f} nested {n} deep, repeated"),
            fill(&one, "+", "x"),
        ));
    }
    for f in BINARY {
        let one = nest(&format!("{f}("), "x", ", y)", n);
        out.push((
            format!("{f} nested {n} deep, repeated"),
            fill(&one, "*", "x"),
        ));
        out.push((
            format!("{f} chained"),
            fill(&format!("{f}(x, y)"), "/", "x"),
        ));
    }
    out.extend([
        (
            "brackets nested to the limit".into(),
            nest("(", "x", ")", n),
        ),
        (
            "brackets nested to the limit, repeated".into(),
            fill(&nest("(", "x", ")", n), "/", "x"),
        ),
        (
            "quotients nested to the limit, repeated".into(),
            fill(&nest("x/(", "x", ")", n), "^", "x"),
        ),
        (
            "powers nested to the limit, repeated".into(),
            fill(&nest("x^(", "y", ")", n), "-", "x"),
        ),
        (
            "unary minus piled up".into(),
            "-".repeat(MAX_FORMULA_BYTES - 1) + "x",
        ),
        ("unary signs alternating".into(), "+-".repeat(2047) + "x"),
        ("negated operands".into(), fill("-x", "*", "x")),
        ("negative powers".into(), fill("x", "^-", "x")),
        ("sums of products".into(), fill("x*y", "+", "z")),
        ("products of sums".into(), fill("(x+y)", "*", "z")),
        (
            "every function once, repeated".into(),
            fill(
                "sin(x)*cos(y)/tan(z)^asin(x)-acos(y)+atan(z)*sqrt(x)/exp(y)^ln(z)",
                "/",
                "x",
            ),
        ),
        (
            "the lecture's spherical v, repeated".into(),
            fill("acos(y / sqrt(x*x + y*y + z*z)) / pi", "*", "1"),
        ),
        ("a long number".into(), "1".repeat(MAX_FORMULA_BYTES)),
        (
            "a long decimal".into(),
            format!("0.{}", "1".repeat(MAX_FORMULA_BYTES - 2)),
        ),
        ("numbers chained".into(), fill("2", "^", "2")),
        (
            "spaces".into(),
            format!("{}x", " ".repeat(MAX_FORMULA_BYTES - 1)),
        ),
        ("one byte over the limit".into(), fill("x", "+", "x") + "+x"),
    ]);
    out
}
