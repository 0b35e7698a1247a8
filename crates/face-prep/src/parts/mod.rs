//! The parts of a head or avatar, found from the geometry (issue 32, items 1 and 2): a file is
//! read whole ([`Scene`]), split into connected components, and each component is given a part:
//!
//! - **skin**: the component with the largest area;
//! - **eyeballs**: closed components whose surface fits a sphere (algebraic least-squares fit,
//!   RMS distance below [`SPHERE_FIT_TOLERANCE`] of the radius) of a radius between 1 % and 8 %
//!   of the skin's extent (twice its largest distance from its centroid); components sharing a centre (a sclera and an iris)
//!   make one eyeball, and the two largest of similar radius (within 25 %) are the eyes;
//! - **teeth**: the closed components at most one and a half eyeball diameters long (a tooth
//!   with its roots) whose centres lie more than an eyeball diameter below the eyes, when there
//!   are at least four; split into the upper and the lower row at the widest gap
//!   of their heights;
//! - **gums and tongue**: the other components, larger than a tooth, centred within the ball
//!   around the teeth that holds them all;
//! - **lid parts** (lashes, eye occlusion, tear film): components lying within two eyeball radii
//!   of an eyeball's centre;
//! - **other**: the rest (they will follow the skin under them).
//!
//! Directions come from the parts too: the eyes' axis is left–right, "up" points from the teeth
//! (or, without teeth, from the skin's centroid) to the eyes, "forward" from the skin's centroid
//! to the eyes; the subject's left is `up × forward`. Names and materials are reported but never
//! required.

pub mod front;
mod scene;
mod sphere;

pub use front::{FrontFace, FrontFaceError, front_face};
pub use scene::{Component, GltfMeshPlacement, PrimitivePlacement, Scene, VertexSource};
pub use sphere::{Sphere, fit_sphere};

use glam::DVec3;

/// Largest RMS distance of a component's vertices from its fitted sphere, as a fraction of the
/// radius, for it to count as an eyeball's surface (a cornea's bulge is a few per cent).
pub const SPHERE_FIT_TOLERANCE: f64 = 0.08;

/// Which side of the subject.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// The subject's own left.
    Left,
    /// The subject's own right.
    Right,
}

/// What a component is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PartKind {
    /// The skin (face, and scalp and neck when they are there).
    Skin,
    /// An eyeball (all its components: sclera, iris, cornea).
    Eyeball(Side),
    /// A tooth of the upper row.
    UpperTooth,
    /// A tooth of the lower row.
    LowerTooth,
    /// Gums, tongue or the inside of the mouth, as separate components.
    GumsAndTongue,
    /// A small part at the lids: lashes, eye occlusion, tear film.
    LidPart,
    /// Anything else.
    Other,
}

impl PartKind {
    /// What `facebem info` calls it.
    pub fn describe(self) -> &'static str {
        match self {
            PartKind::Skin => "skin",
            PartKind::Eyeball(Side::Left) => "eyeball (subject's left)",
            PartKind::Eyeball(Side::Right) => "eyeball (subject's right)",
            PartKind::UpperTooth => "upper teeth",
            PartKind::LowerTooth => "lower teeth",
            PartKind::GumsAndTongue => "gums and tongue",
            PartKind::LidPart => "lid parts (lashes, occlusion, tear film)",
            PartKind::Other => "other (follows the skin under it)",
        }
    }
}

/// The head's directions, found from its parts (unit vectors, the file's frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadFrame {
    /// Toward the subject's own left.
    pub left: DVec3,
    /// Up.
    pub up: DVec3,
    /// The way the face looks.
    pub forward: DVec3,
}

/// The parts found in a [`Scene`].
#[derive(Clone, Debug, PartialEq)]
pub struct HeadParts {
    /// The connected components, largest first.
    pub components: Vec<Component>,
    /// What each component is.
    pub kinds: Vec<PartKind>,
    /// The eyeballs' spheres (left, right), when found.
    pub eyeballs: Option<[Sphere; 2]>,
    /// The directions, when the eyeballs were found.
    pub frame: Option<HeadFrame>,
}

