//! What the viewport draws as the face's surface (issue 35): the user's own vertex layout with
//! their texture coordinates, UV seams split exactly as the glTF export splits them
//! ([`ExportLayout`]), their materials (OBJ `Kd` / `map_Kd`, glTF `baseColorFactor` /
//! `baseColorTexture`), and on request the heat map of displacement over them.
//!
//! Colours are display values throughout, as the viewer's flat skin always was: a texture's
//! texels are used as stored (sRGB-encoded), a linear colour factor is encoded to sRGB before it
//! multiplies them, and the lighting scales the result. The heat map is the contact sheet's
//! fixed millimetre scale ([`facebem::report::contact_sheet::heat`]); skin that moves less than
//! its first edge (0.5 mm) shows the texture.

use std::path::Path;
use std::sync::Arc;

use face_prep::FaceMesh;
use facebem::MuscleBasis;
use facebem::export::layout::ExportLayout;
use facebem::report::contact_sheet::heat;
use glam::DVec3;

use crate::posed_mesh::MeshVertex;

/// Largest texture side uploaded; larger images are scaled down to it.
pub const MAX_TEXTURE_SIDE: u32 = 4096;
/// Opacity of the heat colour over the texture.
pub const HEAT_OPACITY: f32 = 0.85;

/// One vertex of the drawn surface (48 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SurfaceVertex {
    /// Posed position (user frame).
    pub position: [f32; 3],
    /// Unit normal of the posed mesh.
    pub normal: [f32; 3],
    /// Texture coordinate, glTF convention (origin at the image's top left).
    pub uv: [f32; 2],
    /// Heat colour (display RGB, premultiplied by its opacity, so it interpolates without
    /// darkening toward skin that does not move) and its opacity over the material (0: none).
    pub heat: [f32; 4],
}

/// A decoded texture, RGBA8, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureImage {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width · height · 4` bytes.
    pub rgba: Vec<u8>,
}

impl TextureImage {
    /// Decodes a PNG or JPEG file's bytes, scaled down to [`MAX_TEXTURE_SIDE`] if larger.
    pub fn decode(bytes: &[u8]) -> Result<TextureImage, String> {
        let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| e.to_string())?;
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(32_768);
        limits.max_image_height = Some(32_768);
        limits.max_alloc = Some(1 << 30);
        reader.limits(limits);
        let mut img = reader.decode().map_err(|e| e.to_string())?.to_rgba8();
        let (w, h) = img.dimensions();
        if w.max(h) > MAX_TEXTURE_SIDE {
            let k = f64::from(MAX_TEXTURE_SIDE) / f64::from(w.max(h));
            let size = |s: u32| ((f64::from(s) * k).round() as u32).max(1);
            img = image::imageops::thumbnail(&img, size(w), size(h));
        }
        Ok(TextureImage {
            width: img.width(),
            height: img.height(),
            rgba: img.into_raw(),
        })
    }
}

/// One material of the user's file.
#[derive(Clone, Debug, PartialEq)]
pub struct LookMaterial {
    /// Its name in the file.
    pub name: String,
    /// Linear RGBA factor.
    pub base_color: [f32; 4],
    /// The decoded texture.
    pub texture: Option<Arc<TextureImage>>,
}

/// The materials of a face file and which triangle uses which (triangles in the order of the
/// file's faces, polygons fan-triangulated, as [`ExportLayout`] lists them).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Looks {
    /// The materials.
    pub materials: Vec<LookMaterial>,
    /// Per triangle, its material (`None`: the viewer's skin).
    pub triangle_material: Vec<Option<u32>>,
    /// What could not be used, one line each (a missing or undecodable texture).
    pub warnings: Vec<String>,
}

impl Looks {
    /// Reads the materials of the face file `path` (`obj_text`: the OBJ text the face was read
    /// from, for OBJ input). Never fails: what cannot be read is a warning and leaves the skin.
    pub fn load(path: &Path, obj_text: Option<&str>) -> Looks {
        let folder = match path.parent() {
            Some(f) if !f.as_os_str().is_empty() => f,
            _ => Path::new("."),
        };
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        let mut looks = Looks::default();
        match (ext.as_str(), obj_text) {
            ("gltf" | "glb" | "vrm", _) => looks.read_gltf(path, folder),
            (_, Some(text)) => looks.read_obj(text, folder),
            _ => {}
        }
        looks
    }

