//! glTF 2.0 export (`.glb` binary or `.gltf` with an embedded buffer) with morph targets.
//!
//! The file holds the user's neutral face — in the user's own vertex order with the input's
//! texture coordinates and normals where it had them ([`ExportLayout`]), positions in metres
//! (glTF's unit: input positions × [`GltfParams::metres_per_unit`]) — and, as morph targets, in
//! this order ([`GltfParams::names`] picks the sets, default all):
//!
//! 1. the ARKit blendshapes the rig can make, by their ARKit names (`mouthSmileLeft`, …), then
//!    the VRM 1.0 presets (`happy`, `aa`, `blinkLeft`, …, `neutral` as a zero target) — see
//!    [`crate::expressions`]. Names whose controls the rig lacks entirely are left out and
//!    listed with the reason in `mesh.extras.leftOutTargets`; names made from only some of
//!    their controls are listed with the missing ones in `mesh.extras.partialTargets`;
//! 2. facebem's own: `<muscle id>_contract` (slider −1) and `<muscle id>_relax` (slider +1) for
//!    every muscle, then `preset_<name>` for every expression preset except `neutral` (the base
//!    mesh is neutral).
//!
//! Names never repeat (ARKit and VRM names have no `_`, facebem's all have one). Target names
//! are listed in `mesh.extras.targetNames` (three.js's `morphTargetDictionary` reads them, so
//! `morphTargetDictionary['happy']` is the VRM `happy` target). Every morph weight in [0, 1]
//! reproduces the facebem pose exactly for the positions (linear basis): weight `w` on
//! `<id>_contract` equals slider `−w`. NORMAL deltas are the change of the area-weighted vertex
//! normal at full weight (normals are not linear; this is the usual approximation). All
//! default weights are 0.
//!
//! The primitive uses one material, [`MATERIAL_NAME`] (skin-coloured PBR, metalness 0,
//! double-sided: the face is an open surface), for the user to replace. `asset.copyright`
//! carries the source's attribution when it is known ([`super::attribution`]), `asset.extras`
//! its licence, the input's OBJ header and the unit conversion. With
//! [`GltfParams::animation`], each facebem preset gets its own animation clip named after it
//! (`happy`, `sad`, …): neutral → expression → neutral (the VRM expressions instead, when
//! facebem's own names are not exported).

mod buffer;
mod checks;
mod meshopt;
mod primitives;
mod summary;
mod targets;

pub use summary::{GltfSummary, build_gltf};
pub use targets::{NamedTargets, named_targets};

use glam::DVec3;
use serde_json::{Map, Value, json};

use super::layout::ExportLayout;
use crate::MuscleBasis;
use crate::expressions::NameSets;
use crate::expressions::presets::Preset;
use buffer::{Builder, base64, glb};
use checks::{check, check_fields};
use targets::{MorphTargets, morph_targets, target_accessors};

/// Name of the material of the exported face: replace it to texture the face.
pub const MATERIAL_NAME: &str = "facebem_skin";

/// Container format of a glTF export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum GltfFormat {
    /// Binary `.glb`: JSON chunk + BIN chunk.
    Binary,
    /// Text `.gltf` with the buffer embedded as a base64 data URI.
    Embedded,
}

impl GltfFormat {
    /// Picks the format from a file name: `.gltf` → [`GltfFormat::Embedded`], anything else
    /// (normally `.glb`) → [`GltfFormat::Binary`].
    pub fn from_path(path: &std::path::Path) -> GltfFormat {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("gltf") => GltfFormat::Embedded,
            _ => GltfFormat::Binary,
        }
    }
}

/// How ARKit's morph targets are spelled ([`GltfParams::arkit_naming`]).
///
/// ```
/// use facebem::export::ArkitNaming;
/// assert_eq!(ArkitNaming::parse("arkit-raw"), Ok(ArkitNaming::Raw));
/// assert_eq!(ArkitNaming::Raw.name("eyeBlinkLeft"), "eyeBlink_L");
/// assert_eq!(ArkitNaming::Swift.name("eyeBlinkLeft"), "eyeBlinkLeft");
/// assert!(ArkitNaming::parse("apple").is_err());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ArkitNaming {
    /// `eyeBlinkLeft`: the Swift constants' spelling, which glTF and three.js avatars use
    /// (`arkit`).
    #[default]
    Swift,
    /// `eyeBlink_L`: ARKit's raw location strings, which Live Link Face, Face Cap and many
    /// engines send (`arkit-raw`, [`crate::expressions::arkit::raw_name`]).
    Raw,
}