impl HeadParts {
    /// The components that are `kind`.
    ///
    /// ```
    /// use face_prep::parts::{Component, HeadParts, PartKind};
    /// let c = |v: u32| Component { triangles: vec![], vertices: vec![v] };
    /// let parts = HeadParts {
    ///     components: vec![c(0), c(1), c(2)],
    ///     kinds: vec![PartKind::Skin, PartKind::LidPart, PartKind::LidPart],
    ///     eyeballs: None,
    ///     frame: None,
    /// };
    /// let lids: Vec<u32> = parts.of_kind(PartKind::LidPart).map(|c| c.vertices[0]).collect();
    /// assert_eq!(lids, [1, 2]);
    /// ```
    pub fn of_kind(&self, kind: PartKind) -> impl Iterator<Item = &Component> {
        self.components
            .iter()
            .zip(&self.kinds)
            .filter(move |(_, k)| **k == kind)
            .map(|(c, _)| c)
    }
}

/// Errors finding the parts.
#[derive(Clone, Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum PartsError {
    /// The file has no triangles.
    #[error("the file has no triangles")]
    Empty,
    /// Two components are each nearly as large as the largest: two heads or two faces.
    #[error(
        "two skins of about the same size ({0} and {1} triangles): two heads or two faces in one file"
    )]
    TwoSkins(usize, usize),
    /// A part other than the skin has more triangles than [`MAX_PART_TRIANGLES`].
    #[error(
        "a part of {0} triangles beside the skin, over the {MAX_PART_TRIANGLES} a head's part may have (simplify it or leave it out)"
    )]
    PartTooLarge(usize),
}

/// The most triangles a part other than the skin may have (eyeballs, teeth, lashes, hair
/// cards, clothes): a head's parts each have a few thousand; a part of more would cost more to
/// carry the rig to than the head itself is worth.
pub const MAX_PART_TRIANGLES: usize = 250_000;

/// Refuses a part other than the skin with more than [`MAX_PART_TRIANGLES`] triangles.
fn check_part_sizes(components: &[Component], skin: usize) -> Result<(), PartsError> {
    match (0..components.len())
        .filter(|&i| i != skin)
        .map(|i| components[i].triangles.len())
        .find(|&t| t > MAX_PART_TRIANGLES)
    {
        Some(t) => Err(PartsError::PartTooLarge(t)),
        None => Ok(()),
    }
}

