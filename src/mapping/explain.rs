//! The lecture's formulas with a hit point's numbers substituted, for `texplore map` and the
//! GUI's inspector.

use super::Mapping;
use crate::math::{PI, TAU, Vec3A};
use crate::texture::Lookup;

/// The formula lines that take local hit point `p` to (u, v) under `mapping`.
#[must_use]
pub fn explain_mapping(mapping: Mapping, p: Vec3A) -> Vec<String> {
    let mut out = Vec::new();
    let len = p.length();
    let n = if len > 0.0 && len.is_finite() {
        p / len
    } else {
        p
    };
    let on_unit = (len - 1.0).abs() < 1e-4;
    let (x, y, z) = (p.x, p.y, p.z);
    let uv = mapping.map_point(p).uv;
    let phi_lines = |out: &mut Vec<String>, x: f32, z: f32| {
        let raw = x.atan2(z);
        out.push(format!(
            "phi = atan2(x, z) = atan2({x:.4}, {z:.4}) = {raw:.4} rad"
        ));
        if raw < 0.0 {
            out.push(format!(
                "phi < 0, so phi += 2 pi: phi = {:.4} rad",
                raw + TAU
            ));
        }
        out.push(format!("u = phi / (2 pi) = {:.4}", uv.x));
    };
    match mapping {
        Mapping::Rectangular => {
            out.push(format!("u = (z + 1) / 2 = ({z:.4} + 1) / 2 = {:.4}", uv.x));
            out.push(format!("v = (x + 1) / 2 = ({x:.4} + 1) / 2 = {:.4}", uv.y));
        }
        Mapping::Cylindrical => {
            phi_lines(&mut out, x, z);
            out.push(format!("v = (y + 1) / 2 = ({y:.4} + 1) / 2 = {:.4}", uv.y));
        }
        Mapping::Spherical | Mapping::Uv => {
            if !on_unit {
                out.push(format!(
                    "|p| = {len:.4}: normalised to the unit sphere, ({:.4}, {:.4}, {:.4})",
                    n.x, n.y, n.z
                ));
            }
            phi_lines(&mut out, n.x, n.z);
            let theta = (1.0 - uv.y) * PI;
            out.push(format!(
                "theta = acos(y) = acos({:.4}) = {theta:.4} rad",
                n.y.clamp(-1.0, 1.0)
            ));
            out.push(format!("v = 1 - theta / pi = {:.4}", uv.y));
            if mapping == Mapping::Uv {
                out.push("(uv: this shape carries no (u, v) of its own, so its natural spherical map is used)".into());
            }
        }
        Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall => {
            if !on_unit {
                out.push(format!(
                    "|p| = {len:.4}: normalised to the unit sphere, ({:.4}, {:.4}, {:.4})",
                    n.x, n.y, n.z
                ));
            }
            let flip = mapping == Mapping::Panoramic;
            let zz = if flip { -n.z } else { n.z };
            let d = (n.x * n.x + n.y * n.y).sqrt();
            let alpha = d.atan2(zz);
            if flip {
                out.push(format!(
                    "alpha = acos(-z) = acos({zz:.4}) = {alpha:.4} rad (panoramic: z flipped)"
                ));
            } else {
                out.push(format!("alpha = acos(z) = acos({zz:.4}) = {alpha:.4} rad"));
            }
            if d > 0.0 {
                out.push(format!("sin beta = y / sqrt(x^2 + y^2) = {:.4}, cos beta = x / sqrt(x^2 + y^2) = {:.4}", n.y / d, n.x / d));
            } else {
                out.push(
                    "x = y = 0: beta is undefined (the lecture divides by zero); the limit is used"
                        .into(),
                );
            }
            let r = if mapping == Mapping::MirrorBall {
                let r = (alpha * 0.5).sin();
                out.push(format!("r = sin(alpha / 2) = {r:.4} (mirror ball)"));
                r
            } else {
                let r = alpha / PI;
                out.push(format!("r = alpha / pi = {r:.4}"));
                r
            };
            let _ = r;
            out.push(format!("u = (1 + r cos beta) / 2 = {:.4}", uv.x));
            out.push(format!("v = (1 + r sin beta) / 2 = {:.4}", uv.y));
        }
    }
    out
}

/// The lines that take (u, v) to a texel column and row (counted from the bottom, v up).
#[must_use]
pub fn explain_lookup(u: f32, v: f32, hres: u32, vres: u32, lookup: Lookup) -> Vec<String> {
    let (c, r) = (
        lookup.index(u.clamp(0.0, 1.0), hres),
        lookup.index(v.clamp(0.0, 1.0), vres),
    );
    match lookup {
        Lookup::Lecture => vec![
            format!(
                "column = (int)((hres - 1) u) = (int)({} x {u:.4}) = {c}",
                hres - 1
            ),
            format!(
                "row = (int)((vres - 1) v) = (int)({} x {v:.4}) = {r}",
                vres - 1
            ),
        ],
        Lookup::Centred => vec![
            format!(
                "column = min(floor(u hres), hres - 1) = min(floor({u:.4} x {hres}), {}) = {c}",
                hres - 1
            ),
            format!(
                "row = min(floor(v vres), vres - 1) = min(floor({v:.4} x {vres}), {}) = {r}",
                vres - 1
            ),
        ],
    }
}
