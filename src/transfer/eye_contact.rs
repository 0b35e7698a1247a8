//! The lids rest on the eyeballs: no target of a whole head may push skin into an eyeball
//! (issue 32: "no eyeball vertex passes through the lids").
//!
//! The skin around an eye is carried from the front face's rig (the lids, simulated on a shell
//! that does not know the eyeball is there) or turned about the eye's centre with the gaze
//! ([`super::gaze`]), while the eyeball itself is rigid and, in the gaze targets, turns with
//! its cornea's bulge under the lids. Either can bring skin inside the eyeball: a squint's lower
//! lid pushed up and back, a lid margin that stays at its distance from the centre while the
//! cornea turns under it. Like a contact constraint in cloth or skin simulation (the
//! eyeball as a rigid collider, e.g. Bridson, Fedkiw & Anderson, *Robust treatment of
//! collisions, contact and friction for cloth animation*, SIGGRAPH 2002), each target is
//! corrected after the fact: a skin vertex that would come nearer the eyeball than it lies in
//! the neutral, and nearer than the sagitta of its longest edge over the cornea's curvature
//! (so that the flat triangles between vertices on the eyeball do not dip into it), is moved
//! out along the ray from the eye's centre. The eyeball's surface in a direction is the
//! distance from the centre of the eyeball vertex nearest that direction, as the target leaves
//! the eyeball (the cornea's bulge included). Skin that lies inside the eyeball already in the
//! neutral (ICT-FaceKit's inner lids and socket linings are modelled a little through the
//! sclera) may stay as deep as it starts, no deeper, and a target that does not move the skin
//! near an eye leaves it where it is. Parts that follow the skin (lashes, occlusion layers)
//! ride on the corrected skin, turned with it about the eye's centre ([`super::lid_riders`]).

use face_prep::parts::{HeadParts, PartKind, Scene};
use glam::DVec3;

use super::nearest::PointTree;

/// How far from an eye's centre, in its radii, skin is checked against the eyeball.
pub const CONTACT_REACH: f64 = 1.5;

/// The cornea's radius of curvature, in eyeball radii: 7.8 mm on an eyeball of 12 mm (adult
/// means), the tightest curve a lid lies over.
pub const CORNEA_CURVATURE: f64 = 0.65;

/// One eye: its centre, its eyeball's vertices, and the skin near it with the clearance each
/// vertex keeps from the eyeball (the smaller of its neutral one and its edges' sagitta;
/// negative: how deep inside it may stay).
#[derive(Clone, Debug, PartialEq)]
struct Eye {
    centre: DVec3,
    eyeball: Vec<u32>,
    skin: Vec<(u32, f64)>,
    /// The skin's triangles within reach (scene vertices).
    triangles: Vec<[u32; 3]>,
    /// Per eyeball vertex: whether skin already lies between it and the centre in the
    /// neutral (those are left to the vertex pass).
    covered: Vec<bool>,
}

/// The eyes of a head and the skin that rests on them; [`EyeContact::apply`] corrects a
/// target.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct EyeContact {
    eyes: Vec<Eye>,
    /// (vertex, skin vertex it follows, eye): lid parts and other parts near the eyes, which
    /// ride on their skin vertex turned about the eye's centre ([`super::lid_riders::ride`]).
    followers: Vec<(u32, u32, usize)>,
}

