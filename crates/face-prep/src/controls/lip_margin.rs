//! The marginal part of the orbicularis oris (pars marginalis): the fibres that run along each
//! lip under the vermilion and curl it in over the teeth (ARKit's `mouthRollUpper` /
//! `mouthRollLower`).
//!
//! The lips lie on the dental arch, so a band running along a lip is curved in the transverse
//! plane. A band under tension `T` with curvature `κ` presses on what it wraps with a force
//! `T·κ` per unit length toward its centre of curvature (the law of Laplace for a curved
//! membrane or tendon; Fung, *Biomechanics: Mechanical Properties of Living Tissues*, 2nd ed.,
//! 1993, §1.7): the contracted marginal part pulls its lip back toward the arch's centre, into
//! the mouth, while the peripheral part (the sphincter, [`crate::controls::force_controls`])
//! purses the mouth. The force is a traction on the lip's front and back elements within
//! [`MARGINAL_RING_MM`] of the lip margin, largest at the margin and in the lip's middle
//! ([`commissure_taper`]), and the control is
//! force-driven like the other muscles added after the thesis (free in every other response).
//!
//! The arch is the circle in the transverse (x-z) plane through the mouth loop's midline and
//! its two corners ([`arch_centre`]); a flat mouth (corners level with the midline) pulls
//! straight back.
//!
//! ```
//! use face_prep::{FaceRig, MuscleKind, RigParams, load_face};
//! let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
//!     .join("../../assets/mediapipe_canonical_4loop.obj");
//! let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
//! let k = rig.muscle_index(MuscleKind::OrbicularisOrisMarginalLower).unwrap();
//! assert!(rig.is_force_control(k));
//! assert!(!rig.muscles[k].front_chain.is_empty());
//! ```

use crate::controls::muscle_model::{
    CONTOUR_TAPER_MM, band_weight, contour_weight, distance_to_loop,
};
use crate::controls::muscles::Muscle;
use crate::frame::features::FeatureBoxes;
use crate::frame::orient::{FaceLoops, loop_xy};
use crate::shell::Shell;
use glam::{DVec2, DVec3};

/// Half-width of the marginal part, mm from the lip margin: the vermilion and the skin just
/// outside it (the pars marginalis lies under the vermilion, about 8 mm high in adults; Gray's
/// Anatomy, ch. 29).
pub const MARGINAL_RING_MM: f64 = 8.0;

/// Full contraction moves the lip margin in by at most this fraction of half the mouth width
/// (about the height of the lip, 10–14 mm, on an adult mouth 45–55 mm wide: a lip rolled in
/// over the teeth hides its vermilion).
pub const MARGINAL_STRAIN: f64 = 0.5;

/// Centre of the dental arch in the transverse plane (canonical x-z) from the mouth loop's 3D
/// points: the circle through the loop's midline (mean z of the points within a quarter of the
/// half-width of the middle) and its two corners (the loop's extreme x). `None` when the
/// corners are not behind the midline by 5 % of the half-width (a flat mouth: pull straight
/// back) or the loop has fewer than three points.
///
/// ```
/// use face_prep::lip_margin::arch_centre;
/// use glam::{DVec2, DVec3};
/// // A mouth on a circle of radius 30 about (0, 0, 70) in x-z.
/// let loop_points: Vec<DVec3> = (0..16)
///     .map(|i| {
///         let a = -0.8 + 1.6 * i as f64 / 15.0;
///         DVec3::new(30.0 * a.sin(), if i % 2 == 0 { 1.0 } else { -1.0 }, 70.0 + 30.0 * a.cos())
///     })
///     .collect();
/// let c = arch_centre(&loop_points).unwrap();
/// assert!(c.distance(DVec2::new(0.0, 70.0)) < 1.5);
/// // A flat mouth has no centre.
/// let flat: Vec<DVec3> = loop_points.iter().map(|p| DVec3::new(p.x, p.y, 100.0)).collect();
/// assert!(arch_centre(&flat).is_none());
/// ```
pub fn arch_centre(loop_points: &[DVec3]) -> Option<DVec2> {
    if loop_points.len() < 3 {
        return None;
    }
    let by_x = |a: &&DVec3, b: &&DVec3| a.x.total_cmp(&b.x);
    let left = loop_points.iter().min_by(by_x)?;
    let right = loop_points.iter().max_by(by_x)?;
    let half_width = 0.5 * (right.x - left.x);
    if half_width.is_nan() || half_width <= 0.0 {
        return None;
    }
    let cx = 0.5 * (left.x + right.x);
    let middle: Vec<f64> = loop_points
        .iter()
        .filter(|p| (p.x - cx).abs() <= 0.25 * half_width)
        .map(|p| p.z)
        .collect();
    if middle.is_empty() {
        return None;
    }
    let z_mid = middle.iter().sum::<f64>() / middle.len() as f64;
    let depth = z_mid - 0.5 * (left.z + right.z);
    if depth < 0.05 * half_width {
        return None;
    }
    let radius = (half_width * half_width + depth * depth) / (2.0 * depth);
    Some(DVec2::new(cx, z_mid - radius))
}

