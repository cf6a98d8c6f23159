//! Cameras: pinhole, fisheye, spherical panorama and orthographic (the book's chapter 9-11
//! cameras), each turning a film position into a world-space ray.

use crate::math::lanes::{F, M, MAX_LANES, V3, from_array, to_array};
use crate::math::{Quat, Ray, RayDifferential, Vec2, Vec3, Vec3A};
use pulp::Simd;

/// A camera with its orthonormal frame already computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// World-space eye position, where every primary ray starts.
    pub eye: Vec3A,
    /// Right, up and backward axes (u, v, w in the book: w points from the look-at to the eye).
    pub frame: [Vec3A; 3],
    /// How film positions become directions in the `frame`, angles in radians.
    pub projection: Projection,
    /// Film width in pixels.
    pub width: u32,
    /// Film height in pixels.
    pub height: u32,
    /// The pinhole's film-plane size of one pixel, tan(fov_y / 2) 2 / height, computed once
    /// here instead of a `tan` per ray (same value, so the same images).
    pixel_scale: f32,
}

/// How film positions become directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Perspective with a vertical field of view (radians).
    Pinhole {
        /// Vertical field of view in radians.
        fov_y: f32,
    },
    /// Equidistant fisheye: the angle from the view axis grows linearly to `psi_max` at the
    /// edge of the inscribed circle; outside it nothing is seen.
    Fisheye {
        /// Half-angle at the circle's edge, radians.
        psi_max: f32,
    },
    /// Equirectangular panorama: x spans longitude +-`lambda_max`, y latitude +-`psi_max`.
    Spherical {
        /// Half horizontal angle, radians.
        lambda_max: f32,
        /// Half vertical angle, radians.
        psi_max: f32,
    },
    /// Parallel projection: every ray runs along the view axis, from a point on the plane
    /// through the eye perpendicular to it; the film spans `height` world units vertically
    /// (the width follows the aspect ratio).
    Orthographic {
        /// Height of the film in world units.
        height: f32,
    },
}

impl Camera {
    /// A camera at `eye` looking at `look_at` with `up` as the approximate up direction.
    #[must_use]
    pub fn new(
        eye: Vec3A,
        look_at: Vec3A,
        up: Vec3A,
        projection: Projection,
        width: u32,
        height: u32,
    ) -> Self {
        let w = (eye - look_at).normalize_or(Vec3A::Z);
        let mut u = up.cross(w);
        if u.length_squared() < 1e-12 {
            // Looking straight along `up`: pick any perpendicular (the book's singularity fix).
            u = if w.x.abs() < 0.9 {
                Vec3A::X.cross(w)
            } else {
                Vec3A::Z.cross(w)
            };
        }
        let u = u.normalize();
        let v = w.cross(u);
        let pixel_scale = match projection {
            Projection::Pinhole { fov_y } => (fov_y * 0.5).tan() * 2.0 / height as f32,
            Projection::Orthographic { height: film } => film / height as f32,
            Projection::Fisheye { .. } | Projection::Spherical { .. } => 0.0,
        };
        Self {
            eye,
            frame: [u, v, w],
            projection,
            width,
            height,
            pixel_scale,
        }
    }

    /// The direction (unnormalised) through film position `pos` in pixels (x right, y down,
    /// (0, 0) the top-left corner), or `None` where the projection sees nothing: the width-1
    /// instance of [`Camera::rays_lanes`].
    #[must_use]
    #[inline]
    pub fn direction(&self, pos: Vec2) -> Option<Vec3A> {
        let (_, d, seen) = self.rays_lanes(pulp::Scalar, pos.x, pos.y);
        seen.then(|| d.vec())
    }

    /// Where the ray through film position `pos` starts: the eye, or for the orthographic
    /// camera the point of the film plane (through the eye) under `pos`.
    #[must_use]
    #[inline]
    pub fn origin(&self, pos: Vec2) -> Vec3A {
        match self.projection {
            Projection::Orthographic { .. } => self.rays_lanes(pulp::Scalar, pos.x, pos.y).0.vec(),
            _ => self.eye,
        }
    }

