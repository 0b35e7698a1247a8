//! Parts that ride on the lids (lashes, eye occlusion layers, tear film): each rooted in the
//! lid, moving rigidly with its root and turned about the eye's centre as the lid turns.
//!
//! A lash is a card that stands out of the lid margin up to a centimetre. When each of its
//! vertices took the motion of the skin vertex it lay nearest, the root took the margin's motion
//! and the tip that of skin elsewhere on the lid (or none), so in ICT-FaceKit's head the upper
//! lashes' edges stretched up to 3.2 times and shrank to half in `eyeBlinkLeft`, and the strip
//! crumpled at the corners of the closed eye. Now:
//!
//! - **the root:** the vertices of a lid part that lie within [`ROOT_BAND_IOD`] of the part's
//!   closest approach to the skin; every other vertex of the part is attached to the root vertex
//!   it reaches first along the part's own edges (as a hair to its follicle), and through it to
//!   the skin vertex nearest that root ([`lid_part_roots`]);
//! - **the turn:** the lid slides over the eyeball, so near an eye the attached vertex moves as
//!   a rigid body that follows its skin vertex and turns with it about the eye's centre (the
//!   shortest rotation taking the skin vertex's direction from the centre in the neutral to its
//!   direction in the target), applied after the targets are mixed
//!   ([`crate::transfer::eye_contact::EyeContact::apply`]); away from the eyes, and in each
//!   control's own linear field, it moves with its skin vertex.

use face_prep::parts::{HeadParts, PartKind, Scene};
use glam::{DQuat, DVec3};

use super::nearest::PointTree;

/// How far beyond a lid part's closest approach to the skin its vertices count as its root, in
/// interocular distances: 0.005 (0.3 mm on an adult head). ICT-FaceKit's lashes start on the
/// skin (0 mm); its eye blend layer comes no nearer than 0.18 mm.
pub const ROOT_BAND_IOD: f64 = 0.005;

/// For every vertex of a lid part of `parts`, the skin vertex it rides on (see the module
/// documentation); `None` for every other vertex. `skin` finds the nearest skin vertex to a
/// point; `iod` is the head's interocular distance.
///
/// ```
/// use facebem::transfer::lid_riders::lid_part_roots;
/// use facebem::transfer::nearest::PointTree;
/// use face_prep::parts::{Component, HeadParts, PartKind, Scene};
/// use glam::DVec3;
/// // Skin vertices 0 and 1; a lash strip 2-3-4-5 standing up from the skin at x = 0 and 1.
/// let positions = vec![
///     DVec3::ZERO, DVec3::X, // skin
///     DVec3::ZERO, DVec3::X, // the lash's root, on the skin
///     DVec3::new(0.0, 0.0, 0.5), DVec3::new(1.0, 0.0, 0.5), // its tip
/// ];
/// let triangles = vec![[2, 3, 5], [2, 5, 4]];
/// let lash = Component { triangles: vec![0, 1], vertices: vec![2, 3, 4, 5] };
/// let parts = HeadParts {
///     components: vec![lash],
///     kinds: vec![PartKind::LidPart],
///     eyeballs: None,
///     frame: None,
/// };
/// let scene = Scene { positions: positions.clone(), triangles, ..Default::default() };
/// let skin = PointTree::new([(0, positions[0]), (1, positions[1])]);
/// let roots = lid_part_roots(&scene, &parts, &skin, 1.0);
/// // Each tip rides on the skin under its own root, not on whatever skin lies nearest.
/// assert_eq!(&roots[2..], &[Some(0), Some(1), Some(0), Some(1)]);
/// ```
pub fn lid_part_roots(
    scene: &Scene,
    parts: &HeadParts,
    skin: &PointTree,
    iod: f64,
) -> Vec<Option<u32>> {
    let p = &scene.positions;
    let mut sources: Vec<(u32, u32)> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    for comp in parts.of_kind(PartKind::LidPart) {
        let nearest: Vec<(u32, u32, f64)> = comp
            .vertices
            .iter()
            .filter_map(|&v| {
                let (s, d) = skin.nearest(*p.get(v as usize)?)?;
                Some((v, s, d))
            })
            .collect();
        let closest = nearest.iter().map(|n| n.2).fold(f64::INFINITY, f64::min);
        sources.extend(
            nearest
                .iter()
                .filter(|n| n.2 <= closest + ROOT_BAND_IOD * iod)
                .map(|n| (n.0, n.1)),
        );
        triangles.extend(
            comp.triangles
                .iter()
                .filter_map(|&t| scene.triangles.get(t as usize).copied()),
        );
    }
    let reached = super::along_surface::nearest_source(p, &triangles, &sources);
    let mut roots = vec![None; p.len()];
    for comp in parts.of_kind(PartKind::LidPart) {
        for &v in &comp.vertices {
            let Some(root) = roots.get_mut(v as usize) else {
                continue;
            };
            // A vertex its part's edges do not reach from the root (a loose point) rides on
            // the skin it lies nearest.
            *root = reached
                .get(v as usize)
                .copied()
                .flatten()
                .map(|(s, _)| s)
                .or_else(|| skin.nearest(p[v as usize]).map(|(s, _)| s));
        }
    }
    roots
}

/// The displacement of a vertex at `vertex` (neutral) riding on a skin vertex at `skin`
/// (neutral) that moves by `skin_motion`, turned about an eye's `centre` with it: the vertex
/// follows the skin vertex and turns by the shortest rotation that takes the skin vertex's
/// direction from the centre to its new one (a translation when either direction is zero).
///
/// ```
/// use facebem::transfer::lid_riders::ride;
/// use glam::DVec3;
/// // The skin vertex turns a quarter turn about the centre (0 → +z to +y); the lash standing
/// // out of it along +z now stands along +y.
/// let (skin, lash) = (DVec3::Z, DVec3::new(0.0, 0.0, 1.5));
/// let moved = lash + ride(lash, skin, DVec3::Y - DVec3::Z, DVec3::ZERO);
/// assert!(moved.distance(DVec3::new(0.0, 1.5, 0.0)) < 1e-12);
/// ```
pub fn ride(vertex: DVec3, skin: DVec3, skin_motion: DVec3, centre: DVec3) -> DVec3 {
    let moved = skin + skin_motion;
    let (from, to) = (
        (skin - centre).normalize_or_zero(),
        (moved - centre).normalize_or_zero(),
    );
    if from == DVec3::ZERO || to == DVec3::ZERO {
        return skin_motion;
    }
    let turn = DQuat::from_rotation_arc(from, to);
    moved + turn * (vertex - skin) - vertex
}