/// Traction pattern of the marginal part of one lip (`muscle`, placed by
/// [`crate::controls::force_controls::place_sphincter`] with [`MARGINAL_RING_MM`]) at
/// slider = +1: away from the dental arch's centre in the transverse plane (eversion; −1, the
/// contraction, pulls the lip back over the teeth), falling off from the lip margin across the
/// ring and faded in from the outer contour. Arbitrary magnitude: the response is scaled to
/// [`FaceRig::force_target`](crate::FaceRig::force_target).
pub(crate) fn marginal_traction(
    shell: &Shell,
    loops: &FaceLoops,
    mm_per_unit: f64,
    muscle: &Muscle,
) -> Vec<(u32, DVec3)> {
    let mouth = loop_xy(&shell.vertices, &loops.mouth);
    let mouth_3d: Vec<DVec3> = loops
        .mouth
        .iter()
        .filter_map(|&v| shell.vertices.get(v as usize).copied())
        .collect();
    let centre = arch_centre(&mouth_3d);
    let contour = loop_xy(&shell.vertices, &loops.face);
    let ring = MARGINAL_RING_MM / mm_per_unit;
    let (x_min, x_max) = mouth
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.x), hi.max(p.x))
        });
    let (cx, half_width) = (0.5 * (x_min + x_max), 0.5 * (x_max - x_min));
    muscle
        .elements()
        .map(|e| {
            let c = shell.centroid(e as usize);
            let outward = match centre {
                Some(o) => DVec3::new(c.x - o.x, 0.0, c.z - o.y).normalize_or(DVec3::Z),
                None => DVec3::Z,
            };
            let w = plateau_weight(distance_to_loop(c.truncate(), &mouth), ring)
                * commissure_taper(c.x - cx, half_width)
                * contour_weight(
                    distance_to_loop(c.truncate(), &contour),
                    CONTOUR_TAPER_MM / mm_per_unit,
                );
            (e, outward * w)
        })
        .collect()
}

/// Share of the marginal part's force at `distance` from the lip margin: 1 over the inner half
/// of the `ring` (the vermilion, under which the muscle lies evenly), then a raised cosine to 0
/// at its edge (a load peaked at the knife edge of the margin would crumple it).
fn plateau_weight(distance: f64, ring: f64) -> f64 {
    if distance <= 0.5 * ring {
        1.0
    } else {
        band_weight(distance - 0.5 * ring, 0.5 * ring)
    }
}

/// Share of the marginal part's force at `dx` from the mouth's middle (`half_width` = half
/// the mouth's width): 1 at the middle, falling as a quarter cosine to 0 at the corners (the
/// vermilion, and the muscle under it, thin out to nothing at the commissure).
///
/// ```
/// use face_prep::lip_margin::commissure_taper;
/// assert_eq!(commissure_taper(0.0, 25.0), 1.0);
/// assert!((commissure_taper(12.5, 25.0) - 0.5f64.sqrt()).abs() < 1e-12);
/// assert!(commissure_taper(-25.0, 25.0).abs() < 1e-12);
/// assert_eq!(commissure_taper(30.0, 25.0), 0.0);
/// assert_eq!(commissure_taper(1.0, 0.0), 0.0);
/// ```
pub fn commissure_taper(dx: f64, half_width: f64) -> f64 {
    if half_width.is_nan() || half_width <= 0.0 || dx.abs() >= half_width {
        return 0.0;
    }
    (std::f64::consts::FRAC_PI_2 * dx.abs() / half_width).cos()
}

/// Largest front-surface displacement, in the rig's units, of one lip's marginal part at full
/// contraction: [`MARGINAL_STRAIN`] × `strength` × half the mouth's width.
pub(crate) fn marginal_target(boxes: &FeatureBoxes, strength: f64) -> f64 {
    MARGINAL_STRAIN * strength * 0.5 * boxes.mouth.width()
}