    /// Film positions as offsets from the film's centre in the image plane (pinhole and
    /// orthographic): ((px - w / 2) scale, (h / 2 - py) scale).
    #[inline(always)]
    fn centred<S: Simd>(&self, s: S, px: F<S>, py: F<S>) -> (F<S>, F<S>) {
        let (w, h) = (self.width as f32, self.height as f32);
        let scale = s.splat_f32s(self.pixel_scale);
        (
            s.mul_f32s(s.sub_f32s(px, s.splat_f32s(0.5 * w)), scale),
            s.mul_f32s(s.sub_f32s(s.splat_f32s(0.5 * h), py), scale),
        )
    }

    /// The rays through film positions (`px`, `py`) per lane, written once for every width:
    /// origins, unnormalised directions, and which lanes the projection sees (a fisheye sees
    /// only its disc). The pinhole and orthographic projections are lane arithmetic; the
    /// fisheye's and the panorama's sines and cosines are libm's, per lane.
    #[must_use]
    #[inline(always)]
    pub fn rays_lanes<S: Simd>(&self, s: S, px: F<S>, py: F<S>) -> (V3<S>, V3<S>, M<S>) {
        let (w, h) = (self.width as f32, self.height as f32);
        let [u, v, back] = self.frame;
        let (vu, vv, vback) = (V3::splat(s, u), V3::splat(s, v), V3::splat(s, back));
        let eye = V3::splat(s, self.eye);
        let all = crate::math::lanes::mask_splat(s, true);
        match self.projection {
            Projection::Pinhole { .. } => {
                let (x, y) = self.centred(s, px, py);
                (eye, plane(s, &vu, &vv, x, y).sub(s, &vback), all)
            }
            Projection::Orthographic { .. } => {
                let (x, y) = self.centred(s, px, py);
                // eye + x u + y v, summed left to right.
                let o = eye.add(s, &vu.scale(s, x)).add(s, &vv.scale(s, y));
                (o, vback.neg(s), all)
            }
            Projection::Fisheye { psi_max } => {
                let radius = s.splat_f32s(0.5 * w.min(h));
                let x = s.div_f32s(s.sub_f32s(px, s.splat_f32s(0.5 * w)), radius);
                let y = s.div_f32s(s.sub_f32s(s.splat_f32s(0.5 * h), py), radius);
                let r2 = s.add_f32s(s.mul_f32s(x, x), s.mul_f32s(y, y));
                let seen = s.not_m32s(s.greater_than_f32s(r2, s.splat_f32s(1.0)));
                let r = s.sqrt_f32s(r2);
                let psi = s.mul_f32s(r, s.splat_f32s(psi_max));
                let (sin_psi, cos_psi) = sin_cos(s, psi);
                let off = s.greater_than_f32s(r, s.splat_f32s(0.0));
                let sa = s.select_f32s(off, s.div_f32s(y, r), s.splat_f32s(0.0));
                let ca = s.select_f32s(off, s.div_f32s(x, r), s.splat_f32s(1.0));
                let d = plane(
                    s,
                    &vu,
                    &vv,
                    s.mul_f32s(sin_psi, ca),
                    s.mul_f32s(sin_psi, sa),
                )
                .sub(s, &vback.scale(s, cos_psi));
                (eye, d, seen)
            }
            Projection::Spherical {
                lambda_max,
                psi_max,
            } => {
                let x = s.sub_f32s(
                    s.mul_f32s(s.div_f32s(px, s.splat_f32s(w)), s.splat_f32s(2.0)),
                    s.splat_f32s(1.0),
                );
                let y = s.sub_f32s(
                    s.splat_f32s(1.0),
                    s.mul_f32s(s.div_f32s(py, s.splat_f32s(h)), s.splat_f32s(2.0)),
                );
                let (sl, cl) = sin_cos(s, s.mul_f32s(x, s.splat_f32s(lambda_max)));
                let (sp, cp) = sin_cos(s, s.mul_f32s(y, s.splat_f32s(psi_max)));
                let d = plane(s, &vu, &vv, s.mul_f32s(cp, sl), sp)
                    .sub(s, &vback.scale(s, s.mul_f32s(cp, cl)));
                (eye, d, all)
            }
        }
    }

