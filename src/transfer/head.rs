//! A front face's responses carried to a whole head (issue 32, items 4 and 5, first method):
//! every vertex of every part gets a displacement per control, linear in the face's, so the
//! named expressions (sums of controls) carry the same way.
//!
//! - **Skin in the front face**: the rig's own displacement.
//! - **The rest of the skin** (scalp, ears, neck, the eye sockets' and the mouth's linings):
//!   the displacement of the front face's border vertex nearest along the skin
//!   ([`super::along_surface`]: the inside of a lip takes its own lip's motion, not the other
//!   lip's across the mouth), times a falloff that is 1 on the border and reaches 0 at
//!   [`FALLOFF`] interocular distances from it along the skin (`1 − smoothstep`; the mouth's
//!   lining at [`LINING_FALLOFF`]), so there is no seam where the simulated region ends and the
//!   back of the head stays still. The mouth's lining is attached to the bone it lines: in
//!   the jaw controls, what the falloff takes from the border's motion it gives to the
//!   mandible's, in the lower row's share (as the gums).
//! - **Lower teeth**: the rig's own mandible ([`face_prep::jaw::Jaw::activation`]) in the jaw
//!   controls — the same rigid motion the jaw's contour is given — and still in every other
//!   control. **Gums and tongue** take that motion in the share of their distance to the upper
//!   row over their distances to both rows (the lower gums and the tongue's floor with the jaw,
//!   the upper gums still).
//! - **Upper teeth and eyeballs** stay still in every control (the skull); the eyeballs turn
//!   in the gaze targets ([`super::gaze`]).
//! - **Lid parts and other parts** follow the nearest skin vertex.
//!
//! Besides the controls' fields, [`HeadBasis::named_fields`] holds the targets no control
//! makes: ARKit's eight `eyeLook*` and VRM's four `look*` when there are eyeballs
//! ([`super::gaze`]), ARKit's `tongueOut` when there is a tongue ([`super::tongue`]).

use face_prep::parts::{FrontFace, HeadParts, PartKind, Scene};
use face_prep::{FaceMesh, FaceRig, Generator, MuscleKind};
use glam::DVec3;

use super::eye_contact::EyeContact;
use super::nearest::PointTree;
use super::{gaze, tongue};
use crate::model::MuscleBasis;

/// Distance over which the displacement of the skin outside the front face falls to zero, in
/// interocular distances.
pub const FALLOFF: f64 = 0.25;

/// The mouth's lining (skin outside the front face within [`LINING_NEAR`] of the teeth, gums
/// or tongue) is the inner surface of the lips and cheeks, which move as one: its displacement
/// falls to zero over this many interocular distances instead of [`FALLOFF`]. On ICT-FaceKit's
/// head against its captures (`cargo run --release -p facebem-tools --bin head_cosines`), the
/// whole head's cosine in mouthSmile goes from 0.80 to 0.85 (the narrow face's: 0.86),
/// mouthStretch 0.83 → 0.89 (0.91), mouthFrown 0.77 → 0.83 (0.85).
pub const LINING_FALLOFF: f64 = 0.5;

/// How near the teeth, gums or tongue (in interocular distances) skin is the mouth's lining.
pub const LINING_NEAR: f64 = 0.1;

/// A whole head's responses: one field per control, and the named targets no control makes.
#[derive(Clone, Debug, PartialEq)]
pub struct HeadBasis {
    /// Every control's field on every vertex of the head.
    pub basis: MuscleBasis,
    /// (standard name, field at weight 1 on every vertex): the gaze targets and `tongueOut`,
    /// kept off the eyeballs.
    pub named_fields: Vec<(String, Vec<DVec3>)>,
    /// The lids' contact with the eyeballs, for the targets made of the controls' fields
    /// ([`HeadBasis::named_fields_for`]).
    pub contact: EyeContact,
}

impl HeadBasis {
    /// Every ARKit and VRM target of the sets `names` on the whole head — those the controls
    /// make and [`HeadBasis::named_fields`] — each kept off the eyeballs ([`EyeContact`]; FACS
    /// units and facebem's own control targets are left to the controls): to pass as
    /// [`crate::export::GltfParams::named_fields`], which replace what the controls make.
    /// (A sum of corrected targets may still touch an eyeball where two targets push the
    /// same lid; each target alone does not.)
    pub fn named_fields_for(
        &self,
        names: crate::expressions::NameSets,
    ) -> Vec<(String, Vec<DVec3>)> {
        let (made, _) = crate::expressions::for_rig(names, &self.basis.muscle_ids);
        let mut out: Vec<(String, Vec<DVec3>)> = made
            .iter()
            .filter(|r| {
                matches!(
                    r.expression.set,
                    crate::expressions::NameSet::Arkit | crate::expressions::NameSet::Vrm
                )
            })
            .map(|r| {
                (
                    r.expression.name.to_string(),
                    self.field_of(&r.resolved.sliders),
                )
            })
            .collect();
        out.extend(self.named_fields.iter().cloned());
        out
    }

