//! How a muscle's contraction becomes prescribed displacements of shell elements.
//!
//! Two models ([`MuscleModel`]):
//!
//! - [`MuscleModel::Thesis`] — the thesis rule, kept bit for bit: each element of a ray-projected
//!   chain moves toward the next point of the chain's path ([`crate::controls::muscles::muscle_pattern`]),
//!   a rigid slide by one element spacing. It has no physical unit and depends on the mesh.
//! - [`MuscleModel::Anatomical`] (default) — each muscle runs from a bony **origin** to a skin
//!   **insertion** ([`crate::controls::anatomy`]). At full contraction it shortens by `max_strain` of its
//!   length, uniformly, so a point of the muscle at arc length `s` from the origin (measured
//!   along the face surface) moves `max_strain × s` toward the origin: 0 at the bone, largest
//!   at the insertion, whatever the tessellation. The tissue it drags is a band about the
//!   muscle's line, `half_width_mm` wide to each side, whose displacement falls off smoothly
//!   across the band (raised cosine, 1 on the line); only the band's core
//!   ([`AnatomicalParams::core_fraction`] of the half-width) is prescribed, and everything
//!   else — the lip beyond the mouth corner, the skin around the band — follows through the
//!   elastic solve.
//!
//! Slider convention (both models, as in the thesis): a slider in [−1, 1]; −1 is full
//! contraction, +1 the opposite (the muscle lengthened by the same strain: linear, so one
//! solve per muscle gives the exact basis).
//!
//! An edited muscle (e.g. from a thesis-format muscle file) keeps working in the anatomical
//! model: its elements are the band (front chain on the skin, back chain in the deep layer);
//! a standard muscle (its name is one of the table's, [`crate::MuscleKind`]) takes its origin and insertion from the
//! feature boxes, any other muscle from its chain's ends: the first element is the insertion,
//! the last the origin (the thesis's start and end), with [`CUSTOM_HALF_WIDTH_MM`] and
//! [`CUSTOM_MAX_STRAIN`].

use crate::bvh::TriangleBvh;
use crate::controls::anatomy::Attachment;
use crate::controls::muscle_kind::attachment;
use crate::controls::muscles::Muscle;
use crate::frame::features::FeatureBoxes;
use crate::frame::orient::{FaceLoops, loop_xy};
use crate::shell::{ElementTag, Shell};
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};
use std::collections::HashSet;

/// Distance from the outer contour, mm, over which every prescribed displacement fades in from
/// zero (smoothstep): where the mesh ends, the face is held by the fixed rim, so the contour
/// stays put (a mesh's cut line is no anatomical boundary a muscle could pull).
pub const CONTOUR_TAPER_MM: f64 = 15.0;

/// Half-width of a custom (non-standard) muscle's band, mm.
pub const CUSTOM_HALF_WIDTH_MM: f64 = 8.0;
/// Shortening strain at full contraction of a custom muscle.
pub const CUSTOM_MAX_STRAIN: f64 = 0.2;

/// Which rule turns a muscle into prescribed displacements.
///
/// ```
/// use face_prep::muscle_model::MuscleModel;
/// assert_eq!(MuscleModel::default(), MuscleModel::Anatomical);
/// assert_eq!(MuscleModel::parse("thesis"), Some(MuscleModel::Thesis));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[non_exhaustive]
pub enum MuscleModel {
    /// The thesis's chains, each element moved by one element spacing (reproducible).
    Thesis,
    /// Origin on bone, insertion in skin, shortening as a strain, in physical units.
    #[default]
    Anatomical,
}

impl MuscleModel {
    /// Parses `thesis` or `anatomical`.
    pub fn parse(s: &str) -> Option<MuscleModel> {
        match s.to_ascii_lowercase().as_str() {
            "thesis" => Some(MuscleModel::Thesis),
            "anatomical" => Some(MuscleModel::Anatomical),
            _ => None,
        }
    }
}

/// Which layer of the shell a muscle's band is prescribed on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[non_exhaustive]
pub enum BandLayer {
    /// The skin (front elements).
    Front,
    /// The deep layer (back elements); the skin follows through the tissue.
    Back,
    /// Both.
    Both,
}