/// Finds the parts of `scene` (see the module documentation).
pub fn find_parts(scene: &Scene) -> Result<HeadParts, PartsError> {
    let components = scene.components();
    if components.is_empty() {
        return Err(PartsError::Empty);
    }
    let first = scene.first_at_same_place();
    let stats: Vec<ComponentStats> = components
        .iter()
        .map(|c| ComponentStats::new(scene, c, &first))
        .collect();
    let skin = (0..stats.len())
        .max_by(|&a, &b| stats[a].area.total_cmp(&stats[b].area))
        .unwrap_or(0);
    let skin_size = stats[skin].extent;
    check_part_sizes(&components, skin)?;
    for (i, s) in stats.iter().enumerate() {
        let similar = s.area > 0.6 * stats[skin].area && s.extent > 0.6 * skin_size;
        if i != skin && similar && !s.closed_sphere(skin_size) {
            return Err(PartsError::TwoSkins(
                components[skin].triangles.len(),
                components[i].triangles.len(),
            ));
        }
    }
    let mut kinds = vec![PartKind::Other; components.len()];
    kinds[skin] = PartKind::Skin;
    let eyes = find_eyeballs(&stats, skin, skin_size);
    let Some((left_right, eye_members)) = eyes else {
        return Ok(HeadParts {
            components,
            kinds,
            eyeballs: None,
            frame: None,
        });
    };
    let [a, b] = left_right;
    let axis = (b.centre - a.centre).normalize_or_zero();
    let eyes_mid = 0.5 * (a.centre + b.centre);
    let radius = 0.5 * (a.radius + b.radius);
    // Teeth: closed, at most one and a half eyeball diameters long (a tooth with its roots is
    // 2–3 cm; an eyeball 2.4 cm across), not an eyeball's own component.
    let is_eye = |i: usize| eye_members.iter().any(|m| m.contains(&i));
    let small_closed: Vec<usize> = (0..stats.len())
        .filter(|&i| i != skin && !is_eye(i) && stats[i].closed && stats[i].extent < 3.0 * radius)
        .collect();
    let centroid_skin = stats[skin].centroid;
    let teeth_centre = (small_closed.len() >= 4).then(|| {
        small_closed
            .iter()
            .map(|&i| stats[i].centroid)
            .sum::<DVec3>()
            / small_closed.len() as f64
    });
    let below = teeth_centre.unwrap_or(centroid_skin);
    let up = orthogonal(eyes_mid - below, axis);
    let forward = {
        let f = axis.cross(up).normalize_or_zero();
        if (eyes_mid - centroid_skin).dot(f) >= 0.0 {
            f
        } else {
            -f
        }
    };
    let left = up.cross(forward);
    let (left_eye, right_eye, left_members, right_members) =
        if (a.centre - eyes_mid).dot(left) > 0.0 {
            (a, b, &eye_members[0], &eye_members[1])
        } else {
            (b, a, &eye_members[1], &eye_members[0])
        };
    for &i in left_members {
        kinds[i] = PartKind::Eyeball(Side::Left);
    }
    for &i in right_members {
        kinds[i] = PartKind::Eyeball(Side::Right);
    }
    // Teeth: the small closed components below the eyes, split at the widest height gap.
    let teeth: Vec<usize> = small_closed
        .iter()
        .copied()
        .filter(|&i| (stats[i].centroid - eyes_mid).dot(up) < -2.0 * radius)
        .collect();
    if teeth.len() >= 4 {
        let mut heights: Vec<(f64, usize)> = teeth
            .iter()
            .map(|&i| (stats[i].centroid.dot(up), i))
            .collect();
        heights.sort_by(|x, y| x.0.total_cmp(&y.0));
        let gap = (1..heights.len())
            .max_by(|&x, &y| {
                let g = |k: usize| heights[k].0 - heights[k - 1].0;
                g(x).total_cmp(&g(y))
            })
            .unwrap_or(0);
        for (k, &(_, i)) in heights.iter().enumerate() {
            kinds[i] = if k < gap {
                PartKind::LowerTooth
            } else {
                PartKind::UpperTooth
            };
        }
        // The teeth's ball: around their centre, reaching every tooth whole.
        let centre = teeth.iter().map(|&i| stats[i].centroid).sum::<DVec3>() / teeth.len() as f64;
        let reach = teeth
            .iter()
            .map(|&i| stats[i].centroid.distance(centre) + stats[i].extent)
            .fold(0.0, f64::max);
        let tooth_area = teeth.iter().map(|&t| stats[t].area).fold(0.0, f64::max);
        for (i, s) in stats.iter().enumerate() {
            let inside = s.centroid.distance(centre) < reach;
            if kinds[i] == PartKind::Other && inside && s.area > tooth_area {
                kinds[i] = PartKind::GumsAndTongue;
            }
        }
    }
    for (i, s) in stats.iter().enumerate() {
        let near = [left_eye, right_eye]
            .iter()
            .any(|e| s.centroid.distance(e.centre) < 2.0 * e.radius);
        if kinds[i] == PartKind::Other && near {
            kinds[i] = PartKind::LidPart;
        }
    }
    Ok(HeadParts {
        components,
        kinds,
        eyeballs: Some([left_eye, right_eye]),
        frame: Some(HeadFrame { left, up, forward }),
    })
}

/// `v` without its component along the unit `axis`, normalised (zero if nothing is left).
fn orthogonal(v: DVec3, axis: DVec3) -> DVec3 {
    (v - v.dot(axis) * axis).normalize_or_zero()
}