impl ArkitNaming {
    /// Parses `arkit` or `arkit-raw`.
    pub fn parse(s: &str) -> Result<ArkitNaming, String> {
        match s.trim() {
            "arkit" => Ok(ArkitNaming::Swift),
            "arkit-raw" => Ok(ArkitNaming::Raw),
            other => Err(format!(
                "unknown naming {other:?} (known: arkit, arkit-raw)"
            )),
        }
    }

    /// The spelling of ARKit's `name` (as in [`crate::expressions::arkit::NAMES`]); any other
    /// name is returned as it is.
    pub fn name(self, name: &str) -> String {
        match self {
            ArkitNaming::Swift => name.to_string(),
            ArkitNaming::Raw => {
                crate::expressions::arkit::raw_name(name).unwrap_or_else(|| name.to_string())
            }
        }
    }
}

/// Options of a glTF export.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfParams {
    /// Container format.
    pub format: GltfFormat,
    /// Add one animation clip per preset, named after it (off by default: importers such as
    /// Blender's bind a clip to every shape key, which then cannot be set by hand).
    pub animation: bool,
    /// Seconds from neutral to the full expression (and back) in each clip.
    pub seconds_per_keyframe: f32,
    /// Presets to add as morph targets (and as clips); `neutral` is skipped.
    pub presets: Vec<Preset>,
    /// Which name sets become morph targets: ARKit, VRM (first, in that order) and facebem's
    /// own muscle and preset targets.
    pub names: NameSets,
    /// Metres per unit of the input positions (glTF's unit is the metre): 0.01 for a face in
    /// centimetres. [`crate::FaceModel::write_gltf`] sets it from the rig's length unit.
    pub metres_per_unit: f64,
    /// `asset.copyright`: the source's attribution, if known.
    pub copyright: Option<String>,
    /// Extra `asset.extras` entries (licence, source header); the unit conversion is added.
    pub asset_extras: Map<String, Value>,
    /// How the ARKit targets are spelled.
    pub arkit_naming: ArkitNaming,
    /// Compress every buffer view with `EXT_meshopt_compression` (then a required extension:
    /// three.js needs its `MeshoptDecoder`); a neutral coordinate is kept to 2⁻¹⁹ of the
    /// largest on its axis (0.6 µm on a 0.3 m head), a target's deltas to 2⁻¹⁵ of its largest,
    /// normals to 2⁻¹¹.
    pub compress: bool,
    /// The user's OBJ materials ([`crate::export::material::ObjMaterials::load`]): one
    /// primitive per material with its colour and embedded texture; `None` (or none used):
    /// one primitive with [`MATERIAL_NAME`].
    pub materials: Option<crate::export::material::ObjMaterials>,
    /// Fields for ARKit and VRM names: (standard name, displacement of every basis vertex at
    /// weight 1). For names no control makes ([`crate::expressions::NOT_MODELLED`]: the gaze
    /// targets and `tongueOut` of a head with eyeballs and a tongue,
    /// [`crate::transfer::head::HeadBasis::named_fields`]), and in place of what the controls
    /// make of a name (a head's targets kept off its eyeballs,
    /// [`crate::transfer::head::HeadBasis::named_fields_for`]). Written in the standard's
    /// order when the name's set is exported; any other name, or a field of the wrong length,
    /// is an error.
    pub named_fields: Vec<(String, Vec<glam::DVec3>)>,
    /// One mesh (and node) per group of triangles instead of one mesh: a head's parts. All
    /// meshes share the vertices and carry every target.
    pub mesh_split: Option<MeshSplit>,
}