impl EyeContact {
    /// The eyes of `parts` in `scene`; `follows` gives, per vertex, the skin vertex a part that
    /// follows the skin takes its motion from (`None` for the rest). Empty without eyeballs.
    pub fn new(scene: &Scene, parts: &HeadParts, follows: &[Option<u32>]) -> EyeContact {
        let Some(spheres) = parts.eyeballs else {
            return EyeContact::default();
        };
        let p = &scene.positions;
        let mut longest = vec![0.0f64; p.len()];
        for comp in parts.of_kind(PartKind::Skin) {
            for &t in &comp.triangles {
                let [a, b, c] = scene.triangles[t as usize];
                for (x, y) in [(a, b), (b, c), (c, a)] {
                    let l = p[x as usize].distance(p[y as usize]);
                    longest[x as usize] = longest[x as usize].max(l);
                    longest[y as usize] = longest[y as usize].max(l);
                }
            }
        }
        let mut eyes = Vec::new();
        for (side, sphere) in [face_prep::parts::Side::Left, face_prep::parts::Side::Right]
            .into_iter()
            .zip(spheres)
        {
            let eyeball: Vec<u32> = parts
                .of_kind(PartKind::Eyeball(side))
                .flat_map(|c| c.vertices.iter().copied())
                .collect();
            if eyeball.is_empty() {
                continue;
            }
            let c = sphere.centre;
            let surface = Surface::new(c, eyeball.iter().map(|&v| p[v as usize]));
            // A flat triangle between vertices on the eyeball dips into it by its sagitta:
            // each vertex keeps the clearance of its longest edge's over a sphere of the
            // cornea's curvature.
            let curvature = CORNEA_CURVATURE * sphere.radius;
            let skin: Vec<(u32, f64)> = parts
                .of_kind(PartKind::Skin)
                .flat_map(|comp| comp.vertices.iter().copied())
                .filter(|&v| p[v as usize].distance(c) < CONTACT_REACH * sphere.radius)
                .map(|v| {
                    let edge = longest[v as usize];
                    let sag = edge * edge / (8.0 * curvature);
                    (v, surface.clearance(p[v as usize]).min(sag))
                })
                .collect();
            let reach = CONTACT_REACH * sphere.radius;
            let triangles: Vec<[u32; 3]> = parts
                .of_kind(PartKind::Skin)
                .flat_map(|comp| comp.triangles.iter().map(|&t| scene.triangles[t as usize]))
                .filter(|t| t.iter().all(|&v| p[v as usize].distance(c) < reach))
                .collect();
            let covered = crossings(c, &eyeball, &triangles, &|v| p[v as usize])
                .iter()
                .map(|x| x.is_some())
                .collect();
            eyes.push(Eye {
                centre: c,
                eyeball,
                skin,
                triangles,
                covered,
            });
        }
        let near: std::collections::HashMap<u32, usize> = eyes
            .iter()
            .enumerate()
            .flat_map(|(k, e)| e.skin.iter().map(move |&(v, _)| (v, k)))
            .collect();
        let followers = follows
            .iter()
            .enumerate()
            .filter_map(|(v, s)| {
                let s = (*s)?;
                near.get(&s).map(|&eye| (v as u32, s, eye))
            })
            .collect();
        EyeContact { eyes, followers }
    }

    /// Keeps the skin near each eye off the eyeball in `field` (displacements of the head's
    /// vertices at `neutral`): first every skin vertex that would come nearer the eyeball than
    /// its kept clearance is moved out along the ray from the eye's centre; then, for up to
    /// four rounds, the corners of every skin triangle the eyeball still comes through are
    /// pushed out by how far, spread over the rings around them. Followers ride on their
    /// skin vertex, turned with it about the eye's centre ([`super::lid_riders::ride`]). Returns how many vertex moves were made (0: the target left the eyes alone).
    ///
    /// ```
    /// use facebem::transfer::eye_contact::EyeContact;
    /// let none = EyeContact::default();
    /// let mut field = vec![glam::DVec3::X; 3];
    /// assert_eq!(none.apply(&[glam::DVec3::ZERO; 3], &mut field), 0);
    /// ```
    pub fn apply(&self, neutral: &[DVec3], field: &mut [DVec3]) -> usize {
        let mut moved = 0;
        for eye in &self.eyes {
            let at = |v: u32| neutral[v as usize] + field[v as usize];
            let surface = Surface::new(eye.centre, eye.eyeball.iter().map(|&v| at(v)));
            let corrected: Vec<(u32, DVec3)> = eye
                .skin
                .iter()
                .filter_map(|&(v, keep)| {
                    let q = at(v);
                    let inside = keep - surface.clearance(q);
                    (inside > 0.0).then(|| {
                        let out = (q - eye.centre).normalize_or_zero() * inside;
                        (v, field[v as usize] + out)
                    })
                })
                .collect();
            moved += corrected.len();
            for (v, d) in corrected {
                field[v as usize] = d;
            }
            // Faces: an eyeball vertex (the cornea's apex between lid vertices) that comes out
            // through a skin triangle pushes that triangle's corners out by how far it came.
            for _ in 0..FACE_ROUNDS {
                let at = |v: u32| neutral[v as usize] + field[v as usize];
                let hits = crossings(eye.centre, &eye.eyeball, &eye.triangles, &at);
                let mut push: std::collections::HashMap<u32, f64> = Default::default();
                for (k, hit) in hits.iter().enumerate() {
                    let Some((t, depth)) = *hit else { continue };
                    if eye.covered[k] {
                        continue;
                    }
                    for v in eye.triangles[t] {
                        let e = push.entry(v).or_insert(0.0);
                        *e = e.max(depth + FACE_MARGIN * depth.max(1e-9));
                    }
                }
                if push.is_empty() {
                    break;
                }
                // Spread over the lid, so the cornea lifts it as a bump, not a spike.
                for _ in 0..SPREAD_RINGS {
                    let mut wider = push.clone();
                    for t in &eye.triangles {
                        let most = t
                            .iter()
                            .filter_map(|v| push.get(v))
                            .fold(0.0f64, |a, &b| a.max(b));
                        if most > 0.0 {
                            for &v in t {
                                let e = wider.entry(v).or_insert(0.0);
                                *e = e.max(SPREAD_FACTOR * most);
                            }
                        }
                    }
                    push = wider;
                }
                moved += push.len();
                let outward: Vec<(u32, DVec3)> = push
                    .into_iter()
                    .map(|(v, d)| (v, (at(v) - eye.centre).normalize_or_zero() * d))
                    .collect();
                for (v, out) in outward {
                    field[v as usize] += out;
                }
            }
        }
        for &(v, s, eye) in &self.followers {
            let (Some(&at_v), Some(&at_s), Some(eye)) = (
                neutral.get(v as usize),
                neutral.get(s as usize),
                self.eyes.get(eye),
            ) else {
                continue;
            };
            field[v as usize] = super::lid_riders::ride(at_v, at_s, field[s as usize], eye.centre);
        }
        moved
    }
}

