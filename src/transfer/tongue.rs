//! ARKit's `tongueOut` on a whole head with a tongue (issue 32, item 5).
//!
//! The target is the jaw opened by [`TONGUE_OUT_JAW`] of `jawOpen` (the rig's own jaw target,
//! carried to the head: the lower teeth, gums and tongue go with the mandible) plus the
//! tongue's protrusion:
//!
//! - **Which vertices are the tongue**, from the geometry of the gums-and-tongue parts: a
//!   vertex is tongue in the product of three smooth shares — away from the teeth (the gums
//!   hug the teeth: 0 within [`GUM_BAND`]`.0` interocular distances of a tooth, 1 beyond
//!   `GUM_BAND.1`), with the lower jaw (its share of the jaw's motion, 0 under 0.3 and 1 over
//!   0.4: the palate and the upper gums stay) and at the height of the bite (the dorsum lies
//!   near the plane between the rows; the floor of the mouth [`FLOOR_DEPTH`] below it stays),
//!   and inside the lower dental arch (seen from above, nearer the arch's centre than the
//!   teeth at that bearing by [`ARCH_MARGIN`]: the gums in front of the incisors stay).
//! - **How it moves**: forward by [`TONGUE_OUT_FORWARD`] interocular distances at its tip,
//!   falling smoothly to nothing [`TONGUE_LENGTH`] behind the tip (the tongue stretches as it
//!   protrudes), and up or down so that the tip passes midway between the upper incisors and
//!   the lowered lower incisors.

use glam::DVec3;

use super::nearest::PointTree;

/// The share of `jawOpen` in `tongueOut`: the mouth open far enough for the tongue to pass
/// between the incisors.
pub const TONGUE_OUT_JAW: f64 = 0.5;
/// How far the tip of the tongue moves forward, in interocular distances (0.7 ≈ 44 mm: from
/// behind the lower incisors to about 20 mm in front of the lips, as in ARKit's reference
/// picture of tongueOut), before the opening jaw takes it back and down.
pub const TONGUE_OUT_FORWARD: f64 = 0.7;
/// The length of the tongue behind its tip that moves, in interocular distances.
pub const TONGUE_LENGTH: f64 = 0.5;
/// Distances from the nearest tooth (in interocular distances) over which a vertex goes from
/// gum (still with its tooth) to tongue.
pub const GUM_BAND: (f64, f64) = (0.02, 0.06);
/// Depth below the bite (in interocular distances) from which the floor of the mouth stays.
pub const FLOOR_DEPTH: f64 = 0.25;

/// Rounds of neighbour averaging of the tongue's weights over its own triangles, so that the
/// tongue moves as one body rather than as the vertices that passed every test.
pub const SMOOTHING_ROUNDS: usize = 30;

/// How far inside the lower teeth (seen from above, in interocular distances) a vertex is
/// wholly tongue; at a third of it, none.
pub const ARCH_MARGIN: f64 = 0.06;

/// What the tongue needs to know of the head, in the file's frame.
pub struct Mouth<'a> {
    /// Every vertex of the head.
    pub positions: &'a [DVec3],
    /// The head's triangles (those of the gums and tongue smooth the tongue's weights).
    pub triangles: &'a [[u32; 3]],
    /// The vertices of the gums and tongue.
    pub gums_and_tongue: &'a [u32],
    /// The vertices of the upper teeth.
    pub upper_teeth: &'a [u32],
    /// The vertices of the lower teeth.
    pub lower_teeth: &'a [u32],
    /// Up and forward, unit vectors.
    pub up: DVec3,
    /// The way the face looks.
    pub forward: DVec3,
    /// The interocular distance, in the file's units.
    pub iod: f64,
}