    fn read_obj(&mut self, text: &str, folder: &Path) {
        let m = match facebem::export::material::ObjMaterials::load(text, folder) {
            Ok(m) => m,
            Err(e) => return self.warnings.push(e.to_string()),
        };
        self.warnings.extend(m.warnings);
        self.triangle_material = m.triangle_material;
        for u in m.materials {
            let [r, g, b] = u.base_color;
            let texture = u.texture.and_then(|t| self.decoded(&u.name, &t.bytes));
            self.materials.push(LookMaterial {
                name: u.name,
                base_color: [r, g, b, 1.0],
                texture,
            });
        }
    }

    fn read_gltf(&mut self, path: &Path, folder: &Path) {
        let limits = face_prep::InputLimits::default();
        let read = face_prep::limits::read_input_file(path, &limits)
            .map_err(|e| e.to_string())
            .and_then(|bytes| {
                let data = face_prep::gltf_face_data(&bytes, Some(folder), None, &limits)
                    .map_err(|e| e.to_string())?;
                let looks = face_prep::gltf_read::material_looks(&bytes, Some(folder), &limits)
                    .map_err(|e| e.to_string())?;
                Ok((data.triangle_material, looks))
            });
        let (triangle_material, looks) = match read {
            Ok(r) => r,
            Err(e) => return self.warnings.push(e),
        };
        self.triangle_material = triangle_material;
        for l in looks {
            self.warnings.extend(l.warning);
            let texture = l.image.and_then(|b| self.decoded(&l.name, &b));
            self.materials.push(LookMaterial {
                name: l.name,
                base_color: l.base_color,
                texture,
            });
        }
    }

    fn decoded(&mut self, material: &str, bytes: &[u8]) -> Option<Arc<TextureImage>> {
        match TextureImage::decode(bytes) {
            Ok(t) => Some(Arc::new(t)),
            Err(e) => {
                self.warnings
                    .push(format!("material {material:?}: its texture: {e}"));
                None
            }
        }
    }
}

/// Triangles drawn with one material.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfacePart {
    /// Triangle-list indices into the surface's vertices.
    pub indices: Vec<u32>,
    /// RGBA factor, display values.
    pub base_color: [f32; 4],
    /// Index into [`Surface::textures`].
    pub texture: Option<usize>,
}

/// The drawn surface of one face: vertices (with seam copies), their texture coordinates and
/// the triangles of each material.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    /// Per drawn vertex: the basis vertex giving its position, or `None` (an input position no
    /// face uses; drawn at `rest`).
    pub welded: Vec<Option<u32>>,
    /// Per drawn vertex: the input position (used when `welded` is `None`).
    pub rest: Vec<[f32; 3]>,
    /// Per drawn vertex: texture coordinates (zeros without them).
    pub uvs: Vec<[f32; 2]>,
    /// The triangles, by material.
    pub parts: Vec<SurfacePart>,
    /// The textures the parts use.
    pub textures: Vec<Arc<TextureImage>>,
}

impl Surface {
    /// The surface of `basis` in the layout of the OBJ text it was read from (or its welded
    /// vertices), with `looks` (`skin`: the colour of triangles without a material).
    ///
    /// ```
    /// use facebem::MuscleBasis;
    /// use glam::DVec3;
    /// use viewer::surface::{Looks, Surface};
    /// let basis = MuscleBasis {
    ///     muscle_ids: vec![],
    ///     neutral: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
    ///     triangles: vec![[0, 1, 2]],
    ///     displacements: vec![],
    /// };
    /// let s = Surface::new(&basis, None, &Looks::default(), [1.0, 0.5, 0.5, 1.0]);
    /// assert_eq!(s.parts[0].indices, [0, 1, 2]);
    /// assert!(s.textures.is_empty());
    /// ```
    pub fn new(
        basis: &MuscleBasis,
        source: Option<(&FaceMesh, &str)>,
        looks: &Looks,
        skin: [f32; 4],
    ) -> Surface {
        let layout = source
            .and_then(|(mesh, text)| ExportLayout::from_obj_for(text, mesh).ok())
            .unwrap_or_else(|| ExportLayout::welded(&basis.neutral, &basis.triangles));
        Surface::with_layout(basis, layout, looks, skin)
    }

