//! The check a formula passes before exmex parses it: a scan of its tokens (numbers, names,
//! operators, brackets, commas) that finds the mistakes a student makes and says where, by
//! column: an unknown name, a function without its brackets or with the wrong number of
//! arguments, two operators in a row, a missing operator, an unclosed bracket, nesting past
//! [`MAX_NESTING`]. exmex still parses, evaluates and differentiates; its own errors name no
//! position, so this scan runs first.

use super::ops::{BINARY, CONSTANTS, UNARY};

/// The deepest bracket nesting a formula may have.
pub const MAX_NESTING: usize = 32;

/// What a name in a formula stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Name {
    /// The input of this index (`x` of a mapping, `u` of a texture...).
    Var(usize),
    /// `pi` or `tau`.
    Constant,
    /// A function taking this many arguments.
    Function(usize),
}

/// A token of a formula: its kind and where it lies (byte range).
#[derive(Clone, Copy, Debug)]
pub(super) struct Token {
    /// `Some` for a name, `None` for numbers, operators and brackets.
    pub name: Option<Name>,
    /// Byte range in the text.
    pub span: (usize, usize),
}

/// A mistake found by the scan: its column (1-based, in characters) and what is wrong.
pub(super) type Mistake = (usize, String);

/// An open bracket: where, the function's name and arity if it opens a call, commas seen.
type Bracket<'a> = (usize, Option<(&'a str, usize)>, usize);

/// The end (byte) of the number starting at `i`: digits and points, then an exponent if one
/// follows (`e`, a sign, digits).
fn number_end(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
        i += 1;
    }
    if i < bytes.len() && matches!(bytes[i], b'e' | b'E') {
        let mut j = i + 1;
        if j < bytes.len() && matches!(bytes[j], b'+' | b'-') {
            j += 1;
        }
        if j < bytes.len() && bytes[j].is_ascii_digit() {
            i = j;
            while i < bytes.len() && bytes[i].is_ascii_digit() {
                i += 1;
            }
        }
    }
    i
}

/// What is wrong with the number `number` (a value was wanted there if `want_value`).
fn check_number(number: &str, want_value: bool) -> Result<(), String> {
    if number.parse::<f64>().is_err() || number.starts_with('.') || number.ends_with('.') {
        return Err(format!("`{number}` is not a number"));
    }
    if number.contains(['e', 'E']) {
        return Err(format!(
            "write `{number}` without an exponent (exmex reads plain decimals)"
        ));
    }
    if want_value {
        Ok(())
    } else {
        Err(format!("missing an operator before `{number}`"))
    }
}

