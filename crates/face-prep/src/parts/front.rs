//! The front face of a head, cut from its skin (issue 32, item 3, first method): the part of the
//! skin in front of the ears, between the forehead and under the chin, with the eye sockets'
//! linings and the mouth's lining taken out, so that what is left is a face of four openings
//! (contour, two eyes, mouth) the rig is built on.
//!
//! All lengths are proportions of the head's own measures, found from its parts: the distance
//! between the eyeballs' centres (`iod`) and their radius `r`.
//!
//! - **Outline**: a skin triangle is kept when its centroid lies less than
//!   [`BEHIND_EYES`]` · iod` behind the eyes' centres (in front of the ears), less than
//!   [`BELOW_EYES`]` · iod` below them (under the chin: in adults the chin is about 1.9 iod
//!   below the eyes) and less than [`ABOVE_EYES`]` · iod` above them (the forehead).
//! - **Eye openings**: triangles whose corners all lie within [`SOCKET`]` · r` of an eyeball's
//!   centre line its socket (they hug the eyeball) and are taken out; the lids stay.
//! - **Mouth opening**: triangles with a corner within [`MOUTH_LINING`]` · r` of a tooth, the
//!   gums or the tongue line the mouth and are taken out; the lips stay.
//! - Where the cut passes through a vertex and leaves two pieces touching there, the smaller
//!   pieces' triangles at that vertex are dropped; the largest connected piece left is the
//!   front face.
//!
//! On ICT-FaceKit's head (eyeball radius 1.58 cm, iod 6.23 cm) the lining distance is 5 mm:
//! 3 mm leaves a vertex where two openings touch, 8 mm takes the nostrils and the lips
//! (journal, 2026-11-28). Finding the lip margin on the skin itself would not depend on it.

use std::collections::HashMap;

use glam::DVec3;

use super::{HeadParts, PartKind, Scene};

/// How far behind the eyes' centres the front face reaches, in interocular distances.
pub const BEHIND_EYES: f64 = 1.1;
/// How far below the eyes' centres, in interocular distances.
pub const BELOW_EYES: f64 = 2.3;
/// How far above the eyes' centres, in interocular distances.
pub const ABOVE_EYES: f64 = 1.4;
/// Radius around an eyeball's centre within which the skin lines its socket, in eyeball radii.
pub const SOCKET: f64 = 1.08;
/// Distance from the mouth's parts within which the skin lines the mouth, in eyeball radii.
pub const MOUTH_LINING: f64 = 0.32;

/// Rounds of bow-tie removal (one or two suffice on a real cut).
pub const MAX_BOW_TIE_ROUNDS: usize = 64;

/// A front face cut from a head's skin.
#[derive(Clone, Debug, PartialEq)]
pub struct FrontFace {
    /// Its vertices (positions of the scene).
    pub positions: Vec<DVec3>,
    /// Its triangles, indexing [`FrontFace::positions`].
    pub triangles: Vec<[u32; 3]>,
    /// Per vertex, the scene vertex it is.
    pub scene_vertex: Vec<u32>,
}

/// Why no front face could be cut.
#[derive(Clone, Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum FrontFaceError {
    /// No eyeballs were found: the eye openings and the outline cannot be placed.
    #[error(
        "no eyeballs found (two closed spheres of an eye's size): the face cannot be placed on the skin"
    )]
    NoEyeballs,
    /// Nothing of the skin is left.
    #[error("no skin is left in front of the eyes")]
    Empty,
}

/// Cuts the front face from the skin of `scene` (see the module documentation).
pub fn front_face(scene: &Scene, parts: &HeadParts) -> Result<FrontFace, FrontFaceError> {
    let (Some([l, r]), Some(frame)) = (parts.eyeballs, parts.frame) else {
        return Err(FrontFaceError::NoEyeballs);
    };
    let iod = l.centre.distance(r.centre);
    let radius = 0.5 * (l.radius + r.radius);
    let mid = 0.5 * (l.centre + r.centre);
    let p = |v: u32| scene.positions[v as usize];
    let mouth_parts: Vec<DVec3> = parts
        .components
        .iter()
        .zip(&parts.kinds)
        .filter(|(_, k)| {
            matches!(
                k,
                PartKind::UpperTooth | PartKind::LowerTooth | PartKind::GumsAndTongue
            )
        })
        .flat_map(|(c, _)| c.vertices.iter().map(|&v| p(v)))
        .collect();
    let lining = MOUTH_LINING * radius;
    let near_mouth = NearPoints::new(&mouth_parts, lining);
    // A glTF's UV seams split the skin's vertices: the cut is made on the surface, each
    // corner at the first vertex of its coordinates (Scene::first_at_same_place).
    let first = scene.first_at_same_place();
    let kept: Vec<[u32; 3]> = parts
        .of_kind(PartKind::Skin)
        .flat_map(|c| c.triangles.iter().map(|&t| scene.triangles[t as usize]))
        .map(|t| t.map(|v| first.get(v as usize).copied().unwrap_or(v)))
        .filter(|t| {
            let corners = t.map(p);
            let d = (corners[0] + corners[1] + corners[2]) / 3.0 - mid;
            let outline = d.dot(frame.forward) > -BEHIND_EYES * iod
                && d.dot(frame.up) > -BELOW_EYES * iod
                && d.dot(frame.up) < ABOVE_EYES * iod;
            let socket = [l, r].iter().any(|e| {
                corners
                    .iter()
                    .all(|q| q.distance(e.centre) < SOCKET * e.radius)
            });
            let mouth = corners.iter().any(|q| near_mouth.any_within(*q));
            outline && !socket && !mouth
        })
        .collect();
    largest_piece(scene, &without_bow_ties(kept)).ok_or(FrontFaceError::Empty)
}