    /// The surface of `basis` drawn in `layout` (an OBJ's layout whose vertices index
    /// `basis`; its welded vertices if they do not) with `looks`.
    pub fn with_layout(
        basis: &MuscleBasis,
        layout: ExportLayout,
        looks: &Looks,
        skin: [f32; 4],
    ) -> Surface {
        let n = basis.neutral.len();
        let layout = Some(layout)
            .filter(|l| l.welded.iter().flatten().all(|&w| (w as usize) < n))
            .unwrap_or_else(|| ExportLayout::welded(&basis.neutral, &basis.triangles));
        let uvs = layout
            .uvs
            .clone()
            .unwrap_or_else(|| vec![[0.0; 2]; layout.len()]);
        let use_looks = looks.triangle_material.len() == layout.triangles.len();
        let mut textures = Vec::new();
        let mut parts: Vec<SurfacePart> = Vec::new();
        // Part 0..m: the materials; part m: the skin.
        let m = looks.materials.len();
        let mut part_of = vec![usize::MAX; m + 1];
        for (t, tri) in layout.triangles.iter().enumerate() {
            let material = (use_looks)
                .then(|| looks.triangle_material[t])
                .flatten()
                .map_or(m, |k| (k as usize).min(m));
            if part_of[material] == usize::MAX {
                part_of[material] = parts.len();
                parts.push(match looks.materials.get(material) {
                    Some(mat) => {
                        let texture = mat.texture.as_ref().map(|tex| {
                            textures.push(Arc::clone(tex));
                            textures.len() - 1
                        });
                        let [r, g, b, a] = mat.base_color;
                        SurfacePart {
                            indices: Vec::new(),
                            base_color: [srgb(r), srgb(g), srgb(b), a],
                            texture,
                        }
                    }
                    None => SurfacePart {
                        indices: Vec::new(),
                        base_color: skin,
                        texture: None,
                    },
                });
            }
            parts[part_of[material]].indices.extend_from_slice(tri);
        }
        Surface {
            welded: layout.welded,
            rest: layout
                .positions
                .iter()
                .map(|p| p.as_vec3().to_array())
                .collect(),
            uvs,
            parts,
            textures,
        }
    }

    /// Fills `out` with the drawn vertices of the posed welded vertices `posed`; with `heat`
    /// (neutral and posed positions in f64, millimetres per unit) each vertex gets its heat
    /// colour.
    pub fn fill(
        &self,
        posed: &[MeshVertex],
        heat: Option<(&[DVec3], &[DVec3], f64)>,
        out: &mut Vec<SurfaceVertex>,
    ) {
        out.clear();
        out.extend(self.welded.iter().enumerate().map(|(j, w)| {
            let v = w.and_then(|w| posed.get(w as usize));
            let heat = match (w, heat) {
                (Some(w), Some((neutral, posed, mm))) => {
                    let w = *w as usize;
                    match (neutral.get(w), posed.get(w)) {
                        (Some(a), Some(b)) => heat_colour(a.distance(*b) * mm),
                        _ => [0.0; 4],
                    }
                }
                _ => [0.0; 4],
            };
            SurfaceVertex {
                position: v.map_or(self.rest[j], |v| v.position),
                normal: v.map_or([0.0; 3], |v| v.normal),
                uv: self.uvs[j],
                heat,
            }
        }));
    }
}

/// The heat colour of a displacement in millimetres, premultiplied by [`HEAT_OPACITY`]
/// (all zero below the scale's first edge).
///
/// ```
/// use viewer::surface::{HEAT_OPACITY, heat_colour};
/// assert_eq!(heat_colour(0.2), [0.0; 4]);
/// let c = heat_colour(9.3); // [8, 10) mm: orange
/// assert_eq!(c[3], HEAT_OPACITY);
/// assert_eq!(c[0], 250.0 / 255.0 * HEAT_OPACITY);
/// ```
pub fn heat_colour(displacement_mm: f64) -> [f32; 4] {
    match heat::bin(displacement_mm) {
        None => [0.0; 4],
        Some(b) => {
            let [r, g, b] = heat::COLOURS[b].map(|c| f32::from(c) / 255.0 * HEAT_OPACITY);
            [r, g, b, HEAT_OPACITY]
        }
    }
}

/// Linear → sRGB-encoded (IEC 61966-2-1).
fn srgb(linear: f32) -> f32 {
    let c = linear.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}