/// The tokens of `text` over the inputs `vars`, or its first mistake.
pub(super) fn scan(text: &str, vars: &[&str]) -> Result<Vec<Token>, Mistake> {
    let column = |byte: usize| text[..byte].chars().count() + 1;
    let mut tokens = Vec::new();
    let mut open: Vec<Bracket> = Vec::new();
    let mut want_value = true;
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < text.len() {
        let c = text[i..].chars().next().unwrap_or(' ');
        let start = i;
        if c.is_whitespace() {
            i += c.len_utf8();
            continue;
        }
        if c.is_ascii_digit() || c == '.' {
            i = number_end(bytes, i);
            check_number(&text[start..i], want_value).map_err(|m| (column(start), m))?;
            want_value = false;
            tokens.push(Token {
                name: None,
                span: (start, i),
            });
            continue;
        }
        if c.is_ascii_alphabetic() || c == '_' {
            while i < text.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                i += 1;
            }
            let word = &text[start..i];
            if !want_value {
                return Err((
                    column(start),
                    format!("missing an operator before `{word}`"),
                ));
            }
            let name = classify(word, vars).ok_or_else(|| (column(start), unknown(word, vars)))?;
            match name {
                Name::Function(arity) => {
                    if let (2, Some((_, Some((outer, _)), _))) = (
                        arity,
                        open.iter().find(|(_, call, commas)| {
                            call.is_some_and(|(_, a)| a == 2) && *commas > 0
                        }),
                    ) {
                        return Err((
                            column(start),
                            format!(
                                "exmex cannot read {word} inside the second argument of {outer}: make it the first \
                                 (min and max take theirs in either order), e.g. min(max(y, z), x)"
                            ),
                        ));
                    }
                    let rest = text[i..].trim_start();
                    if !rest.starts_with('(') {
                        return Err((
                            column(start),
                            format!("`{word}` is a function: write {word}({})", args(arity)),
                        ));
                    }
                    let paren = text.len() - rest.len();
                    open.push((paren, Some((word, arity)), 0));
                    if open.len() > MAX_NESTING {
                        return Err((column(paren), nesting()));
                    }
                    i = paren + 1;
                }
                Name::Var(_) | Name::Constant => want_value = false,
            }
            tokens.push(Token {
                name: Some(name),
                span: (start, i),
            });
            continue;
        }
        i += c.len_utf8();
        match c {
            '(' => {
                if !want_value {
                    return Err((column(start), "missing an operator before `(`".into()));
                }
                open.push((start, None, 0));
                if open.len() > MAX_NESTING {
                    return Err((column(start), nesting()));
                }
            }
            ')' => {
                let Some((at, call, commas)) = open.pop() else {
                    return Err((column(start), "`)` without its `(`".into()));
                };
                if want_value {
                    return Err((column(start), "missing a value before `)`".into()));
                }
                if let Some((f, arity)) = call
                    && commas + 1 != arity
                {
                    return Err((column(at), arity_message(f, arity, commas + 1)));
                }
                want_value = false;
            }
            ',' => {
                match open.last_mut() {
                    Some((_, Some((f, arity)), commas)) => {
                        *commas += 1;
                        if *commas + 1 > *arity {
                            return Err((column(start), arity_message(f, *arity, *commas + 1)));
                        }
                    }
                    _ => {
                        return Err((
                            column(start),
                            "`,` outside a function's arguments (only atan2, min and max take two)"
                                .into(),
                        ));
                    }
                }
                if want_value {
                    return Err((column(start), "missing a value before `,`".into()));
                }
                want_value = true;
            }
            '+' | '-' => want_value = true, // binary, or unary before a value
            '*' | '/' | '^' => {
                if want_value {
                    return Err((column(start), format!("missing a value before `{c}`")));
                }
                want_value = true;
            }
            // Escaped (`\0`, `\u{1b}`): a control character echoed raw could clear or
            // recolour the terminal the message is printed on.
            _ => {
                return Err((
                    column(start),
                    format!("unexpected character `{}`", c.escape_debug()),
                ));
            }
        }
        tokens.push(Token {
            name: None,
            span: (start, i),
        });
    }
    if let Some((at, _, _)) = open.last() {
        return Err((column(*at), "this `(` is never closed".into()));
    }
    if want_value {
        let what = if tokens.is_empty() {
            "the formula is empty"
        } else {
            "missing a value at the end"
        };
        return Err((column(text.len()), what.into()));
    }
    Ok(tokens)
}

fn classify(word: &str, vars: &[&str]) -> Option<Name> {
    if let Some(i) = vars.iter().position(|v| *v == word) {
        Some(Name::Var(i))
    } else if CONSTANTS.contains(&word) {
        Some(Name::Constant)
    } else if UNARY.contains(&word) {
        Some(Name::Function(1))
    } else if BINARY.contains(&word) {
        Some(Name::Function(2))
    } else {
        None
    }
}

fn unknown(word: &str, vars: &[&str]) -> String {
    let hint = match word {
        "PI" | "Pi" => " (write pi)",
        "TAU" | "Tau" => " (write tau)",
        "signum" | "sgn" => " (write sign)",
        "arctan2" | "atan2f" => " (write atan2)",
        "arccos" => " (write acos)",
        "arcsin" => " (write asin)",
        "log" => " (write ln)",
        "pow" => " (write a ^ b)",
        _ => "",
    };
    format!(
        "unknown name `{word}`{hint}: the variables are {}, the constants pi and tau, the functions {}, {}",
        vars.join(", "),
        UNARY.join(", "),
        BINARY.join(", ")
    )
}

fn args(arity: usize) -> &'static str {
    if arity == 2 { "a, b" } else { "t" }
}

fn arity_message(f: &str, arity: usize, got: usize) -> String {
    if f == "clamp" {
        format!(
            "clamp takes one argument and clamps it into [0, 1] (given {got}); for other bounds write min(max(t, lo), hi)"
        )
    } else {
        let n = if arity == 2 {
            "two arguments"
        } else {
            "one argument"
        };
        format!("{f} takes {n}, not {got}")
    }
}

fn nesting() -> String {
    format!("brackets nested deeper than {MAX_NESTING}")
}
