//! Mouths and eyes that come closed: the contact line where the lips (or the lids) meet, found as
//! a valley of the surface, and the cut that opens it into the loop the rig expects.
//!
//! A sculpt with closed lips, a scan, or a face whose lip or lid loops were welded has fewer than
//! the four boundary loops of a front face: the lips (lids) meet along a line of shared vertices
//! (a *slit*), or at coincident vertices, which the reader welds into one. Where they meet the
//! surface folds inward: the edges of the contact line are the sharpest concave edges (valley
//! edges) across the mouth or the eye. The line is found as a valley line of the mesh's dihedral
//! angles — the discrete counterpart of the crease lines of Ohtake, Belyaev & Seidel,
//! "Ridge-valley lines on meshes via implicit surface fitting", SIGGRAPH 2004, with the angle
//! between the normals of an edge's two triangles (the *fold*) as the curvature measure:
//!
//! 1. **Where to look** comes from the loops that are there ([`mouth`]: the eyes; [`lids`]: the
//!    mouth).
//! 2. **The seed** is the sharpest valley edge there; it must fold by at least
//!    [`MIN_SEED_FOLD_RAD`].
//! 3. **The trace** runs from the seed to each side along the sharpest
//!    valley edge that still goes sideways, while the fold stays above a fraction of the
//!    sharpest of the line so far ([`TraceRule`]) and the line does not come forward by more than
//!    [`MAX_FORWARD_SLOPE`]: the corners of the mouth and the eye (cheilion, canthi) are the
//!    deepest points of their fissures, which curve back from the middle with the dental arch and
//!    the eyeball; lateral to the mouth corner the modiolus raises the skin again (Gray's
//!    Anatomy, 41st ed., ch. 30), so a fold beyond it is the commissure's crease, not the lips'.
//!
//! **The cut** duplicates every line vertex between the two ends; the triangles below
//! the line take the copies, moved [`SEPARATION_REL`] of the face's size down. The ends stay
//! shared, as on an open mouth, so the cut face has the loop of an open mouth (eye) whose lips
//! (lids) touch: a loop of zero width to within 2 µm. The rig treats it as such: the jaw moves
//! the lower lip's copies and not the upper lip's vertices.
//!
//! A mouth that opens into a closed **mouth bag** also leaves three loops; it is looked for
//! first, as a pit of the depth field, and taken off at its rim ([`bag`]).

pub mod bag;
pub mod lids;
pub mod mouth;

use crate::error::PrepError;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// Least fold (the angle between the normals of the two triangles of a valley edge) of a seed:
/// 40°. Lips or lids that meet fold far more (welded loops: 60–170°); a smooth upper lip, chin or
/// lid folds by a few degrees per edge.
pub const MIN_SEED_FOLD_RAD: f64 = 40.0 * std::f64::consts::PI / 180.0;
/// When a trace goes on: an edge must fold by at least `fraction` of the sharpest fold of the
/// line so far and by `least_rad`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceRule {
    /// Fraction of the line's sharpest fold so far.
    pub fraction: f64,
    /// Least fold, radians.
    pub least_rad: f64,
}
/// The trace ends where the line would come forward: a step whose forward rise is more than
/// this fraction of its length (30°).
pub const MAX_FORWARD_SLOPE: f64 = 0.5;
/// How far the lower side's copies are moved away from the upper side's vertices (along the
/// face's down direction), as a fraction of the bounding-box diagonal: 2 µm on a 20 cm face,
/// invisible, but ten thousand times the weld tolerance ([`crate::WELD_RELATIVE_TOLERANCE`]),
/// so that every later step that matches vertices by position (welding, mirror pairs, the
/// canonical grid) sees two lips and never one.
pub const SEPARATION_REL: f64 = 1e-5;

/// A contact line that was cut open: the upper side's vertices from one end to the other (the
/// ends are shared) and the lower side's copies of `upper[1..len - 1]`, in the same order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactLine {
    /// The line from one end (corner) to the other: the upper lip's (lid's) vertices.
    pub upper: Vec<u32>,
    /// The lower lip's (lid's) copies of the inner line vertices, appended to the mesh.
    pub lower: Vec<u32>,
}

impl ContactLine {
    /// Whether `v` is on the line (either side).
    pub fn contains(&self, v: u32) -> bool {
        self.upper.contains(&v) || self.lower.contains(&v)
    }
}