/// The tongue's protrusion at weight 1 (every other vertex zero), given the jaw part of the
/// target `jaw` (per vertex); `None` when no vertex is tongue.
///
/// ```
/// use facebem::transfer::tongue::{Mouth, protrusion};
/// use glam::DVec3;
/// // Two teeth rows at the front, a tongue point behind them at the height of the bite.
/// let positions = [
///     DVec3::new(0.0, 0.02, 1.0),   // upper tooth
///     DVec3::new(0.0, -0.02, 1.0),  // lower tooth
///     DVec3::new(0.0, -0.01, 0.8),  // tongue tip
/// ];
/// let mouth = Mouth {
///     positions: &positions,
///     triangles: &[],
///     gums_and_tongue: &[2],
///     upper_teeth: &[0],
///     lower_teeth: &[1],
///     up: DVec3::Y,
///     forward: DVec3::Z,
///     iod: 1.0,
/// };
/// let field = protrusion(&mouth, &[DVec3::ZERO; 3]).unwrap();
/// assert!((field[2].z - 0.7).abs() < 1e-9);
/// assert_eq!(field[0], DVec3::ZERO);
/// ```
pub fn protrusion(mouth: &Mouth, jaw: &[DVec3]) -> Option<Vec<DVec3>> {
    let at = |v: u32| mouth.positions[v as usize];
    let tree = |row: &[u32]| PointTree::new(row.iter().map(|&v| (v, at(v))));
    let (upper_tree, lower_tree) = (tree(mouth.upper_teeth), tree(mouth.lower_teeth));
    let nearest = |row: &PointTree, p: DVec3| row.nearest(p).map_or(f64::INFINITY, |(_, d)| d);
    let height = |v: u32| mouth.up.dot(at(v));
    let iod = mouth.iod;
    let lowest_upper = incisal_edge(mouth, mouth.upper_teeth, -1.0)?;
    let highest_lower = incisal_edge(mouth, mouth.lower_teeth, 1.0)?;
    let bite = 0.5 * (height(lowest_upper) + height(highest_lower));
    let arch = Arch::new(mouth)?;
    let smooth = |t: f64| {
        let t = t.clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    };
    // Per vertex: how far from the teeth it is (1: tongue, 0: gum at a tooth).
    let away_of: std::collections::HashMap<u32, f64> = mouth
        .gums_and_tongue
        .iter()
        .map(|&v| {
            let teeth = nearest(&upper_tree, at(v)).min(nearest(&lower_tree, at(v)));
            (
                v,
                smooth((teeth / iod - GUM_BAND.0) / (GUM_BAND.1 - GUM_BAND.0)),
            )
        })
        .collect();
    let weights: Vec<(u32, f64)> = mouth
        .gums_and_tongue
        .iter()
        .map(|&v| {
            let p = at(v);
            let (up, low) = (nearest(&upper_tree, p), nearest(&lower_tree, p));
            let away = away_of.get(&v).copied().unwrap_or(0.0);
            let share = if up + low > 0.0 { up / (up + low) } else { 0.0 };
            let lower = smooth((share - 0.3) / 0.1);
            let depth = (bite - height(v)) / iod;
            let level = 1.0 - smooth((depth - 0.6 * FLOOR_DEPTH) / (0.4 * FLOOR_DEPTH));
            (v, away * lower * level * arch.inside(p))
        })
        .collect();
    // Smoothed over the surface, then kept off the teeth again: a vertex at a tooth is gum.
    let weights: Vec<(u32, f64)> = smoothed(mouth, weights)
        .into_iter()
        .map(|(v, w)| (v, w * away_of.get(&v).copied().unwrap_or(0.0)))
        .filter(|&(_, w)| w > 0.0)
        .collect();
    let tongue: Vec<u32> = weights
        .iter()
        .filter(|&&(_, w)| w > 0.5)
        .map(|&(v, _)| v)
        .collect();
    let front = tongue
        .iter()
        .map(|&v| mouth.forward.dot(at(v)))
        .fold(f64::NEG_INFINITY, f64::max);
    if !front.is_finite() {
        return None;
    }
    // The tip (the tongue within 0.05 interocular distances of its front) passes, at its
    // mean height, midway between the upper incisors and the lowered lower ones.
    let moved = |v: u32| at(v) + jaw.get(v as usize).copied().unwrap_or(DVec3::ZERO);
    let tip: Vec<u32> = tongue
        .iter()
        .copied()
        .filter(|&v| mouth.forward.dot(at(v)) >= front - 0.05 * iod)
        .collect();
    let tip_height =
        tip.iter().map(|&v| mouth.up.dot(moved(v))).sum::<f64>() / tip.len().max(1) as f64;
    let gap = 0.5 * (mouth.up.dot(at(lowest_upper)) + mouth.up.dot(moved(highest_lower)));
    let lift = gap - tip_height;
    let length = TONGUE_LENGTH * iod;
    let mut field = vec![DVec3::ZERO; mouth.positions.len()];
    for (v, w) in weights {
        let along = smooth((mouth.forward.dot(at(v)) - (front - length)) / length);
        field[v as usize] =
            w * along * (TONGUE_OUT_FORWARD * iod * mouth.forward + lift * mouth.up);
    }
    Some(field)
}