    /// The ray through `pos` without differentials: one direction instead of three, for scenes
    /// whose filters need no footprint.
    #[must_use]
    #[inline]
    pub fn primary_ray(&self, pos: Vec2) -> Option<Ray> {
        self.direction(pos).map(|d| Ray::new(self.origin(pos), d))
    }

    /// The ray through `pos`, with its neighbours one pixel right and one pixel down as ray
    /// differentials scaled by `spacing` (1 for one sample per pixel; smaller when a pixel is
    /// covered by several samples).
    #[must_use]
    #[inline]
    pub fn ray(&self, pos: Vec2, spacing: f32) -> Option<(Ray, RayDifferential)> {
        let d = self.direction(pos)?;
        let dx = self.direction(pos + Vec2::new(spacing, 0.0)).unwrap_or(d);
        let dy = self.direction(pos + Vec2::new(0.0, spacing)).unwrap_or(d);
        let o = self.origin(pos);
        let ray = Ray::new(o, d);
        // Differentials are expressed per whole pixel.
        let inv = 1.0 / spacing;
        let (ox, oy) = if matches!(self.projection, Projection::Orthographic { .. }) {
            let [u, v, _] = self.frame;
            (o + u * self.pixel_scale, o - v * self.pixel_scale)
        } else {
            (o, o)
        };
        let diff = RayDifferential {
            rx_origin: ox,
            rx_dir: d + (dx - d) * inv,
            ry_origin: oy,
            ry_dir: d + (dy - d) * inv,
        };
        Some((ray, diff))
    }

    /// The rays through film positions (`px`, `py`) per lane with their ray differentials,
    /// for samples standing for cells `cx` x `cy` pixels: [`Camera::ray`] at the cell's shorter
    /// side, its offsets then stretched to `cx` and `cy` (each at least `min_scale`). The same
    /// operations in the same order as the scalar code, lane by lane (the render's
    /// `footprint_ray` is its width-1 instance).
    #[must_use]
    #[inline(always)]
    #[allow(clippy::similar_names)] // rx_ and ry_, as in `RayDifferential`
    pub fn footprint_rays_lanes<S: Simd>(
        &self,
        s: S,
        px: F<S>,
        py: F<S>,
        cx: F<S>,
        cy: F<S>,
        min_scale: f32,
    ) -> FootprintRays<S> {
        let spacing = s.min_f32s(cx, cy);
        let zero = s.splat_f32s(0.0);
        let (o, d, seen) = self.rays_lanes(s, px, py);
        let (_, dx, seen_x) = self.rays_lanes(s, s.add_f32s(px, spacing), s.add_f32s(py, zero));
        let (_, dy, seen_y) = self.rays_lanes(s, s.add_f32s(px, zero), s.add_f32s(py, spacing));
        let dx = V3::select(s, seen_x, &dx, &d);
        let dy = V3::select(s, seen_y, &dy, &d);
        // Differentials are expressed per whole pixel.
        let inv = s.div_f32s(s.splat_f32s(1.0), spacing);
        let (ox, oy) = if matches!(self.projection, Projection::Orthographic { .. }) {
            let [u, v, _] = self.frame;
            (
                o.add(s, &V3::splat(s, u * self.pixel_scale)),
                o.sub(s, &V3::splat(s, v * self.pixel_scale)),
            )
        } else {
            (o, o)
        };
        let rx_dir = d.add(s, &dx.sub(s, &d).scale(s, inv));
        let ry_dir = d.add(s, &dy.sub(s, &d).scale(s, inv));
        // Stretched to the cell's sides.
        let min = s.splat_f32s(min_scale);
        let (sx, sy) = (s.max_f32s(cx, min), s.max_f32s(cy, min));
        FootprintRays {
            rx_origin: o.add(s, &ox.sub(s, &o).scale(s, sx)),
            rx_dir: d.add(s, &rx_dir.sub(s, &d).scale(s, sx)),
            ry_origin: o.add(s, &oy.sub(s, &o).scale(s, sy)),
            ry_dir: d.add(s, &ry_dir.sub(s, &d).scale(s, sy)),
            o,
            d,
            seen,
        }
    }
}

