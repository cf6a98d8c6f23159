//! The wrap and the texel lookup with a hit's numbers substituted, for `texplore map` and the
//! GUI's inspector: the same functions the renderer runs ([`Wrap::coord`], [`Lookup::index`]),
//! in the precision the caller has (f32 in the inspector, f64 in `texplore map`).

use super::{Lookup, Real, Wrap};
use crate::mapping::explain_number;

/// (u, v) brought into the closed square [0, 1] x [0, 1] by the wrap modes `(wu, wv)` as the
/// renderer does it, with a line saying what happened to a coordinate outside (none for
/// coordinates inside: u = 1 and v = 1 stay, they are the last texel's). `None` for the
/// position when a coordinate is outside under [`Wrap::Black`] (no texel: black).
#[must_use]
pub fn explain_wrap<T: Real>(u: T, v: T, (wu, wv): (Wrap, Wrap)) -> (Option<(T, T)>, Vec<String>) {
    let mut lines = Vec::new();
    let mut one = |name: &str, t: T, wrap: Wrap| {
        let w = wrap.coord(t);
        match w {
            Some(w) if w.to_f64().to_bits() == t.to_f64().to_bits() => {}
            Some(w) => lines.push(format!(
                "{name} = {} is outside [0, 1]: {wrap} brings it to {name} = {}",
                explain_number(t.to_f64()),
                explain_number(w.to_f64())
            )),
            None => lines.push(format!(
                "{name} = {} is outside [0, 1]: {wrap} reads black there (no texel)",
                explain_number(t.to_f64())
            )),
        }
        w
    };
    let wrapped = one("u", u, wu);
    let wrapped_v = one("v", v, wv);
    (wrapped.zip(wrapped_v), lines)
}

/// The lines that take (u, v), already in [0, 1] (see [`explain_wrap`]), to a texel column and
/// row (counted from the bottom, v up) of an `hres` x `vres` image: [`Lookup::index`], the
/// renderer's, with its numbers.
#[must_use]
pub fn explain_lookup<T: Real>(u: T, v: T, hres: u32, vres: u32, lookup: Lookup) -> Vec<String> {
    let (c, r) = (lookup.index(u, hres), lookup.index(v, vres));
    let (un, vn) = (explain_number(u.to_f64()), explain_number(v.to_f64()));
    match lookup {
        Lookup::Lecture => vec![
            format!(
                "column = (int)((hres - 1) u) = (int)({} x {un}) = {c}",
                hres - 1
            ),
            format!(
                "row = (int)((vres - 1) v) = (int)({} x {vn}) = {r}",
                vres - 1
            ),
        ],
        Lookup::Centred => vec![
            format!(
                "column = min(floor(u hres), hres - 1) = min(floor({un} x {hres}), {}) = {c}",
                hres - 1
            ),
            format!(
                "row = min(floor(v vres), vres - 1) = min(floor({vn} x {vres}), {}) = {r}",
                vres - 1
            ),
        ],
    }
}