/// `triangles` with every vertex made manifold: where the triangles around a vertex form several
/// fans (a cut passing through the vertex left two pieces touching there), only the largest fan
/// keeps it; the others are dropped. Repeated until no vertex has two fans, at most
/// [`MAX_BOW_TIE_ROUNDS`] times (the face reader refuses what is left, naming the vertex).
fn without_bow_ties(mut triangles: Vec<[u32; 3]>) -> Vec<[u32; 3]> {
    for _round in 0..MAX_BOW_TIE_ROUNDS {
        let mut around: HashMap<u32, Vec<usize>> = HashMap::new();
        for (i, t) in triangles.iter().enumerate() {
            for &v in t {
                around.entry(v).or_default().push(i);
            }
        }
        let mut drop = vec![false; triangles.len()];
        for (&v, fan) in &around {
            let fans = fans_around(v, fan, &triangles);
            if fans.len() > 1
                && let Some(largest) = fans.iter().map(Vec::len).max()
            {
                let keep = fans.iter().position(|f| f.len() == largest).unwrap_or(0);
                for (k, f) in fans.iter().enumerate() {
                    if k != keep {
                        f.iter().for_each(|&i| drop[i] = true);
                    }
                }
            }
        }
        if !drop.contains(&true) {
            break;
        }
        let mut i = 0;
        triangles.retain(|_| {
            i += 1;
            !drop[i - 1]
        });
    }
    triangles
}

/// The triangles around vertex `v` (indices `around`) grouped into fans: triangles sharing an
/// edge at `v` are in the same fan.
fn fans_around(v: u32, around: &[usize], triangles: &[[u32; 3]]) -> Vec<Vec<usize>> {
    let mut fans: Vec<Vec<usize>> = Vec::new();
    let mut fan_of = vec![usize::MAX; around.len()];
    for start in 0..around.len() {
        if fan_of[start] != usize::MAX {
            continue;
        }
        let id = fans.len();
        fans.push(Vec::new());
        let mut stack = vec![start];
        fan_of[start] = id;
        while let Some(k) = stack.pop() {
            fans[id].push(around[k]);
            let others = |t: usize| triangles[t].into_iter().filter(move |&w| w != v);
            for j in 0..around.len() {
                if fan_of[j] == usize::MAX
                    && others(around[k]).any(|w| others(around[j]).any(|x| x == w))
                {
                    fan_of[j] = id;
                    stack.push(j);
                }
            }
        }
    }
    fans
}

/// The largest edge-connected piece of `triangles`, renumbered.
fn largest_piece(scene: &Scene, triangles: &[[u32; 3]]) -> Option<FrontFace> {
    let mut parent: HashMap<u32, u32> = HashMap::new();
    fn find(parent: &mut HashMap<u32, u32>, a: u32) -> u32 {
        let mut root = a;
        while let Some(&up) = parent.get(&root).filter(|&&up| up != root) {
            root = up;
        }
        // Path compression: every vertex on the way points at the root.
        let mut v = a;
        while v != root {
            let up = parent.insert(v, root).unwrap_or(root);
            v = up;
        }
        root
    }
    for t in triangles {
        for &v in t {
            parent.entry(v).or_insert(v);
        }
        for &v in &t[1..] {
            let (a, b) = (find(&mut parent, t[0]), find(&mut parent, v));
            if a != b {
                parent.insert(a.max(b), a.min(b));
            }
        }
    }
    let mut size: HashMap<u32, usize> = HashMap::new();
    let roots: Vec<u32> = triangles.iter().map(|t| find(&mut parent, t[0])).collect();
    for &r in &roots {
        *size.entry(r).or_default() += 1;
    }
    let (&best, _) = size
        .iter()
        .max_by_key(|(r, n)| (**n, std::cmp::Reverse(**r)))?;
    let mut index: HashMap<u32, u32> = HashMap::new();
    let mut face = FrontFace {
        positions: Vec::new(),
        triangles: Vec::new(),
        scene_vertex: Vec::new(),
    };
    for (t, _) in triangles.iter().zip(&roots).filter(|(_, r)| **r == best) {
        let tri = t.map(|v| {
            *index.entry(v).or_insert_with(|| {
                face.positions.push(scene.positions[v as usize]);
                face.scene_vertex.push(v);
                face.scene_vertex.len() as u32 - 1
            })
        });
        face.triangles.push(tri);
    }
    Some(face)
}

/// Points binned in a grid of cells `radius` wide, for "is any point within `radius`".
struct NearPoints<'a> {
    points: &'a [DVec3],
    radius: f64,
    cells: HashMap<[i64; 3], Vec<u32>>,
}

impl<'a> NearPoints<'a> {
    fn new(points: &'a [DVec3], radius: f64) -> Self {
        let mut cells: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        if radius > 0.0 {
            for (i, q) in points.iter().enumerate() {
                cells
                    .entry(Self::cell(*q, radius))
                    .or_default()
                    .push(i as u32);
            }
        }
        NearPoints {
            points,
            radius,
            cells,
        }
    }

    fn cell(q: DVec3, radius: f64) -> [i64; 3] {
        (q / radius).floor().as_i64vec3().to_array()
    }

    fn any_within(&self, q: DVec3) -> bool {
        if self.cells.is_empty() {
            return false;
        }
        let [x, y, z] = Self::cell(q, self.radius);
        (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dz| {
                    self.cells.get(&[x + dx, y + dy, z + dz]).is_some_and(|c| {
                        c.iter()
                            .any(|&i| self.points[i as usize].distance(q) < self.radius)
                    })
                })
            })
        })
    }
}