    /// The displacement of every vertex of the head at `sliders` (one per control; a shorter
    /// slice leaves the rest at 0), the lids kept off the eyeballs and the lid parts riding
    /// on them ([`EyeContact::apply`]).
    pub fn field_of(&self, sliders: &[f64]) -> Vec<DVec3> {
        let mut field = vec![DVec3::ZERO; self.basis.neutral.len()];
        for (control, &s) in self.basis.displacements.iter().zip(sliders) {
            if s != 0.0 {
                for (d, f) in field.iter_mut().zip(control) {
                    *d += s * *f;
                }
            }
        }
        self.contact.apply(&self.basis.neutral, &mut field);
        field
    }
}

/// The basis of the whole `scene` (its positions and triangles, every part) from the basis
/// `face` of the front face `front` (read as `mesh`, rigged as `rig`).
pub fn carry_to_head(
    scene: &Scene,
    parts: &HeadParts,
    front: &FrontFace,
    mesh: &FaceMesh,
    rig: &FaceRig,
    face: &MuscleBasis,
) -> HeadBasis {
    let n = scene.positions.len();
    let kind_of = vertex_kinds(parts, n);
    // Scene vertex → the face mesh's vertex.
    let mut in_face: Vec<Option<u32>> = vec![None; n];
    for (i, &v) in front.scene_vertex.iter().enumerate() {
        in_face[v as usize] = mesh.input_to_vertex.get(i).copied().flatten();
    }
    // The copies of a face vertex (a glTF's UV seams) are in the face too.
    let first = scene.first_at_same_place();
    for v in 0..n {
        if in_face[v].is_none() && kind_of[v] == Some(PartKind::Skin) {
            in_face[v] = first.get(v).and_then(|&f| in_face[f as usize]);
        }
    }
    let border: Vec<u32> = face_prep::topology::validate(&mesh.vertices, &mesh.triangles)
        .map(|loops| loops.into_iter().flatten().collect())
        .unwrap_or_default();
    let iod = parts
        .eyeballs
        .map_or(1.0, |[l, r]| l.centre.distance(r.centre));
    let falloff = FALLOFF * iod;
    let mouth_parts: Vec<u32> = (0..n as u32)
        .filter(|&v| {
            matches!(
                kind_of[v as usize],
                Some(PartKind::UpperTooth | PartKind::LowerTooth | PartKind::GumsAndTongue)
            )
        })
        .collect();
    let border_tree = tree_of(&border, |b| mesh.vertices[b as usize]);
    let along_skin = border_along_skin(scene, parts, front, mesh, &border, &first);
    let mouth_tree = tree_of(&mouth_parts, |m| scene.positions[m as usize]);
    let rows = Rows::new(scene, &kind_of);
    // Each skin vertex outside the face: its border vertex, that vertex's weight, and the
    // share of the jaw's motion the rest takes (the lining's attachment to the bone).
    let skin_source: Vec<Option<(u32, f64, f64)>> = (0..n)
        .map(|v| {
            if kind_of[v] != Some(PartKind::Skin) {
                return None;
            }
            if let Some(m) = in_face[v] {
                return Some((m, 1.0, 0.0));
            }
            let p = scene.positions[v];
            let welded = first.get(v).map_or(v, |&f| f as usize);
            let (b, d) = along_skin[welded].or_else(|| border_tree.nearest(p))?;
            let lining = mouth_tree
                .nearest(p)
                .is_some_and(|(_, to_teeth)| to_teeth < LINING_NEAR * iod);
            let reach = if lining {
                LINING_FALLOFF * iod
            } else {
                falloff
            };
            let t = (d / reach).clamp(0.0, 1.0);
            let w = 1.0 - t * t * (3.0 - 2.0 * t);
            let bone = if lining { rows.lower_share(p) } else { 0.0 };
            (w > 0.0 || bone > 0.0).then_some((b, w, bone))
        })
        .collect();
    let skin: Vec<u32> = (0..n as u32)
        .filter(|&v| kind_of[v as usize] == Some(PartKind::Skin))
        .collect();
    let skin_tree = tree_of(&skin, |s| scene.positions[s as usize]);
    let lid_roots = super::lid_riders::lid_part_roots(scene, parts, &skin_tree, iod);
    // What every other vertex follows, found once for all controls.
    let follow: Vec<Follow> = (0..n)
        .map(|v| {
            let p = scene.positions[v];
            match kind_of[v] {
                Some(PartKind::LowerTooth) => Follow::Jaw(1.0),
                Some(PartKind::GumsAndTongue) => Follow::Jaw(rows.lower_share(p)),
                Some(PartKind::LidPart) => lid_roots[v].map_or(Follow::Still, Follow::Skin),
                Some(PartKind::Other) => skin_tree
                    .nearest(p)
                    .map_or(Follow::Still, |(s, _)| Follow::Skin(s)),
                _ => Follow::Still,
            }
        })
        .collect();
    let jaw = rig.jaw();
    let input_from_canonical = rig.canonical_from_input.inverse();
    let mm = rig.mm_per_unit();
    let displacements = face
        .displacements
        .iter()
        .zip(&face.muscle_ids)
        .map(|(field, id)| {
            let at = |m: u32| field.get(m as usize).copied().unwrap_or(DVec3::ZERO);
            // The mandible's motion at slider +1 (−1 is the full activation).
            let mode = match MuscleKind::from_id(id).map(MuscleKind::generator) {
                Some(Generator::Jaw(mode)) => Some(mode),
                _ => None,
            };
            let bone = |p: DVec3| {
                mode.map_or(DVec3::ZERO, |mode| {
                    let q = rig.canonical_from_input.transform_point3(p);
                    -input_from_canonical.transform_vector3(jaw.activation(mode, q, mm))
                })
            };
            let mut out: Vec<DVec3> = skin_source
                .iter()
                .zip(&scene.positions)
                .map(|(s, &p)| {
                    s.map_or(DVec3::ZERO, |(m, w, share)| {
                        let attached = if share > 0.0 && mode.is_some() {
                            share * bone(p)
                        } else {
                            DVec3::ZERO
                        };
                        w * at(m) + (1.0 - w) * attached
                    })
                })
                .collect();
            for v in 0..n {
                match follow[v] {
                    Follow::Jaw(share) => out[v] = share * bone(scene.positions[v]),
                    Follow::Skin(s) => out[v] = out[s as usize],
                    Follow::Still => {}
                }
            }
            out
        })
        .collect();
    let basis = MuscleBasis {
        muscle_ids: face.muscle_ids.clone(),
        neutral: scene.positions.clone(),
        triangles: scene.triangles.clone(),
        displacements,
    };
    let mut named_fields = gaze_fields(scene, parts, &kind_of, &follow);
    named_fields.extend(tongue_out(scene, &kind_of, parts, &basis, iod));
    let follows: Vec<Option<u32>> = follow
        .iter()
        .map(|f| match f {
            Follow::Skin(s) => Some(*s),
            _ => None,
        })
        .collect();
    let contact = EyeContact::new(scene, parts, &follows);
    for (_, field) in &mut named_fields {
        contact.apply(&scene.positions, field);
    }
    HeadBasis {
        basis,
        named_fields,
        contact,
    }
}

