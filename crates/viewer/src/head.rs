//! Heads and avatars in the viewer: a file whose parts hold two eyeballs
//! ([`facebem::input::heads::WholeFile`]) is shown whole at once, its front face is cut and
//! rigged (through the rig cache, like a face), and the rig is carried to every part
//! ([`facebem::transfer::head::carry_to_head`]): the sliders move the whole head, eyeballs,
//! teeth, tongue and lashes included, and the gaze and `tongueOut` targets get sliders of their
//! own.
//!
//! ```no_run
//! use viewer::head::HeadSource;
//! let path = std::path::Path::new("assets/heads/ict_generic_head.obj");
//! let whole = facebem::input::heads::WholeFile::read(path).unwrap();
//! let head = HeadSource::new(path, whole).unwrap();
//! let preview = head.preview_basis();
//! assert_eq!(preview.neutral.len(), head.whole.scene.positions.len());
//! ```

use std::path::{Path, PathBuf};

use face_prep::FaceMesh;
use face_prep::parts::{FrontFace, front_face};
use facebem::export::ExportLayout;
use facebem::input::CacheStatus;
use facebem::input::heads::WholeFile;
use facebem::transfer::head::HeadBasis;
use facebem::{Control, FaceModel, MuscleBasis, PipelineParams};

use crate::surface::{Looks, Surface};

/// A head read whole, with its front face cut for the simulation.
#[derive(Clone, Debug)]
pub struct HeadSource {
    /// The file it was read from (the glTF export writes that file back with the targets).
    pub path: PathBuf,
    /// The file's parts.
    pub whole: WholeFile,
    /// The front face cut from its skin.
    pub front: FrontFace,
    /// The front face as a face mesh (what is rigged).
    pub mesh: FaceMesh,
    /// The OBJ text of an OBJ head (its layout and materials are drawn).
    pub obj_text: Option<String>,
}

/// A head's rig: the front face's model and its responses carried to the whole head.
#[derive(Clone, Debug)]
pub struct HeadRig {
    /// The front face's model (muscles, rig, overlays).
    pub model: FaceModel,
    /// Where the model came from.
    pub status: CacheStatus,
    /// Every control's field on the whole head, and the gaze and tongue targets.
    pub head: HeadBasis,
}

impl HeadSource {
    /// Cuts the front face of `whole` (read from `path`); the error is one line naming the file.
    pub fn new(path: &Path, whole: WholeFile) -> Result<HeadSource, String> {
        let front = front_face(&whole.scene, &whole.parts)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let mesh = FaceMesh::from_triangles(&front.positions, &front.triangles)
            .map_err(|e| format!("{}: its front face: {e}", path.display()))?;
        let is_obj = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
        let obj_text = if is_obj {
            face_prep::limits::read_input_file(path, &face_prep::InputLimits::default())
                .ok()
                .map(|b| String::from_utf8_lossy(&b).into_owned())
        } else {
            None
        };
        Ok(HeadSource {
            path: path.to_path_buf(),
            whole,
            front,
            mesh,
            obj_text,
        })
    }

    /// The whole head at rest, without controls: what is drawn while the rig is computed.
    pub fn preview_basis(&self) -> MuscleBasis {
        MuscleBasis {
            muscle_ids: Vec::new(),
            neutral: self.whole.scene.positions.clone(),
            triangles: self.whole.scene.triangles.clone(),
            displacements: Vec::new(),
        }
    }

    /// The drawn surface of `basis` (the whole head's vertices and triangles): an OBJ head in
    /// its own layout with its materials ([`Looks::load`]), anything else in one colour per
    /// part (skin, eyeballs, teeth, gums and tongue, lid parts).
    ///
    /// Lid parts in front of an eyeball's pupil (ICT's eye occlusion and tear films: shading
    /// layers a renderer blends with an alpha texture) are not drawn: the viewer draws opaque
    /// surfaces, and drawn they would hide the eyes.
    pub fn surface(&self, basis: &MuscleBasis, skin: [f32; 4]) -> (Surface, Looks) {
        let n = self.whole.scene.positions.len();
        let hidden = films_over_the_eyes(&self.whole);
        let drawn = |mut layout: ExportLayout, mut looks: Looks| {
            if layout.triangles.len() == hidden.len() {
                let keep = |t: usize| !hidden[t];
                let mut t = 0;
                layout.triangles.retain(|_| (keep(t), t += 1).0);
                if looks.triangle_material.len() == hidden.len() {
                    let mut t = 0;
                    looks.triangle_material.retain(|_| (keep(t), t += 1).0);
                }
            }
            (Surface::with_layout(basis, layout, &looks, skin), looks)
        };
        if let Some(text) = &self.obj_text {
            let identity: Vec<Option<u32>> = (0..n as u32).map(Some).collect();
            let looks = Looks::load(&self.path, Some(text));
            if let Ok(layout) = ExportLayout::from_obj(text, &identity)
                && !looks.materials.is_empty()
                && looks.triangle_material.len() == layout.triangles.len()
            {
                return drawn(layout, looks);
            }
        }
        let layout = ExportLayout::welded(&basis.neutral, &basis.triangles);
        drawn(layout, part_looks(&self.whole))
    }