/// Rays with their ray differentials per lane ([`Camera::footprint_rays_lanes`]).
#[derive(Clone, Copy, Debug)]
pub struct FootprintRays<S: Simd> {
    /// Origins.
    pub o: V3<S>,
    /// Directions (not normalised).
    pub d: V3<S>,
    /// The lanes the projection sees.
    pub seen: M<S>,
    /// The neighbour one cell to the right: origin and direction.
    pub rx_origin: V3<S>,
    /// See `rx_origin`.
    pub rx_dir: V3<S>,
    /// The neighbour one cell down: origin and direction.
    pub ry_origin: V3<S>,
    /// See `ry_origin`.
    pub ry_dir: V3<S>,
}

/// Orbits `eye` about `look_at`: `yaw` radians about `up`, then `pitch` radians up or down,
/// keeping the distance and stopping 1 degree short of the poles (where `up` stops defining a
/// frame).
#[must_use]
pub fn orbit(eye: Vec3, look_at: Vec3, up: Vec3, yaw: f32, pitch: f32) -> Vec3 {
    let up = up.try_normalize().unwrap_or(Vec3::Y);
    let offset = eye - look_at;
    let dist = offset.length();
    if dist == 0.0 || !dist.is_finite() {
        return eye;
    }
    let dir = offset / dist;
    let elevation = dir.dot(up).clamp(-1.0, 1.0).asin();
    let limit = std::f32::consts::FRAC_PI_2 - 1f32.to_radians();
    let new_elevation = (elevation + pitch).clamp(-limit, limit);
    let flat = (dir - up * dir.dot(up))
        .try_normalize()
        .unwrap_or_else(|| up.any_orthonormal_vector());
    let flat = Quat::from_axis_angle(up, yaw) * flat;
    look_at + (flat * new_elevation.cos() + up * new_elevation.sin()) * dist
}

/// Moves the eye toward `look_at` by the factor `scale` of the distance (below 1 comes closer),
/// never closer than `min_distance`.
#[must_use]
pub fn dolly(eye: Vec3, look_at: Vec3, scale: f32, min_distance: f32) -> Vec3 {
    let offset = eye - look_at;
    let dist = offset.length();
    if dist == 0.0 || !scale.is_finite() || scale <= 0.0 {
        return eye;
    }
    look_at + offset * ((dist * scale).max(min_distance) / dist)
}

/// Zooming in stops when the gap between the eye and the surface in front of it is this
/// fraction of the eye's distance to the look-at point (see [`zoom_toward_surface`]).
pub const ZOOM_MIN_GAP: f32 = 0.05;

/// Where zooming by `scale` (below 1 comes closer) puts the eye, when the nearest surface on
/// the line from `eye` to `look_at` is `surface` away (`None`: nothing lies between them).
///
/// As viewers do, the zoom slows down near the surface and stops short of it: it scales the gap
/// to that surface rather than the distance to the look-at point, so each wheel notch covers
/// the same fraction of what is left and the eye never reaches the surface. Zooming in stops
/// once the gap is [`ZOOM_MIN_GAP`] of the eye's distance to the look-at point (a unit sphere
/// looked at from its centre: 0.053 above its surface), and never below 1e-4 of the
/// coordinates' magnitude (at least 1e-4), where f32 positions stop telling the eye from the
/// surface. With nothing in between, the distance to the look-at point scales as [`dolly`]
/// does, down to 1e-3.
#[must_use]
pub fn zoom_toward_surface(eye: Vec3, look_at: Vec3, surface: Option<f32>, scale: f32) -> Vec3 {
    let to_target = look_at - eye;
    let dist = to_target.length();
    if dist <= 0.0 || !dist.is_finite() || scale <= 0.0 || !scale.is_finite() {
        return eye;
    }
    let Some(gap) = surface.filter(|t| t.is_finite() && *t >= 0.0 && *t <= dist) else {
        return dolly(eye, look_at, scale, 1e-3);
    };
    // The look-at point lies `behind` past the surface: gap >= f (gap + behind), solved for gap.
    let behind = dist - gap;
    let magnitude = eye
        .abs()
        .max_element()
        .max(look_at.abs().max_element())
        .max(1.0);
    let floor = (ZOOM_MIN_GAP * behind / (1.0 - ZOOM_MIN_GAP)).max(1e-4 * magnitude);
    let new_gap = if scale < 1.0 {
        // Never backwards: an eye already nearer than the floor stays where it is.
        (gap * scale).max(floor.min(gap))
    } else {
        gap * scale
    };
    eye + to_target * ((gap - new_gap) / dist)
}