/// For every scene vertex (by its first copy at the same place), the front face's border
/// vertex (a vertex of `mesh`) nearest along the skin's edges, and how far.
fn border_along_skin(
    scene: &Scene,
    parts: &HeadParts,
    front: &FrontFace,
    mesh: &FaceMesh,
    border: &[u32],
    first: &[u32],
) -> Vec<Option<(u32, f64)>> {
    let weld = |v: u32| first.get(v as usize).copied().unwrap_or(v);
    let mut on_border = vec![false; mesh.vertices.len()];
    border.iter().for_each(|&b| on_border[b as usize] = true);
    let sources: Vec<(u32, u32)> = front
        .scene_vertex
        .iter()
        .zip(&mesh.input_to_vertex)
        .filter_map(|(&v, m)| m.filter(|&m| on_border[m as usize]).map(|m| (weld(v), m)))
        .collect();
    let skin_triangles: Vec<[u32; 3]> = parts
        .of_kind(PartKind::Skin)
        .flat_map(|c| {
            c.triangles
                .iter()
                .map(|&t| scene.triangles[t as usize].map(weld))
        })
        .collect();
    super::along_surface::nearest_source(&scene.positions, &skin_triangles, &sources)
}

/// ARKit's eight gaze targets and VRM's four, with lid parts following the skin (none without
/// eyeballs and the head's frame).
fn gaze_fields(
    scene: &Scene,
    parts: &HeadParts,
    kind_of: &[Option<PartKind>],
    follow: &[Follow],
) -> Vec<(String, Vec<DVec3>)> {
    let (Some(eyeballs), Some(frame)) = (parts.eyeballs, parts.frame) else {
        return Vec::new();
    };
    let arkit: Vec<(String, Vec<DVec3>)> = gaze::ARKIT_GAZE
        .iter()
        .map(|&(name, side, look)| {
            let mut field =
                gaze::look_field(&scene.positions, kind_of, &frame, eyeballs, side, look);
            for (v, f) in follow.iter().enumerate() {
                if let Follow::Skin(s) = f {
                    field[v] = field[*s as usize];
                }
            }
            (name.to_string(), field)
        })
        .collect();
    let sum = |names: [&str; 2]| {
        let mut out = vec![DVec3::ZERO; scene.positions.len()];
        for (_, field) in arkit.iter().filter(|(n, _)| names.contains(&n.as_str())) {
            for (o, f) in out.iter_mut().zip(field) {
                *o += *f;
            }
        }
        out
    };
    let vrm: Vec<(String, Vec<DVec3>)> = gaze::VRM_GAZE
        .iter()
        .map(|&(name, of)| (name.to_string(), sum(of)))
        .collect();
    arkit.into_iter().chain(vrm).collect()
}

