//! A mouth that comes closed: the lips' contact line, found as the surface's valley across the
//! mouth, and the cut that opens it into the mouth loop the rig expects.
//!
//! A sculpt with closed lips, a scan, or a face whose lip loops were welded has three boundary
//! loops (the contour and two eyes) instead of four: the lips meet along a line of shared
//! vertices (a *slit*). Where the lips meet, the surface folds inward: the edges of the contact
//! line are the sharpest concave edges (valley edges) across the mouth. The line is found as
//! a valley line of the mesh's dihedral angles (the discrete version of the crease lines of
//! Ohtake, Belyaev & Seidel, "Ridge-valley lines on meshes via implicit surface fitting",
//! SIGGRAPH 2004, here with the dihedral angle as the curvature measure):
//!
//! 1. **Where to look.** The two loops of smallest perimeter are the eyes; their centroids give
//!    the eye line and the interocular distance `iod`; the surface's area-weighted normal gives
//!    the front. The nose tip (the front-most point between the eyes' columns) says which way is
//!    down. The lips meet on the face's centre line between
//!    [`MOUTH_BELOW_NOSE_IOD`]`.0` and `.1` interocular distances below the nose tip.
//! 2. **The seed** is the most concave interior edge there within [`SEED_HALF_WIDTH_IOD`] of the
//!    centre line; it must fold by at least [`MIN_SEED_FOLD_RAD`].
//! 3. **The trace** runs from the seed to each side along the most concave edge that still goes
//!    sideways, while the fold stays above [`TRACE_FOLD_FRACTION`] of the seed's; where it
//!    fades are the mouth corners. The line must span [`MIN_WIDTH_IOD`] at least.
//!
//! **The cut** duplicates every line vertex between the two corners; the triangles below the
//! line take the copies, moved [`LIP_SEPARATION_REL`] of the face's size down. The corners stay
//! shared, as on an open mouth, so the cut face has the four loops of an open mouth whose lips
//! touch (a mouth loop of zero width to within 2 µm). The rig treats it as such: the jaw moves
//! the lower copies and not the upper vertices.

use crate::error::PrepError;
use crate::frame::orient::{loop_centroid, loop_perimeter};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// The lips meet between this many interocular distances below the nose tip (the mouth line
/// lies 0.35–0.5 iod below the nose tip on adult faces: subnasale-to-stomion about 20–23 mm,
/// nose tip to subnasale about 10–15 mm, iod about 63 mm; Farkas, *Anthropometry of the Head
/// and Face*, 1994). The window is wide so that long and short faces fit.
pub const MOUTH_BELOW_NOSE_IOD: (f64, f64) = (0.15, 1.0);
/// The seed edge's midpoint lies within this many interocular distances of the centre line.
pub const SEED_HALF_WIDTH_IOD: f64 = 0.12;
/// Least fold (the angle between the normals of the two triangles of a concave edge) of the
/// seed: 40°. Lips that meet fold far more (welded lip loops: 120–170°); a smooth upper lip or
/// chin folds by a few degrees per edge.
pub const MIN_SEED_FOLD_RAD: f64 = 40.0 * std::f64::consts::PI / 180.0;
/// The trace continues while an edge folds by at least this fraction of the sharpest fold of
/// the line so far (and of the seed's).
pub const TRACE_FOLD_FRACTION: f64 = 0.5;
/// Least width of the found line (corner to corner, along the eye line), interocular
/// distances: a mouth is 0.7–0.9 iod wide.
pub const MIN_WIDTH_IOD: f64 = 0.25;
/// Widest the line may run to either side of the centre line, interocular distances: the
/// mouth's width is 0.65–0.9 interocular distances (Farkas 1994: 50 ± 3.5 mm against 62 ± 3 mm
/// between the pupils), so a fold that runs on past 0.45 is the commissure's crease in the cheek.
pub const MAX_HALF_WIDTH_IOD: f64 = 0.45;
/// The trace ends where the line would come forward: a step whose forward rise is more than
/// this fraction of its length (30°). The mouth corner (cheilion) is the deepest point of the
/// oral fissure, which curves back with the dental arch from the middle of the lips; lateral
/// to it the modiolus raises the skin again (Gray's Anatomy, 41st ed., ch. 30), and a fold
/// there is the commissure's crease, not the lips'.
pub const MAX_FORWARD_SLOPE: f64 = 0.5;
/// How far the lower lip's copies are moved away from the upper lip's vertices (along the
/// face's down direction), as a fraction of the bounding-box diagonal: 2 µm on a 20 cm face,
/// invisible, but a thousand times the weld tolerance
/// ([`crate::WELD_RELATIVE_TOLERANCE`]), so that every later step that matches vertices by
/// position (welding, mirror pairs, the canonical grid) sees two lips and never one.
pub const LIP_SEPARATION_REL: f64 = 1e-5;