/// The world-space shift of eye and look-at that moves the view by (`dx`, `dy`) of the distance
/// to the look-at point, along the camera's right and up axes.
#[must_use]
pub fn pan_offset(eye: Vec3, look_at: Vec3, up: Vec3, dx: f32, dy: f32) -> Vec3 {
    let cam = Camera::new(
        eye.into(),
        look_at.into(),
        up.into(),
        Projection::Pinhole { fov_y: 1.0 },
        1,
        1,
    );
    let dist = (eye - look_at).length();
    Vec3::from(cam.frame[0] * dx + cam.frame[1] * dy) * dist
}

/// x u + y v per lane (each a vector times a number), as glam sums `x * u + y * v`.
#[inline(always)]
fn plane<S: Simd>(s: S, u: &V3<S>, v: &V3<S>, x: F<S>, y: F<S>) -> V3<S> {
    u.scale(s, x).add(s, &v.scale(s, y))
}

/// `x.sin_cos()` per lane (libm's, lane by lane).
#[inline(always)]
fn sin_cos<S: Simd>(s: S, x: F<S>) -> (F<S>, F<S>) {
    let xs = to_array::<S>(x);
    let (mut sn, mut cs) = ([0.0; MAX_LANES], [0.0; MAX_LANES]);
    for i in 0..S::F32_LANES {
        (sn[i], cs[i]) = xs[i].sin_cos();
    }
    let _ = s;
    (from_array::<S>(&sn), from_array::<S>(&cs))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pinhole_centre_looks_at_target_and_fov_is_vertical() {
        let cam = Camera::new(
            Vec3A::new(0.0, 0.0, 5.0),
            Vec3A::ZERO,
            Vec3A::Y,
            Projection::Pinhole {
                fov_y: 90f32.to_radians(),
            },
            200,
            100,
        );
        let d = cam.direction(Vec2::new(100.0, 50.0)).unwrap().normalize();
        assert!((d - Vec3A::NEG_Z).length() < 1e-6);
        // Top edge at 45 degrees up.
        let d = cam.direction(Vec2::new(100.0, 0.0)).unwrap().normalize();
        assert!((d.y - std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-5);
        // x right is +x in the world.
        assert!(cam.direction(Vec2::new(199.0, 50.0)).unwrap().x > 0.0);
    }

    #[test]
    fn looking_straight_down_has_a_frame() {
        let cam = Camera::new(
            Vec3A::Y * 5.0,
            Vec3A::ZERO,
            Vec3A::Y,
            Projection::Pinhole { fov_y: 1.0 },
            10,
            10,
        );
        assert!(
            cam.frame
                .iter()
                .all(|a| a.is_finite() && (a.length() - 1.0).abs() < 1e-5)
        );
    }

    #[test]
    fn fisheye_and_spherical() {
        let fish = Camera::new(
            Vec3A::ZERO,
            Vec3A::NEG_Z,
            Vec3A::Y,
            Projection::Fisheye {
                psi_max: std::f32::consts::PI,
            },
            100,
            100,
        );
        assert!(fish.direction(Vec2::new(0.0, 0.0)).is_none());
        let d = fish.direction(Vec2::new(100.0, 50.0)).unwrap();
        assert!((d - Vec3A::Z).length() < 1e-5, "{d:?}"); // rim of a 360 fisheye looks backwards
        let pano = Camera::new(
            Vec3A::ZERO,
            Vec3A::NEG_Z,
            Vec3A::Y,
            Projection::Spherical {
                lambda_max: std::f32::consts::PI,
                psi_max: std::f32::consts::FRAC_PI_2,
            },
            200,
            100,
        );
        let d = pano.direction(Vec2::new(100.0, 0.0)).unwrap();
        assert!((d - Vec3A::Y).length() < 1e-5);
        let d = pano.direction(Vec2::new(150.0, 50.0)).unwrap();
        assert!((d - Vec3A::X).length() < 1e-5);
    }

    #[test]
    fn orbit_keeps_distance_and_turns_about_up() {
        let eye = Vec3::new(0.0, 0.0, 4.0);
        let e = orbit(eye, Vec3::ZERO, Vec3::Y, std::f32::consts::FRAC_PI_2, 0.0);
        assert!((e - Vec3::new(4.0, 0.0, 0.0)).length() < 1e-5, "{e}");
        let e = orbit(eye, Vec3::ZERO, Vec3::Y, 0.0, 3.0);
        assert!(
            (e.length() - 4.0).abs() < 1e-5 && e.y < 4.0 && e.y > 3.99,
            "{e}"
        );
        let d = dolly(eye, Vec3::ZERO, 0.5, 0.1);
        assert!((d - Vec3::new(0.0, 0.0, 2.0)).length() < 1e-6);
        assert!((dolly(eye, Vec3::ZERO, 1e-9, 0.1).length() - 0.1).abs() < 1e-6);
        let p = pan_offset(eye, Vec3::ZERO, Vec3::Y, 0.25, 0.0);
        assert!((p - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-5, "{p}");
    }

    #[test]
    fn zoom_slows_down_near_the_surface_and_stops_short_of_it() {
        // The unit sphere looked at from its centre, 3.6 away (the Earth preset).
        let (mut eye, look_at) = (Vec3::new(0.0, 0.0, 3.6), Vec3::ZERO);
        let gap = |e: Vec3| e.length() - 1.0;
        let mut steps = Vec::new();
        for _ in 0..200 {
            let next = zoom_toward_surface(eye, look_at, Some(gap(eye)), 0.9);
            steps.push((eye - next).length());
            eye = next;
        }
        // Each notch covers 10 % of the gap left, so the steps shrink near the surface...
        assert!((steps[0] - 0.26).abs() < 1e-5, "{}", steps[0]);
        assert!(steps[10] < steps[0] * 0.4, "{steps:?}");
        // ... and the eye stops 5 % of its distance to the centre above the surface.
        let stop = 1.0 / (1.0 - ZOOM_MIN_GAP);
        assert!((eye.length() - stop).abs() < 1e-4, "{eye}");
        assert!(eye.x == 0.0 && eye.y == 0.0, "{eye}");
        // Zooming out doubles the gap.
        let out = zoom_toward_surface(eye, look_at, Some(gap(eye)), 2.0);
        assert!((gap(out) - 2.0 * gap(eye)).abs() < 1e-5, "{out}");
    }

    #[test]
    fn zoom_with_no_surface_before_the_look_at_point_goes_toward_it() {
        let eye = Vec3::new(0.0, 0.0, 4.0);
        // Nothing in between, or a surface past the look-at point: the distance halves.
        for surface in [None, Some(6.0), Some(f32::INFINITY), Some(f32::NAN)] {
            let e = zoom_toward_surface(eye, Vec3::ZERO, surface, 0.5);
            assert!(
                (e - Vec3::new(0.0, 0.0, 2.0)).length() < 1e-6,
                "{surface:?}: {e}"
            );
        }
        // The look-at point on the surface (a plane's): the eye stops 1e-4 above it.
        let mut e = Vec3::new(0.0, 2.0, 0.0);
        for _ in 0..500 {
            e = zoom_toward_surface(e, Vec3::ZERO, Some(e.y), 0.9);
        }
        assert!(e.y >= 0.99e-4 && e.y < 1.1e-4, "{e}");
        // Nothing to zoom toward, or no factor: the eye stays.
        assert_eq!(zoom_toward_surface(eye, eye, Some(1.0), 0.5), eye);
        assert_eq!(
            zoom_toward_surface(eye, Vec3::ZERO, Some(1.0), f32::NAN),
            eye
        );
    }
}