/// Rounds of the face pass (each pushes the triangles the eyeball still comes through).
const FACE_ROUNDS: usize = 4;

/// Extra push of a face pass, as a fraction of the depth found.
const FACE_MARGIN: f64 = 0.1;

/// Rings of neighbours a face pass's push spreads over, and the share it keeps per ring.
const SPREAD_RINGS: usize = 5;
const SPREAD_FACTOR: f64 = 0.75;

/// Per eyeball vertex (positions by `at`): the skin triangle (index into `triangles`) that the
/// segment from `centre` to it crosses farthest from it, and how far that crossing lies
/// inside the vertex; `None` when it crosses none.
fn crossings(
    centre: DVec3,
    eyeball: &[u32],
    triangles: &[[u32; 3]],
    at: &dyn Fn(u32) -> DVec3,
) -> Vec<Option<(usize, f64)>> {
    let corners: Vec<[DVec3; 3]> = triangles.iter().map(|t| t.map(at)).collect();
    if corners.is_empty() {
        return vec![None; eyeball.len()];
    }
    let bvh = face_prep::bvh::TriangleBvh::new(&corners);
    eyeball
        .iter()
        .map(|&e| {
            let q = at(e);
            bvh.overlapping(centre.min(q), centre.max(q))
                .into_iter()
                .filter_map(|t| {
                    segment_hit(centre, q, &corners[t as usize])
                        .map(|s| (t as usize, (1.0 - s) * q.distance(centre)))
                })
                .max_by(|a, b| a.1.total_cmp(&b.1))
        })
        .collect()
}

/// Where the segment from `a` to `b` crosses the triangle `t`, as a fraction of its length
/// from `a` (Möller–Trumbore); `None` when it does not or lies in its plane.
fn segment_hit(a: DVec3, b: DVec3, t: &[DVec3; 3]) -> Option<f64> {
    let (e1, e2, d) = (t[1] - t[0], t[2] - t[0], b - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() <= 1e-12 * e1.length() * e2.length() * d.length() {
        return None;
    }
    let s = a - t[0];
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = d.dot(q) / det;
    let along = e2.dot(q) / det;
    ((0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && (0.0..=1.0).contains(&along))
        .then_some(along)
}

/// An eyeball's surface seen from its centre: the distance of its vertex nearest each
/// direction.
struct Surface {
    centre: DVec3,
    directions: PointTree,
    radii: Vec<f64>,
}

impl Surface {
    fn new(centre: DVec3, points: impl Iterator<Item = DVec3>) -> Surface {
        let (units, radii): (Vec<DVec3>, Vec<f64>) = points
            .map(|q| ((q - centre).normalize_or_zero(), q.distance(centre)))
            .unzip();
        Surface {
            centre,
            directions: PointTree::new(units.into_iter().enumerate().map(|(i, u)| (i as u32, u))),
            radii,
        }
    }

    /// How far `q` lies outside the surface along the ray from the centre (negative: inside).
    fn clearance(&self, q: DVec3) -> f64 {
        let u = (q - self.centre).normalize_or_zero();
        let r = self
            .directions
            .nearest(u)
            .map_or(0.0, |(i, _)| self.radii[i as usize]);
        q.distance(self.centre) - r
    }
}
