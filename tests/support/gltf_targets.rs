//! The morph targets of an exported glTF by name, with the targets left out as repeats
//! (`mesh.extras.sameAs`, `negativeOf`) resolved to the field they stand for.
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::Path;

/// What an export holds, read back with the `gltf` crate (sparse accessors included).
pub struct Targets {
    /// `mesh.extras.targetNames`: the targets written, in file order.
    pub written: Vec<String>,
    /// Position deltas per glTF vertex, by name: every written target, and every left-out
    /// repeat as the written target it equals (or its negative).
    pub positions: HashMap<String, Vec<[f32; 3]>>,
    /// `meshes[0].extras`.
    pub extras: serde_json::Value,
}

/// Reads `path` (`.glb` or `.gltf`).
pub fn read(path: &Path) -> Targets {
    let (doc, buffers, _) = gltf::import(path).expect("the gltf crate reads the export");
    let mesh = doc.meshes().next().expect("one mesh");
    let extras: serde_json::Value = mesh
        .extras()
        .as_ref()
        .map(|raw| serde_json::from_str(raw.get()).unwrap())
        .unwrap_or_default();
    let written: Vec<String> = extras["targetNames"]
        .as_array()
        .map(|a| a.iter().map(|s| s.as_str().unwrap().to_string()).collect())
        .unwrap_or_default();
    let prim = mesh.primitives().next().expect("one primitive");
    let reader = prim.reader(|b| Some(&buffers[b.index()]));
    let fields: Vec<Vec<[f32; 3]>> = reader
        .read_morph_targets()
        .map(|(p, _, _)| p.expect("a POSITION delta").collect())
        .collect();
    assert_eq!(fields.len(), written.len(), "one name per target");
    let mut positions: HashMap<String, Vec<[f32; 3]>> =
        written.iter().cloned().zip(fields).collect();
    for (key, sign) in [("sameAs", 1.0f32), ("negativeOf", -1.0)] {
        for (name, of) in extras[key].as_object().into_iter().flatten() {
            let field = positions[of.as_str().unwrap()]
                .iter()
                .map(|d| d.map(|c| sign * c))
                .collect();
            positions.insert(name.clone(), field);
        }
    }
    Targets {
        written,
        positions,
        extras,
    }
}