/// A face whose closed mouth and eyes were cut open ([`open_closed_features`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Opened {
    /// The input vertices followed by the lower sides' copies.
    pub vertices: Vec<DVec3>,
    /// The triangles, in input order; below a line they use the copies.
    pub triangles: Vec<[u32; 3]>,
    /// The lips' line, when the mouth was closed.
    pub lips: Option<ContactLine>,
    /// The lids' lines, when the eyes were closed.
    pub lids: Vec<ContactLine>,
    /// Vertices no triangle uses any more (a mouth bag taken off, [`bag`]), each with the
    /// vertex it follows.
    pub followers: Vec<(u32, u32)>,
}

impl Opened {
    /// `vertices` and `triangles` cut open along each of `lines` (lower side toward `down`, see
    /// [`cut`]), the lines' sides in `lips` when `are_lips`, in `lids` otherwise.
    fn cut_along(
        vertices: &[DVec3],
        triangles: &[[u32; 3]],
        lines: &[Vec<u32>],
        down: DVec3,
        are_lips: bool,
    ) -> Opened {
        let mut vertices = vertices.to_vec();
        let mut triangles = triangles.to_vec();
        let mut sides: Vec<ContactLine> = lines
            .iter()
            .map(|line| cut(&mut vertices, &mut triangles, line, down))
            .collect();
        let (lips, lids) = if are_lips {
            (sides.pop(), Vec::new())
        } else {
            (None, std::mem::take(&mut sides))
        };
        Opened {
            vertices,
            triangles,
            lips,
            lids,
            followers: Vec::new(),
        }
    }
}