/// Triangles grouped into meshes ([`GltfParams::mesh_split`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshSplit {
    /// The meshes' names.
    pub names: Vec<String>,
    /// Per triangle of the export layout, its mesh (an index into `names`); ignored (one mesh)
    /// when its length is not the layout's triangle count.
    pub triangle_mesh: Vec<u32>,
}

impl Default for GltfParams {
    fn default() -> Self {
        GltfParams {
            format: GltfFormat::Binary,
            animation: false,
            seconds_per_keyframe: 1.0,
            presets: crate::expressions::presets::ALL.to_vec(),
            names: NameSets::USERS,
            metres_per_unit: 1.0,
            copyright: None,
            asset_extras: Map::new(),
            arkit_naming: ArkitNaming::Swift,
            compress: false,
            materials: None,
            named_fields: Vec::new(),
            mesh_split: None,
        }
    }
}

/// Errors from glTF export.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GltfExportError {
    /// The basis has no vertices or no triangles.
    #[error("cannot export an empty mesh ({vertices} vertices, {triangles} triangles)")]
    EmptyMesh {
        /// Vertex count.
        vertices: usize,
        /// Triangle count.
        triangles: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {vertex}, but there are only {count} vertices")]
    IndexOutOfRange {
        /// Triangle index.
        triangle: usize,
        /// Offending vertex index.
        vertex: u32,
        /// Vertex count.
        count: usize,
    },
    /// A muscle's displacement field does not have one vector per vertex.
    #[error("muscle {muscle} has {got} displacement vectors for {expected} vertices")]
    FieldLength {
        /// Muscle id.
        muscle: String,
        /// Vertex count.
        expected: usize,
        /// Vectors found.
        got: usize,
    },
    /// A named field ([`GltfParams::named_fields`]) is for no ARKit or VRM name.
    #[error("{0:?} is not an ARKit or VRM name, for which a named field can be given")]
    NotANamedField(String),
    /// A named field does not have one vector per vertex.
    #[error("the field of {name} has {len} vectors for {vertices} vertices")]
    NamedFieldLength {
        /// The standard name.
        name: String,
        /// Vectors found.
        len: usize,
        /// Vertex count.
        vertices: usize,
    },
    /// A number to write is NaN or infinite once converted to f32 (glTF's float): a position,
    /// normal, texture coordinate, displacement or animation value.
    #[error("element {vertex} of {what} is not finite in f32")]
    NonFinite {
        /// Which field (`neutral`, `texture coordinates`, a target name, `animation times`).
        what: String,
        /// Element (vertex) index.
        vertex: usize,
    },
    /// The seconds per keyframe are not a positive finite number (twice it too: the clips'
    /// last keyframe).
    #[error("seconds per keyframe must be positive and finite (twice it too), got {0}")]
    BadKeyframeTime(f32),
    /// The metres per input unit are not a positive finite number.
    #[error("metres per unit must be positive and finite, got {0}")]
    BadUnit(f64),
    /// The export layout does not fit the basis.
    #[error("the export layout does not fit the mesh: {0}")]
    Layout(String),
    /// Two morph targets would have the same name (e.g. a muscle file naming two muscles alike).
    #[error("two morph targets are named {0:?}")]
    DuplicateTarget(String),
    /// meshoptimizer refused to encode a buffer view (`--compress`).
    #[error("compressing the glTF failed: {0}")]
    Compress(String),
    /// The morph targets would make the file larger than [`MAX_EXPORT_BYTES`].
    #[error(
        "the glTF would be about {} MiB ({targets} morph targets x {vertices} vertices), over the {} MiB limit; export fewer names (--names arkit) or simplify the face mesh",
        bytes >> 20,
        MAX_EXPORT_BYTES >> 20
    )]
    TooLarge {
        /// Estimated size in bytes.
        bytes: u64,
        /// Morph targets asked for.
        targets: usize,
        /// glTF vertices.
        vertices: usize,
    },
}

