//! glTF 2.0 export (`.glb` binary or `.gltf` with an embedded buffer) with morph targets.
//!
//! The file holds the neutral face (POSITION, NORMAL, indices) and, as morph targets:
//! `<muscle id>_contract` (slider −1) and `<muscle id>_relax` (slider +1) for every muscle, then
//! `preset_<name>` for every expression preset except `neutral` (the base mesh is neutral).
//! Target names are listed in `mesh.extras.targetNames`. Every morph weight in [0, 1]
//! reproduces the facebem pose exactly for the positions (linear basis): weight `w` on
//! `<id>_contract` equals slider `−w`. NORMAL deltas are the change of the area-weighted vertex
//! normal at full weight (normals are not linear; this is the usual approximation). An optional
//! animation plays the presets one after another, returning to neutral in between.

use glam::DVec3;
use serde_json::{Value, json};

use crate::MuscleBasis;
use crate::presets::Preset;

/// Container format of a glTF export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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

/// Options of a glTF export.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfParams {
    /// Container format.
    pub format: GltfFormat,
    /// Add an animation named `presets` that blends through every preset.
    pub animation: bool,
    /// Seconds from one keyframe to the next in the animation.
    pub seconds_per_keyframe: f32,
    /// Presets to add as morph targets (and to play in the animation); `neutral` is skipped.
    pub presets: Vec<Preset>,
}

impl Default for GltfParams {
    fn default() -> Self {
        GltfParams {
            format: GltfFormat::Binary,
            animation: true,
            seconds_per_keyframe: 1.0,
            presets: crate::presets::ALL.to_vec(),
        }
    }
}

/// Errors from glTF export.
#[derive(Debug, thiserror::Error)]
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
    /// A position or displacement is not finite once converted to f32.
    #[error("vertex {vertex} of {what} is not finite in f32")]
    NonFinite {
        /// Which field (`neutral`, a target name).
        what: String,
        /// Vertex index.
        vertex: usize,
    },
    /// The seconds per keyframe are not a positive finite number.
    #[error("seconds per keyframe must be positive and finite, got {0}")]
    BadKeyframeTime(f32),
}

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;

/// Builds the glTF file (bytes of a `.glb`, or UTF-8 JSON of a `.gltf`) for `basis`.
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
    let n = basis.neutral.len();
    if n == 0 || basis.triangles.is_empty() {
        return Err(GltfExportError::EmptyMesh {
            vertices: n,
            triangles: basis.triangles.len(),
        });
    }
    if !(params.seconds_per_keyframe.is_finite() && params.seconds_per_keyframe > 0.0) {
        return Err(GltfExportError::BadKeyframeTime(
            params.seconds_per_keyframe,
        ));
    }
    for (t, tri) in basis.triangles.iter().enumerate() {
        if let Some(&v) = tri.iter().find(|&&v| v as usize >= n) {
            return Err(GltfExportError::IndexOutOfRange {
                triangle: t,
                vertex: v,
                count: n,
            });
        }
    }
    for (id, field) in basis.muscle_ids.iter().zip(&basis.displacements) {
        if field.len() != n {
            return Err(GltfExportError::FieldLength {
                muscle: id.clone(),
                expected: n,
                got: field.len(),
            });
        }
    }

    let mut b = Builder::default();
    let neutral_normals = vertex_normals(&basis.neutral, &basis.triangles);
    let position = b.vec3_accessor("neutral", &basis.neutral, true)?;
    let normal = b.vec3_accessor("neutral normals", &neutral_normals, false)?;
    let indices = b.indices_accessor(&basis.triangles);

    // Morph targets: (name, position deltas).
    let mut targets: Vec<(String, Vec<DVec3>)> = Vec::new();
    for (id, field) in basis.muscle_ids.iter().zip(&basis.displacements) {
        targets.push((
            format!("{id}_contract"),
            field.iter().map(|d| -*d).collect(),
        ));
        targets.push((format!("{id}_relax"), field.clone()));
    }
    let mut preset_targets = Vec::new();
    for preset in params.presets.iter().filter(|p| p.name != "neutral") {
        let sliders = preset.sliders_for(&basis.muscle_ids);
        let mut delta = vec![DVec3::ZERO; n];
        for (field, &s) in basis.displacements.iter().zip(&sliders) {
            for (d, f) in delta.iter_mut().zip(field) {
                *d += s * *f;
            }
        }
        preset_targets.push(targets.len());
        targets.push((format!("preset_{}", preset.name), delta));
    }

    let mut target_json = Vec::with_capacity(targets.len());
    for (name, delta) in &targets {
        let posed: Vec<DVec3> = basis
            .neutral
            .iter()
            .zip(delta)
            .map(|(p, d)| *p + *d)
            .collect();
        let normals = vertex_normals(&posed, &basis.triangles);
        let normal_delta: Vec<DVec3> = normals
            .iter()
            .zip(&neutral_normals)
            .map(|(a, b)| *a - *b)
            .collect();
        let p = b.vec3_accessor(name, delta, true)?;
        let nd = b.vec3_accessor(name, &normal_delta, false)?;
        target_json.push(json!({ "POSITION": p, "NORMAL": nd }));
    }
    let names: Vec<&str> = targets.iter().map(|(n, _)| n.as_str()).collect();

    let mut root = json!({
        "asset": { "version": "2.0", "generator": concat!("facebem ", env!("CARGO_PKG_VERSION")) },
        "scene": 0,
        "scenes": [{ "name": "face", "nodes": [0] }],
        "nodes": [{ "name": "face", "mesh": 0 }],
        "meshes": [{
            "name": "face",
            "primitives": [{
                "attributes": { "POSITION": position, "NORMAL": normal },
                "indices": indices,
                "mode": 4,
                "targets": target_json,
            }],
            "weights": vec![0.0; targets.len()],
            "extras": { "targetNames": names },
        }],
    });

    if params.animation && !preset_targets.is_empty() {
        // Keyframes: neutral, preset 1, neutral, preset 2, ..., neutral.
        let keys = 2 * preset_targets.len() + 1;
        let times: Vec<f32> = (0..keys)
            .map(|k| k as f32 * params.seconds_per_keyframe)
            .collect();
        let mut weights = vec![0.0f32; keys * targets.len()];
        for (i, &t) in preset_targets.iter().enumerate() {
            weights[(2 * i + 1) * targets.len() + t] = 1.0;
        }
        let input = b.scalar_accessor(&times, true);
        let output = b.scalar_accessor(&weights, false);
        root["animations"] = json!([{
            "name": "presets",
            "samplers": [{ "input": input, "output": output, "interpolation": "LINEAR" }],
            "channels": [{ "sampler": 0, "target": { "node": 0, "path": "weights" } }],
        }]);
    }

    let Builder {
        mut bin,
        views,
        accessors,
    } = b;
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    root["bufferViews"] = Value::Array(views);
    root["accessors"] = Value::Array(accessors);
    match params.format {
        GltfFormat::Binary => {
            root["buffers"] = json!([{ "byteLength": bin.len() }]);
            Ok(glb(&root, &bin))
        }
        GltfFormat::Embedded => {
            root["buffers"] = json!([{
                "byteLength": bin.len(),
                "uri": format!("data:application/octet-stream;base64,{}", base64(&bin)),
            }]);
            Ok(serde_json::to_vec_pretty(&root).unwrap_or_default())
        }
    }
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