/// The two eyeballs (their spheres and member components), if found.
fn find_eyeballs(
    stats: &[ComponentStats],
    skin: usize,
    skin_size: f64,
) -> Option<([Sphere; 2], [Vec<usize>; 2])> {
    // Sphere-like closed components, grouped by shared centre.
    let mut groups: Vec<(Sphere, Vec<usize>, f64)> = Vec::new();
    for (i, s) in stats.iter().enumerate() {
        if i == skin || !s.closed_sphere(skin_size) {
            continue;
        }
        let Some(sphere) = s.sphere else { continue };
        match groups
            .iter_mut()
            .find(|g| g.0.centre.distance(sphere.centre) < 0.3 * g.0.radius)
        {
            Some(g) => {
                g.1.push(i);
                g.2 += s.area;
                if sphere.radius > g.0.radius {
                    g.0 = sphere;
                }
            }
            None => groups.push((sphere, vec![i], s.area)),
        }
    }
    groups.sort_by(|a, b| b.2.total_cmp(&a.2));
    // The largest group and the largest other one of a similar radius.
    let first = groups.first()?;
    let second = groups[1..].iter().find(|g| {
        let ratio = g.0.radius / first.0.radius;
        (0.8..=1.25).contains(&ratio) && g.0.centre.distance(first.0.centre) > 2.0 * first.0.radius
    })?;
    Some(([first.0, second.0], [first.1.clone(), second.1.clone()]))
}

/// What the classification needs of a component.
struct ComponentStats {
    area: f64,
    centroid: DVec3,
    /// Twice the largest distance of a vertex from the centroid (turning the head leaves it).
    extent: f64,
    closed: bool,
    sphere: Option<Sphere>,
}

impl ComponentStats {
    /// `first`: each vertex's first vertex at the same coordinates
    /// ([`Scene::first_at_same_place`]). Closedness is the surface's, not its texture
    /// layout's: vertices at exactly the same coordinates (a UV seam's copies, in a glTF) are
    /// one. Regression: the ICT head as a GLB (seams split) had no closed eyeball.
    fn new(scene: &Scene, c: &Component, first: &[u32]) -> Self {
        let p = |v: u32| scene.positions[v as usize];
        let (mut area, mut weighted) = (0.0, DVec3::ZERO);
        let weld = |v: u32| first.get(v as usize).copied().unwrap_or(v);
        let mut edges: std::collections::HashMap<(u32, u32), i32> = Default::default();
        for &t in &c.triangles {
            let [a, b, cc] = scene.triangles[t as usize];
            let a2 = (p(b) - p(a)).cross(p(cc) - p(a)).length() / 2.0;
            area += a2;
            weighted += a2 * (p(a) + p(b) + p(cc)) / 3.0;
            for (x, y) in [(a, b), (b, cc), (cc, a)] {
                let (x, y) = (weld(x), weld(y));
                *edges.entry((x.min(y), x.max(y))).or_default() += 1;
            }
        }
        let points: Vec<DVec3> = c.vertices.iter().map(|&v| p(v)).collect();
        let centroid = if area > 0.0 {
            weighted / area
        } else {
            points.iter().sum::<DVec3>() / points.len().max(1) as f64
        };
        let extent = 2.0
            * points
                .iter()
                .map(|q| q.distance(centroid))
                .fold(0.0, f64::max);
        ComponentStats {
            area,
            centroid,
            extent,
            closed: edges.values().all(|&n| n != 1),
            sphere: fit_sphere(&points),
        }
    }

    /// Closed and fits a sphere of an eyeball's size relative to the skin.
    fn closed_sphere(&self, skin_size: f64) -> bool {
        self.closed
            && self.sphere.is_some_and(|s| {
                s.rms <= SPHERE_FIT_TOLERANCE * s.radius
                    && (0.01..=0.08).contains(&(s.radius / skin_size))
            })
    }
}