/// A closed mouth opened along its lips' contact line ([`open_closed_mouth`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LipLine {
    /// The line from one corner to the other: the upper lip's vertices (the corners are shared).
    pub upper: Vec<u32>,
    /// The lower lip's copies of `upper[1..len - 1]`, in the same order.
    pub lower: Vec<u32>,
}

/// The result of [`open_closed_mouth`]: the cut mesh and the line.
#[derive(Clone, Debug, PartialEq)]
pub struct OpenedMouth {
    /// The input vertices followed by the lower-lip copies.
    pub vertices: Vec<DVec3>,
    /// The triangles, in input order; below the line they use the copies.
    pub triangles: Vec<[u32; 3]>,
    /// The line and its copies.
    pub line: LipLine,
    /// Per triangle: it lies below the line and uses at least one copy.
    pub lower_triangles: Vec<bool>,
}

/// Signed fold of the interior edge `a → b` (`t1` holds `a → b`, `t2` holds `b → a`): the
/// angle between the two triangles' normals, positive where the surface folds toward its
/// front (a valley), negative on a ridge.
fn fold(vertices: &[DVec3], t1: [u32; 3], t2: [u32; 3], a: u32, b: u32) -> f64 {
    let p = |i: u32| vertices[i as usize];
    let normal = |t: [u32; 3]| (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
    let (n1, n2) = (normal(t1), normal(t2));
    let d = t2.into_iter().find(|&v| v != a && v != b).unwrap_or(a);
    let angle = n1.cross(n2).length().atan2(n1.dot(n2));
    if (p(d) - p(a)).dot(n1) > 0.0 {
        angle
    } else {
        -angle
    }
}

/// The face's frame for the search: eye midpoint, unit eye-line direction, unit "down" in the
/// front plane, interocular distance, and how far below the eyes the nose tip is.
struct SearchFrame {
    eyes_mid: DVec3,
    across: DVec3,
    down: DVec3,
    iod: f64,
    nose_below_eyes: f64,
}

fn search_frame(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Option<SearchFrame> {
    let mut by_perimeter: Vec<usize> = (0..loops.len()).collect();
    by_perimeter.sort_by(|&a, &b| {
        loop_perimeter(vertices, &loops[a]).total_cmp(&loop_perimeter(vertices, &loops[b]))
    });
    let (e1, e2) = (
        loop_centroid(vertices, &loops[by_perimeter[0]]),
        loop_centroid(vertices, &loops[by_perimeter[1]]),
    );
    let iod = e1.distance(e2);
    if !iod.is_finite() || iod <= 0.0 {
        return None;
    }
    let across = (e2 - e1) / iod;
    let area_normal: DVec3 = triangles
        .iter()
        .map(|t| {
            let p = |k: usize| vertices[t[k] as usize];
            (p(1) - p(0)).cross(p(2) - p(0))
        })
        .sum();
    let front = (area_normal - area_normal.dot(across) * across).try_normalize()?;
    let up_or_down = front.cross(across);
    let eyes_mid = 0.5 * (e1 + e2);
    let tip = vertices
        .iter()
        .filter(|p| {
            let r = **p - eyes_mid;
            r.dot(across).abs() < 0.35 * iod && r.dot(up_or_down).abs() < 1.5 * iod
        })
        .max_by(|a, b| {
            (**a - eyes_mid)
                .dot(front)
                .total_cmp(&(**b - eyes_mid).dot(front))
        })?;
    let along = (*tip - eyes_mid).dot(up_or_down);
    let down = if along >= 0.0 {
        up_or_down
    } else {
        -up_or_down
    };
    Some(SearchFrame {
        eyes_mid,
        across,
        down,
        iod,
        nose_below_eyes: along.abs(),
    })
}

/// Finds the lips' contact line of a face with three boundary loops (contour and two eyes) and
/// cuts it open. `Ok(None)` when `loops` is not three loops; an error naming what is missing
/// when no line is found.
///
/// ```
/// use face_prep::frame::lip_line::open_closed_mouth;
/// use glam::DVec3;
/// // A flat sheet has no closed mouth to open.
/// let v = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert!(open_closed_mouth(&v, &[[0, 1, 2]], &[vec![0, 1, 2]]).unwrap().is_none());
/// ```
pub fn open_closed_mouth(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Result<Option<OpenedMouth>, PrepError> {
    if loops.len() != 3 {
        return Ok(None);
    }
    let no_mouth = |reason: String| PrepError::NoMouth { reason };
    let frame = search_frame(vertices, triangles, loops)
        .ok_or_else(|| no_mouth("the eyes and the front could not be placed".into()))?;
    let on_boundary: Vec<bool> = {
        let mut b = vec![false; vertices.len()];
        for &v in loops.iter().flatten() {
            b[v as usize] = true;
        }
        b
    };
    // Directed edge → triangle.
    let mut directed: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            directed.insert((tri[k], tri[(k + 1) % 3]), t);
        }
    }
    let edge_fold = |a: u32, b: u32| -> Option<f64> {
        let t1 = *directed.get(&(a, b))?;
        let t2 = *directed.get(&(b, a))?;
        Some(fold(vertices, triangles[t1], triangles[t2], a, b))
    };
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); vertices.len()];
    for &(a, b) in directed.keys() {
        neighbours[a as usize].push(b);
    }
    for n in &mut neighbours {
        n.sort_unstable();
        n.dedup();
    }
    let p = |i: u32| vertices[i as usize];
    let across_of = |i: u32| (p(i) - frame.eyes_mid).dot(frame.across);
    let below_eyes = |x: DVec3| (x - frame.eyes_mid).dot(frame.down);
    let iod = frame.iod;
    let front = frame.across.cross(frame.down);
    let (lo, hi) = (
        frame.nose_below_eyes + MOUTH_BELOW_NOSE_IOD.0 * iod,
        frame.nose_below_eyes + MOUTH_BELOW_NOSE_IOD.1 * iod,
    );
    let mut seed: Option<(f64, u32, u32)> = None;
    for (&(a, b), _) in directed.iter().filter(|((a, b), _)| a < b) {
        if on_boundary[a as usize] || on_boundary[b as usize] {
            continue;
        }
        let mid = 0.5 * (p(a) + p(b));
        let depth = below_eyes(mid);
        if (mid - frame.eyes_mid).dot(frame.across).abs() > SEED_HALF_WIDTH_IOD * iod
            || depth < lo
            || depth > hi
        {
            continue;
        }
        if let Some(f) = edge_fold(a, b)
            && seed.is_none_or(|(best, _, _)| f > best)
        {
            seed = Some((f, a, b));
        }
    }
    let Some((seed_fold, a, b)) = seed else {
        return Err(no_mouth(
            "no surface below the nose to look for the lips in".into(),
        ));
    };
    if seed_fold < MIN_SEED_FOLD_RAD {
        return Err(no_mouth(format!(
            "the sharpest fold below the nose is {:.0}°, lips that meet fold by {:.0}° at least",
            seed_fold.to_degrees(),
            MIN_SEED_FOLD_RAD.to_degrees()
        )));
    }
    let (a, b) = if across_of(a) <= across_of(b) {
        (a, b)
    } else {
        (b, a)
    };
    let mut in_line = vec![false; vertices.len()];
    in_line[a as usize] = true;
    in_line[b as usize] = true;
    let trace = |from: u32, sign: f64, in_line: &mut [bool]| -> Vec<u32> {
        let mut out = Vec::new();
        let mut at = from;
        let mut sharpest = seed_fold;
        loop {
            let threshold = TRACE_FOLD_FRACTION * sharpest;
            let next = neighbours[at as usize]
                .iter()
                .copied()
                .filter(|&w| {
                    !in_line[w as usize]
                        && !on_boundary[w as usize]
                        && sign * (across_of(w) - across_of(at)) > 0.0
                        && sign * across_of(w) <= MAX_HALF_WIDTH_IOD * iod
                        && (p(w) - p(at)).dot(front) <= MAX_FORWARD_SLOPE * p(w).distance(p(at))
                })
                .filter_map(|w| edge_fold(at, w).map(|f| (f, w)))
                .filter(|&(f, _)| f >= threshold)
                .max_by(|x, y| x.0.total_cmp(&y.0));
            match next {
                Some((f, w)) => {
                    sharpest = sharpest.max(f);
                    in_line[w as usize] = true;
                    out.push(w);
                    at = w;
                }
                None => return out,
            }
        }
    };
    let left = trace(a, -1.0, &mut in_line);
    let right = trace(b, 1.0, &mut in_line);
    let line: Vec<u32> = left.into_iter().rev().chain([a, b]).chain(right).collect();
    let (first, last) = (line[0], line[line.len() - 1]);
    let width = across_of(last) - across_of(first);
    if line.len() < 3 || width < MIN_WIDTH_IOD * iod {
        return Err(no_mouth(format!(
            "the fold below the nose ({:.0}°) runs {:.2} eye distances, a mouth is {:.2} wide at \
             least",
            seed_fold.to_degrees(),
            width / iod,
            MIN_WIDTH_IOD
        )));
    }
    Ok(Some(cut(vertices, triangles, &line, &frame)))
}