#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut v = json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    fn vec3_accessor(
        &mut self,
        what: &str,
        data: &[DVec3],
        with_bounds: bool,
    ) -> Result<usize, GltfExportError> {
        let mut bytes = Vec::with_capacity(data.len() * 12);
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for (vertex, p) in data.iter().enumerate() {
            let q = p.as_vec3().to_array();
            if !q.iter().all(|c| c.is_finite()) {
                return Err(GltfExportError::NonFinite {
                    what: what.to_string(),
                    vertex,
                });
            }
            for i in 0..3 {
                min[i] = min[i].min(q[i]);
                max[i] = max[i].max(q[i]);
                bytes.extend_from_slice(&q[i].to_le_bytes());
            }
        }
        let view = self.view(&bytes, Some(ARRAY_BUFFER));
        let mut a = json!({
            "bufferView": view, "componentType": FLOAT, "count": data.len(), "type": "VEC3",
        });
        if with_bounds {
            a["min"] = json!(min);
            a["max"] = json!(max);
        }
        self.accessors.push(a);
        Ok(self.accessors.len() - 1)
    }

    fn indices_accessor(&mut self, triangles: &[[u32; 3]]) -> usize {
        let bytes: Vec<u8> = triangles
            .iter()
            .flatten()
            .flat_map(|i| i.to_le_bytes())
            .collect();
        let view = self.view(&bytes, Some(ELEMENT_ARRAY_BUFFER));
        self.accessors.push(json!({
            "bufferView": view, "componentType": UNSIGNED_INT, "count": triangles.len() * 3,
            "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    fn scalar_accessor(&mut self, data: &[f32], with_bounds: bool) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, None);
        let mut a = json!({
            "bufferView": view, "componentType": FLOAT, "count": data.len(), "type": "SCALAR",
        });
        if with_bounds {
            let min = data.iter().copied().fold(f32::INFINITY, f32::min);
            let max = data.iter().copied().fold(f32::NEG_INFINITY, f32::max);
            a["min"] = json!([min]);
            a["max"] = json!([max]);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }
}

/// Binary glTF container: 12-byte header, JSON chunk (space-padded), BIN chunk (zero-padded).
fn glb(root: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(root).unwrap_or_default();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out
}

/// Standard base64 (RFC 4648, with padding) for the embedded buffer's data URI.
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, encoded) in cases {
            assert_eq!(base64(plain.as_bytes()), encoded);
        }
    }

    #[test]
    fn bad_inputs_are_typed_errors() {
        let mut basis = MuscleBasis {
            muscle_ids: vec!["m".into()],
            neutral: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            triangles: vec![[0, 1, 3]],
            displacements: vec![vec![DVec3::ZERO; 3]],
        };
        let p = GltfParams::default();
        assert!(matches!(
            export_gltf(&basis, &p),
            Err(GltfExportError::IndexOutOfRange { vertex: 3, .. })
        ));
        basis.triangles = vec![[0, 1, 2]];
        basis.displacements[0].pop();
        assert!(matches!(
            export_gltf(&basis, &p),
            Err(GltfExportError::FieldLength { got: 2, .. })
        ));
        basis.displacements[0].push(DVec3::new(f64::MAX, 0.0, 0.0));
        assert!(matches!(
            export_gltf(&basis, &p),
            Err(GltfExportError::NonFinite { vertex: 2, .. })
        ));
    }
}