/// Largest glTF export written (1 GiB), checked from the target and vertex counts before any
/// target is built. Regression (issue 36): a 1.18 M-triangle face's export was 2.0 GB and took
/// 6.6 GB of memory; three.js and Blender load files up to this size in a few seconds per
/// hundred MB, and a GLB cannot exceed 4 GiB at all.
pub const MAX_EXPORT_BYTES: u64 = 1 << 30;

/// Builds the glTF file (bytes of a `.glb`, or UTF-8 JSON of a `.gltf`) for `basis`, with its
/// welded vertices in order ([`ExportLayout::welded`]).
///
/// ```
/// use facebem::MuscleBasis;
/// use facebem::export::gltf::{export_gltf, GltfParams};
/// use glam::DVec3;
/// let basis = MuscleBasis {
///     muscle_ids: vec!["zygomaticus_major_l".into()],
///     neutral: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
///     triangles: vec![[0, 1, 2]],
///     displacements: vec![vec![DVec3::ZERO, DVec3::Z * 0.1, DVec3::ZERO]],
/// };
/// let glb = export_gltf(&basis, &GltfParams::default()).unwrap();
/// assert_eq!(&glb[0..4], b"glTF");
/// ```
pub fn export_gltf(basis: &MuscleBasis, params: &GltfParams) -> Result<Vec<u8>, GltfExportError> {
    let layout = ExportLayout::welded(&basis.neutral, &basis.triangles);
    export_gltf_layout(basis, &layout, params)
}

/// Like [`export_gltf`], with the glTF vertices of `layout` (the user's own order, texture
/// coordinates and normals).
pub fn export_gltf_layout(
    basis: &MuscleBasis,
    layout: &ExportLayout,
    params: &GltfParams,
) -> Result<Vec<u8>, GltfExportError> {
    check(basis, layout, params)?;
    let scale = params.metres_per_unit;
    let mut b = Builder {
        compress: params.compress,
        ..Builder::default()
    };
    let neutral_normals = vertex_normals(&basis.neutral, &basis.triangles);
    let attributes = neutral_accessors(&mut b, basis, layout, &neutral_normals, scale)?;
    let looks = primitives::looks(&mut b, layout, params, &attributes);
    let MorphTargets {
        targets,
        clip_targets,
        partial,
        left_out,
        same_as,
        negative_of,
    } = morph_targets(basis, params)?;
    // A POSITION and a NORMAL delta (3 f32 each) per vertex per target, plus the neutral
    // attributes and the indices.
    let vertices = layout.len();
    let bytes = (vertices as u64)
        .saturating_mul(24 * targets.len() as u64 + 32)
        .saturating_add(12 * basis.triangles.len() as u64);
    if bytes > MAX_EXPORT_BYTES {
        return Err(GltfExportError::TooLarge {
            bytes,
            targets: targets.len(),
            vertices,
        });
    }
    let target_json = target_accessors(&mut b, basis, layout, &targets, &neutral_normals, scale)?;
    let names: Vec<&str> = targets.iter().map(|(n, _)| n.as_str()).collect();
    let mut extras = mesh_extras(&names, left_out, partial, layout);
    if !same_as.is_empty() {
        extras["sameAs"] = Value::Object(same_as);
    }
    if !negative_of.is_empty() {
        extras["negativeOf"] = Value::Object(negative_of);
    }
    if !looks.warnings.is_empty() {
        extras["materialWarnings"] = json!(looks.warnings);
    }
    let names = params.mesh_split.as_ref().map(|s| s.names.clone());
    let mut root = root_json(asset_json(params), looks, extras, names);
    // glTF requires at least one target when `targets` is present.
    if !targets.is_empty() {
        for mesh in root["meshes"].as_array_mut().into_iter().flatten() {
            for primitive in mesh["primitives"].as_array_mut().into_iter().flatten() {
                primitive["targets"] = Value::Array(target_json.clone());
            }
            mesh["weights"] = json!(vec![0.0; targets.len()]);
        }
    }
    if params.animation && !clip_targets.is_empty() {
        let nodes = root["nodes"].as_array().map_or(1, Vec::len);
        root["animations"] = animations(&mut b, params, &clip_targets, targets.len(), nodes)?;
    }
    finish(b, root, params.format)
}