/// Cuts `triangles` open along `line` (interior vertices; the ends stay shared): the triangles
/// below the line get copies of its inner vertices.
fn cut(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    line: &[u32],
    frame: &SearchFrame,
) -> OpenedMouth {
    let mut vertex_triangles: Vec<Vec<usize>> = vec![Vec::new(); vertices.len()];
    for (t, tri) in triangles.iter().enumerate() {
        for &v in tri {
            vertex_triangles[v as usize].push(t);
        }
    }
    let holds_directed = |t: usize, a: u32, b: u32| {
        let tri = triangles[t];
        (0..3).any(|k| tri[k] == a && tri[(k + 1) % 3] == b)
    };
    let centroid = |t: usize| {
        triangles[t]
            .iter()
            .map(|&v| vertices[v as usize])
            .sum::<DVec3>()
            / 3.0
    };
    // Which side of the directed line (first → last) is below: the triangles left of it
    // (holding a → b) or right of it (holding b → a).
    let mut left_lower = 0.0;
    for w in line.windows(2) {
        let (l, r) = (
            vertex_triangles[w[0] as usize]
                .iter()
                .copied()
                .find(|&t| holds_directed(t, w[0], w[1])),
            vertex_triangles[w[0] as usize]
                .iter()
                .copied()
                .find(|&t| holds_directed(t, w[1], w[0])),
        );
        if let (Some(l), Some(r)) = (l, r) {
            left_lower += (centroid(l) - centroid(r)).dot(frame.down);
        }
    }
    let lower_of = |a: u32, b: u32| -> Option<usize> {
        let (x, y) = if left_lower > 0.0 { (a, b) } else { (b, a) };
        vertex_triangles[a as usize]
            .iter()
            .copied()
            .find(|&t| holds_directed(t, x, y))
    };
    let (lo, hi) = crate::frame::topology::bounding_box(vertices.iter().copied());
    let separation = LIP_SEPARATION_REL * (hi - lo).length() * frame.down;
    let mut out_vertices = vertices.to_vec();
    let mut out_triangles = triangles.to_vec();
    let mut lower_triangles = vec![false; triangles.len()];
    let mut lower = Vec::with_capacity(line.len().saturating_sub(2));
    for i in 1..line.len() - 1 {
        let (prev, v, next) = (line[i - 1], line[i], line[i + 1]);
        let copy = out_vertices.len() as u32;
        out_vertices.push(vertices[v as usize] + separation);
        lower.push(copy);
        // Flood the fan of `v` from the lower triangles of its two line edges, across edges
        // of `v` that are not on the line.
        let mut stack: Vec<usize> = [lower_of(prev, v), lower_of(v, next)]
            .into_iter()
            .flatten()
            .collect();
        let mut seen: Vec<usize> = Vec::new();
        while let Some(t) = stack.pop() {
            if seen.contains(&t) {
                continue;
            }
            seen.push(t);
            for &x in &triangles[t] {
                if x == v || x == prev || x == next {
                    continue;
                }
                for &u in &vertex_triangles[v as usize] {
                    if u != t && triangles[u].contains(&x) && !seen.contains(&u) {
                        stack.push(u);
                    }
                }
            }
        }
        for t in seen {
            lower_triangles[t] = true;
            for c in &mut out_triangles[t] {
                if *c == v {
                    *c = copy;
                }
            }
        }
    }
    OpenedMouth {
        vertices: out_vertices,
        triangles: out_triangles,
        line: LipLine {
            upper: line.to_vec(),
            lower,
        },
        lower_triangles,
    }
}