/// `tongueOut`: the jaw opened by [`tongue::TONGUE_OUT_JAW`] of `jawOpen` plus the tongue's
/// protrusion; `None` without a jaw control or a tongue.
fn tongue_out(
    scene: &Scene,
    kind_of: &[Option<PartKind>],
    parts: &HeadParts,
    basis: &MuscleBasis,
    iod: f64,
) -> Option<(String, Vec<DVec3>)> {
    let frame = parts.frame?;
    let open = basis.muscle_ids.iter().position(|id| id == "jaw_open")?;
    // Slider −1 opens the jaw.
    let jaw: Vec<DVec3> = basis.displacements[open]
        .iter()
        .map(|d| -tongue::TONGUE_OUT_JAW * *d)
        .collect();
    let of = |k: PartKind| -> Vec<u32> {
        (0..kind_of.len() as u32)
            .filter(|&v| kind_of[v as usize] == Some(k))
            .collect()
    };
    let (gums, upper, lower) = (
        of(PartKind::GumsAndTongue),
        of(PartKind::UpperTooth),
        of(PartKind::LowerTooth),
    );
    let mouth = tongue::Mouth {
        positions: &scene.positions,
        triangles: &scene.triangles,
        gums_and_tongue: &gums,
        upper_teeth: &upper,
        lower_teeth: &lower,
        up: frame.up,
        forward: frame.forward,
        iod,
    };
    let push = tongue::protrusion(&mouth, &jaw)?;
    let field = jaw.iter().zip(&push).map(|(j, p)| *j + *p).collect();
    Some(("tongueOut".to_string(), field))
}

/// The part of each scene vertex (`None`: used by no triangle).
fn vertex_kinds(parts: &HeadParts, n: usize) -> Vec<Option<PartKind>> {
    let mut kinds = vec![None; n];
    for (c, k) in parts.components.iter().zip(&parts.kinds) {
        for &v in &c.vertices {
            kinds[v as usize] = Some(*k);
        }
    }
    kinds
}

/// A tree of the `candidates` (positions by `at`) for nearest-point queries.
fn tree_of(candidates: &[u32], at: impl Fn(u32) -> DVec3) -> PointTree {
    PointTree::new(candidates.iter().map(|&c| (c, at(c))))
}

/// What a vertex that is not simulated skin follows.
#[derive(Clone, Copy, Debug)]
enum Follow {
    /// Nothing (or, for skin, its own weighted border vertex).
    Still,
    /// This share of the jaw's rigid motion.
    Jaw(f64),
    /// The skin vertex it lies nearest (a lid part: the one its root lies nearest,
    /// [`super::lid_riders`]).
    Skin(u32),
}

/// The two rows of teeth, for the gums' and tongue's share of the jaw's motion.
struct Rows {
    upper: PointTree,
    lower: PointTree,
}

impl Rows {
    fn new(scene: &Scene, kind_of: &[Option<PartKind>]) -> Rows {
        let of = |k: PartKind| -> PointTree {
            PointTree::new(
                (0..kind_of.len())
                    .filter(|&v| kind_of[v] == Some(k))
                    .map(|v| (v as u32, scene.positions[v])),
            )
        };
        Rows {
            upper: of(PartKind::UpperTooth),
            lower: of(PartKind::LowerTooth),
        }
    }

    /// How much of the jaw's motion a point of the gums or tongue takes: its distance to the
    /// upper row over the sum of its distances to both rows (none without a lower row),
    /// through a smoothstep from 0.25 to 0.75, so that the gums at a tooth go wholly with its
    /// row.
    fn lower_share(&self, p: DVec3) -> f64 {
        let t = ((self.linear_share(p) - 0.25) / 0.5).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    }

    /// Distance to the upper row over the sum of the distances to both rows.
    fn linear_share(&self, p: DVec3) -> f64 {
        let d = |row: &PointTree| row.nearest(p).map_or(f64::INFINITY, |(_, d)| d);
        let (up, low) = (d(&self.upper), d(&self.lower));
        match (up.is_finite(), low.is_finite()) {
            (true, true) if up + low > 0.0 => up / (up + low),
            (false, true) => 1.0,
            _ => 0.0,
        }
    }
}