    /// Rigs the front face (loaded from, or computed into, the rig cache `cache_dir`) and
    /// carries the rig to the whole head.
    pub fn rig(
        &self,
        params: &PipelineParams,
        cache_dir: &Path,
        control: &Control,
    ) -> Result<HeadRig, String> {
        let params = PipelineParams {
            outline_is_cut: true,
            ..params.clone()
        };
        let cache_path = facebem::input::cache_file_for(cache_dir, &self.mesh, &params);
        let (model, status) =
            facebem::input::load_or_build(&self.mesh, None, &params, &cache_path, control)
                .map_err(|e| e.to_string())?;
        let head = facebem::transfer::head::carry_to_head(
            &self.whole.scene,
            &self.whole.parts,
            &self.front,
            &model.mesh,
            &model.rig,
            &model.basis,
        );
        Ok(HeadRig {
            model,
            status,
            head,
        })
    }
}

/// What the viewer draws and poses for a rigged head: one slider per control, then one per
/// target no control makes (ARKit's eight `eyeLook*`, VRM's four `look*`, `tongueOut`; 0 … 1
/// is the target), on every vertex of the head.
pub fn display_basis(head: &HeadBasis) -> MuscleBasis {
    let mut basis = head.basis.clone();
    for (name, field) in &head.named_fields {
        basis.muscle_ids.push(name.clone());
        basis.displacements.push(field.clone());
    }
    basis
}

/// Per scene triangle: whether it belongs to a lid part that a ray from an eyeball's centre
/// straight forward (through the pupil) passes through, within two eyeball radii. A lid part
/// is split by the file's groups or materials where it has them (ICT's lashes, tear film and
/// eye occlusion are one connected part per eye: only the occlusion's group is hidden).
pub fn films_over_the_eyes(whole: &WholeFile) -> Vec<bool> {
    use face_prep::parts::PartKind;
    let scene = &whole.scene;
    let mut hidden = vec![false; scene.triangles.len()];
    let (Some(eyeballs), Some(frame)) = (whole.parts.eyeballs, whole.parts.frame) else {
        return hidden;
    };
    let label = |t: u32| scene.triangle_label.get(t as usize).copied().unwrap_or(0);
    for (c, kind) in whole.parts.components.iter().zip(&whole.parts.kinds) {
        if *kind != PartKind::LidPart {
            continue;
        }
        let mut labels: Vec<u32> = c.triangles.iter().map(|&t| label(t)).collect();
        labels.sort_unstable();
        labels.dedup();
        for l in labels {
            let group: Vec<u32> = (c.triangles.iter().copied())
                .filter(|&t| label(t) == l)
                .collect();
            let triangles: Vec<[u32; 3]> = (group.iter())
                .filter_map(|&t| scene.triangles.get(t as usize).copied())
                .collect();
            let covers = eyeballs.iter().any(|eye| {
                let hit = crate::picking::pick_triangle(
                    &scene.positions,
                    &triangles,
                    eye.centre,
                    frame.forward,
                );
                hit.is_some_and(|hit| hit.distance < 2.0 * eye.radius)
            });
            if covers {
                for &t in &group {
                    if let Some(h) = hidden.get_mut(t as usize) {
                        *h = true;
                    }
                }
            }
        }
    }
    hidden
}

/// One material per kind of part found (the skin in the viewer's skin colour), for a head
/// drawn without its own materials.
fn part_looks(whole: &WholeFile) -> Looks {
    use crate::surface::LookMaterial;
    use face_prep::parts::PartKind;
    // Linear colours (the surface encodes material colours as sRGB for display).
    let kinds: [(&str, [f32; 3]); 5] = [
        ("eyeball", [0.8, 0.8, 0.78]),
        ("teeth", [0.85, 0.8, 0.65]),
        ("gums and tongue", [0.45, 0.08, 0.1]),
        ("lid parts", [0.02, 0.015, 0.01]),
        ("other", [0.3, 0.3, 0.35]),
    ];
    let mut triangle_material = vec![None; whole.scene.triangles.len()];
    for (c, kind) in whole.parts.components.iter().zip(&whole.parts.kinds) {
        let m = match kind {
            PartKind::Skin => None,
            PartKind::Eyeball(_) => Some(0),
            PartKind::UpperTooth | PartKind::LowerTooth => Some(1),
            PartKind::GumsAndTongue => Some(2),
            PartKind::LidPart => Some(3),
            _ => Some(4),
        };
        for &t in &c.triangles {
            if let Some(slot) = triangle_material.get_mut(t as usize) {
                *slot = m;
            }
        }
    }
    Looks {
        materials: kinds
            .iter()
            .map(|(name, [r, g, b])| LookMaterial {
                name: name.to_string(),
                base_color: [*r, *g, *b, 1.0],
                texture: None,
            })
            .collect(),
        triangle_material,
        warnings: Vec::new(),
    }
}