/// Parameters of the anatomical model.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AnatomicalParams {
    /// Scales every muscle's maximum shortening. Default 1.
    pub strength: f64,
    /// Fraction of a band's half-width that is prescribed (the rest follows elastically).
    /// Default 0.6.
    pub core_fraction: f64,
    /// Layer the bands are prescribed on. Default [`BandLayer::Both`].
    pub layer: BandLayer,
}

impl Default for AnatomicalParams {
    fn default() -> Self {
        AnatomicalParams {
            strength: 1.0,
            core_fraction: 0.6,
            layer: BandLayer::Both,
        }
    }
}

/// A muscle's line on the face: the origin → insertion segment of the front plane, lifted onto
/// the front surface, with arc lengths measured along the surface from the origin.
#[derive(Clone, Debug, PartialEq)]
pub struct MusclePath {
    /// Origin and insertion in the front plane.
    pub origin: DVec2,
    /// Insertion in the front plane.
    pub insertion: DVec2,
    /// Surface points at evenly spaced parameters t = k / (n − 1) from origin to insertion.
    pub points: Vec<DVec3>,
    /// Arc length from the origin to each point.
    pub arc: Vec<f64>,
}

/// Steepest depth change per in-plane length counted in a muscle's arc length (about 56°).
const MAX_SLOPE: f64 = 1.5;

/// Samples along a muscle's line.
const PATH_SAMPLES: usize = 48;

impl MusclePath {
    /// Lifts the segment onto the front surface with rays along −z (the first front hit of
    /// each). Where a ray misses the face (an origin beyond the outer contour), the nearest
    /// hit's depth is used. `None` when no ray hits the front.
    pub fn lift(
        shell: &Shell,
        bvh: &TriangleBvh,
        origin: DVec2,
        insertion: DVec2,
    ) -> Option<MusclePath> {
        let z_top = shell.vertices.iter().map(|v| v.z).fold(f64::MIN, f64::max);
        let z_bottom = shell.vertices.iter().map(|v| v.z).fold(f64::MAX, f64::min);
        let z0 = z_top + 0.01 * (z_top - z_bottom).max(1e-9);
        let n = PATH_SAMPLES;
        let hits: Vec<Option<f64>> = (0..n)
            .map(|k| {
                let p = origin.lerp(insertion, k as f64 / (n - 1) as f64);
                let hits = bvh.ray_hits(DVec3::new(p.x, p.y, z0), DVec3::NEG_Z);
                hits.iter()
                    .find(|h| shell.tags[h.triangle as usize] == ElementTag::Front)
                    .map(|h| z0 - h.t)
            })
            .collect();
        let known: Vec<usize> = (0..n).filter(|&k| hits[k].is_some()).collect();
        if known.is_empty() {
            return None;
        }
        let depth: Vec<f64> = (0..n)
            .map(|k| {
                hits[k].unwrap_or_else(|| {
                    known
                        .iter()
                        .min_by_key(|&&j| j.abs_diff(k))
                        .and_then(|&j| hits[j])
                        .unwrap_or(0.0)
                })
            })
            .collect();
        // Median of 5 neighbours: a ray that slips into a lip fold or a nostril lands far
        // deeper than its neighbours; such spikes must not add to the muscle's length.
        let points: Vec<DVec3> = (0..n)
            .map(|k| {
                let p = origin.lerp(insertion, k as f64 / (n - 1) as f64);
                let mut w: Vec<f64> = depth[k.saturating_sub(2)..(k + 3).min(n)].to_vec();
                w.sort_by(f64::total_cmp);
                DVec3::new(p.x, p.y, w[w.len() / 2])
            })
            .collect();
        // Arc length along the surface, each step's depth change capped at
        // MAX_SLOPE × its in-plane length: where the line crosses a hole (the mouth) or a fold,
        // the first front hit jumps in depth, which is no length of skin.
        let mut arc = Vec::with_capacity(n);
        let mut total = 0.0;
        for k in 0..n {
            if k > 0 {
                let step = points[k] - points[k - 1];
                let in_plane = step.truncate().length();
                let dz = step.z.abs().min(MAX_SLOPE * in_plane);
                total += (in_plane * in_plane + dz * dz).sqrt();
            }
            arc.push(total);
        }
        Some(MusclePath {
            origin,
            insertion,
            points,
            arc,
        })
    }

    /// Total length along the surface.
    pub fn length(&self) -> f64 {
        self.arc.last().copied().unwrap_or(0.0)
    }