/// Opens what came closed: with one loop (the contour) the lips' line found from the surface
/// alone and then both eyes' lid lines, with two loops (the contour and an open mouth) both
/// eyes' lid lines ([`lids`]), with three (the contour and the eyes) a mouth bag ([`bag`]) or
/// else the lips' line ([`mouth`]), or else, when the three are the contour, an open mouth and
/// one open eye, the other eye's lid line ([`lids::open_one_closed_eye`]). `Ok(None)` for
/// four loops (nothing to open) and for counts this does not handle (then the caller's loop
/// count error stands).
///
/// ```
/// use face_prep::frame::contact::open_closed_features;
/// use glam::DVec3;
/// // A single triangle has one loop: nothing this opens.
/// let v = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert!(open_closed_features(&v, &[[0, 1, 2]], &[vec![0, 1, 2]]).unwrap().is_none());
/// ```
pub fn open_closed_features(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Result<Option<Opened>, PrepError> {
    match loops.len() {
        // One loop: where no closed mouth and eyes are found, the loop count's error stands
        // (a sheet with one loop need not be meant as a face).
        1 => Ok(open_all_closed(vertices, triangles, loops)),
        2 => lids::open_closed_eyes(vertices, triangles, loops).map(Some),
        3 => {
            let bag = mouth::search_frame(vertices, triangles, loops)
                .and_then(|frame| bag::cut_mouth_bag(vertices, triangles, loops, &frame));
            if let Some(opened) = bag {
                return Ok(Some(opened));
            }
            // Two small loops are the eyes and the mouth is closed, or else one of them is an
            // open mouth and the other an open eye, and the other eye is closed.
            match mouth::open_closed_mouth(vertices, triangles, loops) {
                Ok(opened) => Ok(Some(opened)),
                Err(no_mouth) => lids::open_one_closed_eye(vertices, triangles, loops)
                    .map(Some)
                    .ok_or(no_mouth),
            }
        }
        _ => Ok(None),
    }
}

/// A face with one loop whose mouth and both eyes came closed, opened: the lips' line found
/// from the surface alone ([`mouth::open_closed_mouth_without_eyes`]), then the lids' lines from
/// the mouth; `None` when either is not found.
fn open_all_closed(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Option<Opened> {
    let mouth = mouth::open_closed_mouth_without_eyes(vertices, triangles, loops).ok()?;
    let loops = crate::topology::validate(&mouth.vertices, &mouth.triangles).ok()?;
    if loops.len() != 2 {
        return None;
    }
    let eyes = lids::open_closed_eyes(&mouth.vertices, &mouth.triangles, &loops).ok()?;
    Some(Opened {
        lips: mouth.lips,
        ..eyes
    })
}

/// The mesh's edges for the search: which triangle holds each directed edge, every vertex's
/// neighbours, and which vertices lie on a boundary loop.
pub(crate) struct Surface<'a> {
    vertices: &'a [DVec3],
    triangles: &'a [[u32; 3]],
    directed: HashMap<(u32, u32), usize>,
    neighbours: Vec<Vec<u32>>,
    on_boundary: Vec<bool>,
}

impl<'a> Surface<'a> {
    pub(crate) fn new(
        vertices: &'a [DVec3],
        triangles: &'a [[u32; 3]],
        loops: &[Vec<u32>],
    ) -> Surface<'a> {
        let mut on_boundary = vec![false; vertices.len()];
        for &v in loops.iter().flatten() {
            on_boundary[v as usize] = true;
        }
        let mut directed = HashMap::with_capacity(3 * triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                directed.insert((tri[k], tri[(k + 1) % 3]), t);
            }
        }
        let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); vertices.len()];
        for &(a, b) in directed.keys() {
            neighbours[a as usize].push(b);
        }
        for n in &mut neighbours {
            n.sort_unstable();
            n.dedup();
        }
        Surface {
            vertices,
            triangles,
            directed,
            neighbours,
            on_boundary,
        }
    }

    pub(crate) fn p(&self, v: u32) -> DVec3 {
        self.vertices[v as usize]
    }

    /// Signed fold of the interior edge `a`–`b`: the angle between its two triangles' normals,
    /// positive where the surface folds toward its front (a valley), negative on a ridge;
    /// `None` on a boundary edge.
    pub(crate) fn fold(&self, a: u32, b: u32) -> Option<f64> {
        let t1 = self.triangles[*self.directed.get(&(a, b))?];
        let t2 = self.triangles[*self.directed.get(&(b, a))?];
        let p = |i: u32| self.p(i);
        let normal = |t: [u32; 3]| (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
        let (n1, n2) = (normal(t1), normal(t2));
        let d = t2.into_iter().find(|&v| v != a && v != b).unwrap_or(a);
        let angle = n1.cross(n2).length().atan2(n1.dot(n2));
        Some(if (p(d) - p(a)).dot(n1) > 0.0 {
            angle
        } else {
            -angle
        })
    }

    /// The sharpest valley edge `(fold, a, b)` among interior edges off the boundary whose
    /// midpoint `within` accepts.
    pub(crate) fn sharpest_edge(&self, within: impl Fn(DVec3) -> bool) -> Option<(f64, u32, u32)> {
        self.sharpest_edges(within, 1).into_iter().next()
    }

    /// The `count` sharpest valley edges `(fold, a, b)`, sharpest first, among interior edges
    /// off the boundary whose midpoint `within` accepts.
    pub(crate) fn sharpest_edges(
        &self,
        within: impl Fn(DVec3) -> bool,
        count: usize,
    ) -> Vec<(f64, u32, u32)> {
        let mut edges: Vec<(f64, u32, u32)> = self
            .directed
            .keys()
            .filter(|(a, b)| {
                a < b
                    && !self.on_boundary[*a as usize]
                    && !self.on_boundary[*b as usize]
                    && within(0.5 * (self.p(*a) + self.p(*b)))
            })
            .filter_map(|&(a, b)| self.fold(a, b).map(|f| (f, a, b)))
            .collect();
        edges.sort_by(|x, y| y.0.total_cmp(&x.0).then((x.1, x.2).cmp(&(y.1, y.2))));
        edges.truncate(count);
        edges
    }

    /// How much valley a line holds: the sum over its edges of fold × length.
    pub(crate) fn valley_weight(&self, line: &[u32]) -> f64 {
        line.windows(2)
            .map(|w| {
                self.fold(w[0], w[1]).unwrap_or(0.0).max(0.0) * self.p(w[0]).distance(self.p(w[1]))
            })
            .sum()
    }

    /// The valley line through the seed edge `a`–`b` (folding by `seed_fold`), traced to both
    /// sides along `across` (see the module docs), every vertex accepted by `allowed`; from the
    /// end at −`across` to the end at +`across`.
    pub(crate) fn trace(
        &self,
        (a, b): (u32, u32),
        seed_fold: f64,
        rule: TraceRule,
        across: DVec3,
        front: DVec3,
        allowed: impl Fn(DVec3) -> bool,
    ) -> Vec<u32> {
        let (a, b) = if (self.p(b) - self.p(a)).dot(across) >= 0.0 {
            (a, b)
        } else {
            (b, a)
        };
        let mut in_line = vec![false; self.vertices.len()];
        in_line[a as usize] = true;
        in_line[b as usize] = true;
        let mut walk = |from: u32, sign: f64| -> Vec<u32> {
            let mut out = Vec::new();
            let (mut at, mut sharpest) = (from, seed_fold);
            loop {
                let threshold = (rule.fraction * sharpest).max(rule.least_rad);
                let next = self.neighbours[at as usize]
                    .iter()
                    .copied()
                    .filter(|&w| {
                        let step = self.p(w) - self.p(at);
                        !in_line[w as usize]
                            && !self.on_boundary[w as usize]
                            && sign * step.dot(across) > 0.0
                            && step.dot(front) <= MAX_FORWARD_SLOPE * step.length()
                            && allowed(self.p(w))
                    })
                    .filter_map(|w| self.fold(at, w).map(|f| (f, w)))
                    .filter(|&(f, _)| f >= threshold)
                    .max_by(|x, y| x.0.total_cmp(&y.0).then(y.1.cmp(&x.1)));
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
        let left = walk(a, -1.0);
        let right = walk(b, 1.0);
        left.into_iter().rev().chain([a, b]).chain(right).collect()
    }
}

/// Cuts `triangles` open along `line` (a path of interior vertices; its ends stay shared): the
/// triangles on the `down` side of the line get copies of its inner vertices, appended to
/// `vertices` and moved [`SEPARATION_REL`] of the face's size along `down`.
pub(crate) fn cut(
    vertices: &mut Vec<DVec3>,
    triangles: &mut [[u32; 3]],
    line: &[u32],
    down: DVec3,
) -> ContactLine {
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
        let find = |x: u32, y: u32| {
            vertex_triangles[w[0] as usize]
                .iter()
                .copied()
                .find(|&t| holds_directed(t, x, y))
        };
        if let (Some(l), Some(r)) = (find(w[0], w[1]), find(w[1], w[0])) {
            left_lower += (centroid(l) - centroid(r)).dot(down);
        }
    }
    let lower_of = |a: u32, b: u32| -> Option<usize> {
        let (x, y) = if left_lower > 0.0 { (a, b) } else { (b, a) };
        vertex_triangles[a as usize]
            .iter()
            .copied()
            .find(|&t| holds_directed(t, x, y))
    };
    // Every lower triangle of every inner vertex, found before any corner is replaced.
    let mut replace: Vec<(usize, u32)> = Vec::new();
    for i in 1..line.len() - 1 {
        let (prev, v, next) = (line[i - 1], line[i], line[i + 1]);
        // Flood the fan of `v` from the lower triangles of its two line edges, across edges of
        // `v` that are not on the line: the fan's triangles by the vertex they share with `v`
        // (each edge of a manifold fan has two), so the flood is linear in the fan's size.
        let fan = &vertex_triangles[v as usize];
        let mut by_edge: HashMap<u32, Vec<usize>> = HashMap::with_capacity(2 * fan.len());
        for &t in fan {
            for &x in &triangles[t] {
                if x != v {
                    by_edge.entry(x).or_default().push(t);
                }
            }
        }
        let mut stack: Vec<usize> = [lower_of(prev, v), lower_of(v, next)]
            .into_iter()
            .flatten()
            .collect();
        let mut seen: std::collections::HashSet<usize> = std::collections::HashSet::new();
        while let Some(t) = stack.pop() {
            if !seen.insert(t) {
                continue;
            }
            for &x in &triangles[t] {
                if x == v || x == prev || x == next {
                    continue;
                }
                for &u in by_edge.get(&x).into_iter().flatten() {
                    if !seen.contains(&u) {
                        stack.push(u);
                    }
                }
            }
        }
        let mut seen: Vec<usize> = seen.into_iter().collect();
        seen.sort_unstable();
        replace.extend(seen.into_iter().map(|t| (t, v)));
    }
    let (lo, hi) = crate::frame::topology::bounding_box(vertices.iter().copied());
    let separation = SEPARATION_REL * (hi - lo).length() * down;
    let mut lower = Vec::with_capacity(line.len().saturating_sub(2));
    let mut copy_of: HashMap<u32, u32> = HashMap::new();
    for &v in &line[1..line.len() - 1] {
        let copy = vertices.len() as u32;
        vertices.push(vertices[v as usize] + separation);
        lower.push(copy);
        copy_of.insert(v, copy);
    }
    for (t, v) in replace {
        if let Some(&copy) = copy_of.get(&v) {
            for c in &mut triangles[t] {
                if *c == v {
                    *c = copy;
                }
            }
        }
    }
    ContactLine {
        upper: line.to_vec(),
        lower,
    }
}