/// How far from the vertex it takes, as a fraction of the face's bounding-box diagonal, a line
/// must be drawn to keep its own neutral position: a hundred times the separation of a cut
/// line's two sides ([`face_prep::frame::contact::SEPARATION_REL`]).
pub const FOLLOWER_REL: f64 = 100.0 * face_prep::frame::contact::SEPARATION_REL;

/// Writes the neutral face's accessors (positions, normals, texture coordinates); returns the
/// primitives' `attributes`.
fn neutral_accessors(
    b: &mut Builder,
    basis: &MuscleBasis,
    layout: &ExportLayout,
    neutral_normals: &[DVec3],
    scale: f64,
) -> Result<Value, GltfExportError> {
    // A line drawn away from the vertex it takes (a mouth bag's line following its lip,
    // `face_prep::frame::contact::bag`) keeps its own position; one at its vertex (to within
    // the 2 µm of a cut line's sides) gets the vertex's.
    let (lo, hi) = face_prep::topology::bounding_box(basis.neutral.iter().copied());
    let own_beyond = FOLLOWER_REL * (hi - lo).length();
    let positions: Vec<DVec3> = layout
        .welded
        .iter()
        .zip(&layout.positions)
        .map(|(w, p)| match w {
            Some(w) if basis.neutral[*w as usize].distance(*p) <= own_beyond => {
                basis.neutral[*w as usize] * scale
            }
            _ => *p * scale,
        })
        .collect();
    let normals: Vec<DVec3> = (0..layout.len())
        .map(|j| {
            let given = layout.normals.as_ref().and_then(|n| n[j]);
            let computed = layout.welded[j].map(|w| neutral_normals[w as usize]);
            given.or(computed).unwrap_or(DVec3::Z)
        })
        .collect();
    let position = b.vec3_accessor("neutral", &positions, true, buffer::POSITION_BITS)?;
    let normal = b.vec3_accessor("neutral normals", &normals, false, buffer::NORMAL_BITS)?;
    let mut attributes = json!({ "POSITION": position, "NORMAL": normal });
    if let Some(uvs) = &layout.uvs {
        attributes["TEXCOORD_0"] = json!(b.vec2_accessor("texture coordinates", uvs)?);
    }
    Ok(attributes)
}

/// `mesh.extras`: the target names, the left-out and partial targets, the seam copies.
fn mesh_extras(
    names: &[&str],
    left_out: Map<String, Value>,
    partial: Map<String, Value>,
    layout: &ExportLayout,
) -> Value {
    let mut extras = json!({ "targetNames": names });
    if !left_out.is_empty() {
        extras["leftOutTargets"] = Value::Object(left_out);
    }
    if !partial.is_empty() {
        extras["partialTargets"] = Value::Object(partial);
    }
    if layout.len() > layout.input_count {
        extras["seamCopyOf"] = json!(&layout.input_index[layout.input_count..]);
    }
    extras
}

/// The `asset` object: version, generator, extras (with the unit conversion), copyright.
fn asset_json(params: &GltfParams) -> Value {
    let mut asset_extras = params.asset_extras.clone();
    asset_extras.insert("metresPerInputUnit".into(), json!(params.metres_per_unit));
    let mut asset = json!({
        "version": "2.0",
        "generator": concat!("facebem ", env!("CARGO_PKG_VERSION")),
        "extras": asset_extras,
    });
    if let Some(c) = &params.copyright {
        asset["copyright"] = json!(c);
    }
    asset
}