    /// For a point of the front plane: the parameter t ∈ [0, 1] of its closest point on the
    /// segment (unclamped value first: outside [0, 1] it lies beyond an end) and the distance
    /// to the segment in the plane.
    pub fn project(&self, p: DVec2) -> (f64, f64) {
        project_on_segment(self.origin, self.insertion, p)
    }

    /// Arc length from the origin at parameter t (clamped to [0, 1]).
    pub fn arc_at(&self, t: f64) -> f64 {
        let n = self.points.len();
        let x = t.clamp(0.0, 1.0) * (n - 1) as f64;
        let k = (x.floor() as usize).min(n - 2);
        let f = x - k as f64;
        self.arc[k] + f * (self.arc[k + 1] - self.arc[k])
    }

    /// The origin on the surface.
    pub fn origin_point(&self) -> DVec3 {
        self.points[0]
    }
}

/// Smoothstep fade-in with the distance from the outer contour: 0 on it, 1 from `taper` on.
pub(crate) fn contour_weight(distance: f64, taper: f64) -> f64 {
    if taper <= 0.0 {
        return 1.0;
    }
    let x = (distance / taper).clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// Distance in the front plane from `p` to a closed polyline.
pub fn distance_to_loop(p: DVec2, polyline: &[DVec2]) -> f64 {
    let n = polyline.len();
    (0..n)
        .map(|i| project_on_segment(polyline[i], polyline[(i + 1) % n], p).1)
        .fold(f64::INFINITY, f64::min)
}

/// Raised-cosine fall-off across a band: 1 on the muscle's line, 0 at `half_width`.
pub(crate) fn band_weight(distance: f64, half_width: f64) -> f64 {
    if half_width <= 0.0 || distance >= half_width {
        0.0
    } else {
        0.5 * (1.0 + (std::f64::consts::PI * distance / half_width).cos())
    }
}

/// The attachment a muscle uses in the anatomical model: from the boxes for a standard muscle,
/// from its chain's ends otherwise (`None` for a muscle without elements).
pub(crate) fn muscle_attachment(
    shell: &Shell,
    boxes: &FeatureBoxes,
    muscle: &Muscle,
) -> Option<Attachment> {
    if let Some(kind) = muscle.kind {
        return attachment(kind, boxes);
    }
    let chain = if muscle.front_chain.is_empty() {
        &muscle.back_chain
    } else {
        &muscle.front_chain
    };
    let first = *chain.first()?;
    let last = *chain.last()?;
    Some(Attachment {
        origin: shell.centroid(last as usize).truncate(),
        insertion: shell.centroid(first as usize).truncate(),
        half_width_mm: CUSTOM_HALF_WIDTH_MM,
        max_strain: CUSTOM_MAX_STRAIN,
        spread_mm: 0.0,
    })
}

/// Places a standard muscle's band: the front and back elements (not skull) whose centroids
/// lie, in the front plane, within the core of the band and between origin and insertion,
/// each chain sorted from the insertion to the origin (the thesis's start → end).
pub(crate) fn place_band(
    shell: &Shell,
    skull: &HashSet<u32>,
    att: &Attachment,
    mm_per_unit: f64,
    params: &AnatomicalParams,
) -> (Vec<u32>, Vec<u32>) {
    let half_width = att.half_width_mm / mm_per_unit;
    let t_max = 1.0 + spread_fraction(att, mm_per_unit);
    let mut front = Vec::new();
    let mut back = Vec::new();
    for e in 0..shell.element_count() {
        let tag = shell.tags[e];
        let wanted = !matches!(
            (tag, params.layer),
            (ElementTag::Rim, _)
                | (ElementTag::Front, BandLayer::Back)
                | (ElementTag::Back, BandLayer::Front)
        );
        if !wanted || skull.contains(&(e as u32)) {
            continue;
        }
        let (t, d) = project_on_segment(att.origin, att.insertion, shell.centroid(e).truncate());
        if (0.0..=t_max).contains(&t) && d <= params.core_fraction * half_width {
            match tag {
                ElementTag::Front => front.push((t, e as u32)),
                _ => back.push((t, e as u32)),
            }
        }
    }
    let order = |v: &mut Vec<(f64, u32)>| {
        v.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        v.iter().map(|&(_, e)| e).collect::<Vec<u32>>()
    };
    (order(&mut front), order(&mut back))
}

/// Per-element prescribed displacement of `muscle` at slider = +1 in the anatomical model
/// (the lengthening; −1, full contraction, is its negative): each element of the muscle moves
/// `max_strain × strength × s × w` away from the origin (the direction to the origin projected
/// into the element's plane), where `s` is the arc length from the origin to the element's closest point on
/// the line and `w` the band fall-off ([`band_weight`]) at its distance from the line, times
/// the fade-in from the outer contour `contour` (canonical x-y, [`contour_weight`]).
/// Front chain entries come first, then back chain entries, as in the thesis model.
#[allow(clippy::too_many_arguments)]
pub(crate) fn anatomical_pattern(
    shell: &Shell,
    bvh: &TriangleBvh,
    boxes: &FeatureBoxes,
    contour: &[DVec2],
    muscle: &Muscle,
    mm_per_unit: f64,
    params: &AnatomicalParams,
) -> Vec<(u32, DVec3)> {
    let elements: Vec<u32> = muscle.elements().collect();
    let Some(att) = muscle_attachment(shell, boxes, muscle) else {
        return Vec::new();
    };
    let Some(path) = MusclePath::lift(shell, bvh, att.origin, att.insertion) else {
        return elements.into_iter().map(|e| (e, DVec3::ZERO)).collect();
    };
    let half_width = att.half_width_mm / mm_per_unit;
    let strain = att.max_strain * params.strength;
    elements
        .into_iter()
        .map(|e| {
            let c3 = shell.centroid(e as usize);
            let c = c3.truncate();
            let (t, d) = path.project(c);
            let s = path.arc_at(t);
            // Toward the origin, along the element's own plane (the skin slides, it is not
            // pushed into the face).
            let n = element_normal(shell, e as usize);
            let to_origin = path.origin_point() - c3;
            let toward_origin = (to_origin - n * to_origin.dot(n)).normalize_or_zero();
            let w = band_weight(d, half_width)
                * contour_weight(distance_to_loop(c, contour), CONTOUR_TAPER_MM / mm_per_unit);
            (e, -toward_origin * (strain * s * w))
        })
        .collect()
}

/// [`anatomical_pattern`] of `muscle` on a rig's shell: its band's per-element motion at
/// slider = +1 (a prescribed band's displacement; a force-driven band's traction shape), with
/// the shell's BVH ([`shell_bvh`]) and the outer contour of `loops` in the front plane.
pub(crate) fn band_pattern(
    shell: &Shell,
    loops: &FaceLoops,
    boxes: &FeatureBoxes,
    mm_per_unit: f64,
    params: &AnatomicalParams,
    muscle: &Muscle,
) -> Vec<(u32, DVec3)> {
    anatomical_pattern(
        shell,
        &shell_bvh(shell),
        boxes,
        &loop_xy(&shell.vertices, &loops.face),
        muscle,
        mm_per_unit,
        params,
    )
}

/// Bounding-volume hierarchy of the shell's elements (for ray casts).
pub(crate) fn shell_bvh(shell: &Shell) -> TriangleBvh {
    let tris: Vec<[DVec3; 3]> = (0..shell.element_count())
        .map(|e| shell.corners(e))
        .collect();
    TriangleBvh::new(&tris)
}

/// [`Attachment::spread_mm`] as a fraction of the muscle's in-plane length.
fn spread_fraction(att: &Attachment, mm_per_unit: f64) -> f64 {
    let len = att.origin.distance(att.insertion) * mm_per_unit;
    if len > 0.0 { att.spread_mm / len } else { 0.0 }
}

/// Unit normal of a shell element (zero for a degenerate one).
fn element_normal(shell: &Shell, e: usize) -> DVec3 {
    let [a, b, c] = shell.corners(e);
    (b - a).cross(c - a).normalize_or_zero()
}

/// Parameter t of the closest point to `p` on the line through `a` and `b` (outside [0, 1]
/// beyond an end) and the distance from `p` to the segment.
fn project_on_segment(a: DVec2, b: DVec2, p: DVec2) -> (f64, f64) {
    let d = b - a;
    let len2 = d.length_squared();
    let t = if len2 > 0.0 {
        (p - a).dot(d) / len2
    } else {
        0.0
    };
    (t, p.distance(a + d * t.clamp(0.0, 1.0)))
}