/// The incisal edge of a row: among its teeth's vertices within 0.05 interocular distances of
/// its front-most one, the lowest (`sign` −1, the upper row) or highest (`sign` +1, the lower).
fn incisal_edge(mouth: &Mouth, row: &[u32], sign: f64) -> Option<u32> {
    let at = |v: u32| mouth.positions[v as usize];
    let front = row
        .iter()
        .map(|&v| mouth.forward.dot(at(v)))
        .fold(f64::NEG_INFINITY, f64::max);
    row.iter()
        .copied()
        .filter(|&v| mouth.forward.dot(at(v)) >= front - 0.05 * mouth.iod)
        .max_by(|&a, &b| (sign * mouth.up.dot(at(a))).total_cmp(&(sign * mouth.up.dot(at(b)))))
}

/// The lower dental arch seen from above: per bearing about the lower teeth's centroid, the
/// nearest tooth.
struct Arch {
    centre: DVec3,
    left: DVec3,
    forward: DVec3,
    /// Per [`ARCH_BINS`] bearing, the smallest horizontal distance of a lower tooth.
    radius: Vec<f64>,
    margin: f64,
}

/// Bearings of the arch (over the full turn).
const ARCH_BINS: usize = 36;

impl Arch {
    fn new(mouth: &Mouth) -> Option<Arch> {
        let n = mouth.lower_teeth.len();
        if n == 0 {
            return None;
        }
        let centre = mouth
            .lower_teeth
            .iter()
            .map(|&v| mouth.positions[v as usize])
            .sum::<DVec3>()
            / n as f64;
        let mut arch = Arch {
            centre,
            left: mouth.up.cross(mouth.forward).normalize_or_zero(),
            forward: mouth.forward,
            radius: vec![f64::INFINITY; ARCH_BINS],
            margin: ARCH_MARGIN * mouth.iod,
        };
        for &v in mouth.lower_teeth {
            let (bin, r) = arch.polar(mouth.positions[v as usize]);
            arch.radius[bin] = arch.radius[bin].min(r);
        }
        Some(arch)
    }

    /// The bearing's bin and the horizontal distance of `p` from the centre.
    fn polar(&self, p: DVec3) -> (usize, f64) {
        let d = p - self.centre;
        let (x, z) = (self.left.dot(d), self.forward.dot(d));
        let turn = x.atan2(z).rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU;
        let bin = ((turn * ARCH_BINS as f64) as usize).min(ARCH_BINS - 1);
        (bin, x.hypot(z))
    }

    /// 1 well inside the arch, 0 at the teeth less a third of the margin (bearings without
    /// teeth, behind the last molars, are inside).
    fn inside(&self, p: DVec3) -> f64 {
        let (bin, r) = self.polar(p);
        let teeth = self.radius[bin];
        if !teeth.is_finite() || self.margin <= 0.0 {
            return 1.0;
        }
        let t = ((teeth - r) / self.margin - 1.0 / 3.0) / (2.0 / 3.0);
        let t = t.clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    }
}

/// The weights averaged [`SMOOTHING_ROUNDS`] times with their neighbours along the gums' and
/// tongue's triangles (Jacobi, half the own weight kept), then doubled (at most 1); only
/// weights above zero are kept.
fn smoothed(mouth: &Mouth, weights: Vec<(u32, f64)>) -> Vec<(u32, f64)> {
    use std::collections::HashMap;
    let slot: HashMap<u32, usize> = weights
        .iter()
        .enumerate()
        .map(|(i, &(v, _))| (v, i))
        .collect();
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); weights.len()];
    for t in mouth.triangles {
        let s = t.map(|v| slot.get(&v).copied());
        for (a, b) in [(0, 1), (1, 2), (2, 0)] {
            if let (Some(i), Some(j)) = (s[a], s[b]) {
                neighbours[i].push(j);
                neighbours[j].push(i);
            }
        }
    }
    let mut w: Vec<f64> = weights.iter().map(|&(_, w)| w).collect();
    for _ in 0..SMOOTHING_ROUNDS {
        w = (0..w.len())
            .map(|i| match neighbours[i].len() {
                0 => w[i],
                k => 0.5 * w[i] + 0.5 * neighbours[i].iter().map(|&j| w[j]).sum::<f64>() / k as f64,
            })
            .collect();
    }
    // Averaging lowers the peak: what was half tongue or more afterwards is wholly tongue.
    weights
        .iter()
        .zip(w)
        .filter(|&(_, w)| w > 1e-6)
        .map(|(&(v, _), w)| (v, (2.0 * w).min(1.0)))
        .collect()
}