/// The document's root: one scene, node and mesh; the primitives and materials of `looks`.
/// The node and the mesh are named `face`, the scene `facebem`: three.js names its objects after
/// them and makes a repeated name unique (`face_1`), so with the scene also named `face`,
/// `getObjectByName('face')` found the scene instead of the mesh (issue 34).
fn root_json(
    asset: Value,
    looks: primitives::Looks,
    extras: Value,
    names: Option<Vec<String>>,
) -> Value {
    // One mesh and node per group that has primitives (one, `face`, without a split).
    let names = names.unwrap_or_else(|| vec!["face".to_string()]);
    let (mut meshes, mut nodes) = (Vec::new(), Vec::new());
    for (group, name) in names.iter().enumerate() {
        let primitives: Vec<Value> = looks
            .primitives
            .iter()
            .filter(|(m, _)| *m == group)
            .map(|(_, p)| p.clone())
            .collect();
        if primitives.is_empty() {
            continue;
        }
        nodes.push(json!({ "name": name, "mesh": meshes.len() }));
        meshes.push(json!({ "name": name, "primitives": primitives, "extras": extras }));
    }
    let scene_nodes: Vec<usize> = (0..nodes.len()).collect();
    let mut root = json!({
        "asset": asset,
        "scene": 0,
        "scenes": [{ "name": "facebem", "nodes": scene_nodes }],
        "nodes": nodes,
        "materials": looks.materials,
        "meshes": meshes,
    });
    if !looks.images.is_empty() {
        root["images"] = json!(looks.images);
        root["textures"] = json!(looks.textures);
    }
    root
}

/// One clip per preset (`clip_targets`: clip name, target index among `target_count`):
/// neutral, the preset at full weight, neutral. Writes their accessors.
fn animations(
    b: &mut Builder,
    params: &GltfParams,
    clip_targets: &[(String, usize)],
    target_count: usize,
    nodes: usize,
) -> Result<Value, GltfExportError> {
    let s = params.seconds_per_keyframe;
    let input = b.scalar_accessor("animation times", &[0.0, s, 2.0 * s], true)?;
    let mut clips = Vec::new();
    for (name, t) in clip_targets {
        let t = *t;
        let mut weights = vec![0.0f32; 3 * target_count];
        weights[target_count + t] = 1.0;
        let output = b.scalar_accessor(&format!("animation {name} weights"), &weights, false)?;
        clips.push(json!({
            "name": name,
            "samplers": [{ "input": input, "output": output, "interpolation": "LINEAR" }],
            "channels": (0..nodes).map(|node| json!({ "sampler": 0, "target": { "node": node, "path": "weights" } })).collect::<Vec<_>>(),
        }));
    }
    Ok(Value::Array(clips))
}

/// Pads the buffer, adds the buffer views, accessors and buffer to `root` (compressed with
/// [`meshopt`] when the builder says so) and writes the file in `format`.
fn finish(b: Builder, mut root: Value, format: GltfFormat) -> Result<Vec<u8>, GltfExportError> {
    let Builder {
        mut bin,
        mut views,
        accessors,
        codecs,
        compress,
    } = b;
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let mut buffers = Vec::new();
    if compress {
        let packed = meshopt::compress_views(&bin, &mut views, &codecs)?;
        // The uncompressed views' buffer holds no data: decoders fill it.
        buffers.push(json!({
            "byteLength": bin.len(),
            "extensions": { "EXT_meshopt_compression": { "fallback": true } },
        }));
        bin = packed;
        root["extensionsUsed"] = json!(["EXT_meshopt_compression"]);
        root["extensionsRequired"] = json!(["EXT_meshopt_compression"]);
    }
    root["bufferViews"] = Value::Array(views);
    root["accessors"] = Value::Array(accessors);
    let mut data = json!({ "byteLength": bin.len() });
    if format == GltfFormat::Embedded {
        data["uri"] = json!(format!(
            "data:application/octet-stream;base64,{}",
            base64(&bin)
        ));
    }
    buffers.insert(0, data);
    root["buffers"] = Value::Array(buffers);
    Ok(match format {
        GltfFormat::Binary => glb(&root, &bin),
        GltfFormat::Embedded => serde_json::to_vec_pretty(&root).unwrap_or_default(),
    })
}

/// Area-weighted unit vertex normals (`+z` for a vertex without area).
pub fn vertex_normals(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<DVec3> {
    let mut normals = vec![DVec3::ZERO; positions.len()];
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let n = (b - a).cross(c - a);
        for &i in t {
            normals[i as usize] += n;
        }
    }
    normals
        .into_iter()
        .map(|n| n.try_normalize().unwrap_or(DVec3::Z))
        .collect()
}

#[cfg(test)]
mod tests;
