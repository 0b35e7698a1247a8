//! glTF export on a small analytic basis: Khronos glTF-Validator (0 errors) and a re-read with
//! the gltf crate that compares every morph target with the basis.

#[path = "support/gltf_targets.rs"]
mod gltf_targets;
mod support;

use facebem::MuscleBasis;
use facebem::export::{GltfParams, write_gltf};
use glam::DVec3;

/// A bumpy 12 x 12 grid with two "muscles": a smooth upward bulge and a sideways shear.
fn grid_basis() -> MuscleBasis {
    let n = 12u32;
    let mut neutral = vec![];
    for y in 0..n {
        for x in 0..n {
            let (fx, fy) = (f64::from(x) / 11.0, f64::from(y) / 11.0);
            neutral.push(DVec3::new(fx, fy, 0.1 * (3.0 * fx).sin() * fy));
        }
    }
    let mut triangles = vec![];
    for y in 0..n - 1 {
        for x in 0..n - 1 {
            let v = y * n + x;
            triangles.push([v, v + 1, v + n + 1]);
            triangles.push([v, v + n + 1, v + n]);
        }
    }
    let bulge = neutral
        .iter()
        .map(|p| DVec3::Z * 0.05 * (-(p.x - 0.5).powi(2) * 10.0).exp())
        .collect();
    let shear = neutral.iter().map(|p| DVec3::X * 0.02 * p.y).collect();
    MuscleBasis {
        muscle_ids: vec!["zygomaticus_major_l".into(), "frontalis_r".into()],
        neutral,
        triangles,
        displacements: vec![bulge, shear],
    }
}

/// `meshes[0].extras.targetNames` of a glTF document.
fn target_names(doc: &gltf::Document) -> Vec<String> {
    let mesh = doc.meshes().next().expect("one mesh");
    mesh.extras()
        .as_ref()
        .map(|raw| {
            let v: serde_json::Value = serde_json::from_str(raw.get()).unwrap();
            v["targetNames"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| s.as_str().unwrap().to_string())
                .collect()
        })
        .unwrap_or_default()
}

fn check_file(path: &std::path::Path, basis: &MuscleBasis) {
    support::assert_valid(path);
    let (doc, buffers, _) = gltf::import(path).expect("gltf crate re-reads the export");
    let mesh = doc.meshes().next().expect("one mesh");
    let names = target_names(&doc);
    // The ARKit and VRM names the two muscles can make come first (ARKit: browDownRight,
    // browInnerUp, browOuterUpRight, mouthSmileLeft; VRM: the facebem presets happy and
    // surprised, relaxed and ih; neutral, the base mesh, is left out, sad, which in this
    // two-muscle rig is browInnerUp's frontalis_r at −0.45, and angry, which uses neither
    // muscle since the orbicularis oculi's brow part lowers its brows: all zero), then the
    // muscles' contractions that no named target already is
    // (none: in this two-muscle rig VRM surprised is frontalis_r contracted) and the presets
    // that no VRM one is (the other four); every relax is −1 × a written target and left out.
    let first_own = 4 + 4;
    assert_eq!(
        names,
        [
            "browDownRight",
            "browInnerUp",
            "browOuterUpRight",
            "mouthSmileLeft",
            "happy",
            "relaxed",
            "surprised",
            "ih",
            "preset_smile",
            "preset_laugh",
            "preset_disgust",
            "preset_fear",
        ]
    );
    let read = gltf_targets::read(path);
    assert_eq!(
        read.extras["sameAs"]["zygomaticus_major_l_contract"],
        "mouthSmileLeft"
    );
    assert_eq!(read.extras["sameAs"]["preset_happy"], "happy");
    assert_eq!(read.extras["sameAs"]["sad"], "browInnerUp");
    assert_eq!(
        read.extras["leftOutTargets"]["angry"],
        "all zero: the base mesh is this expression"
    );
    assert_eq!(read.extras["sameAs"]["frontalis_r_contract"], "surprised");
    assert_eq!(read.extras["negativeOf"]["frontalis_r_relax"], "surprised");
    assert_eq!(
        read.extras["leftOutTargets"]["neutral"],
        "all zero: the base mesh is this expression"
    );
    let prim = mesh.primitives().next().unwrap();
    let reader = prim.reader(|b| Some(&buffers[b.index()]));
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    for (p, q) in positions.iter().zip(&basis.neutral) {
        assert_eq!(*p, q.as_vec3().to_array());
    }
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    assert_eq!(indices.len(), basis.triangles.len() * 3);
    assert_eq!(read.written.len(), names.len());
    assert!(names[first_own..].iter().all(|n| n.contains('_')));
    // contract = -D, relax = +D, exactly (f32 of the f64 field), whether written or resolved
    // through the repeat it is.
    for (k, id) in basis.muscle_ids.iter().enumerate() {
        let contract = &read.positions[&format!("{id}_contract")];
        let relax = &read.positions[&format!("{id}_relax")];
        for (v, d) in basis.displacements[k].iter().enumerate() {
            assert_eq!(contract[v], (-*d).as_vec3().to_array());
            assert_eq!(relax[v], d.as_vec3().to_array());
        }
    }
    // The happy preset target equals the pose's displacement (f32 tolerance 1e-7 relative).
    let happy = facebem::expressions::presets::find("happy").unwrap();
    let posed = basis.pose(&happy.sliders_for(&basis.muscle_ids)).unwrap();
    let preset_happy = &read.positions["preset_happy"];
    for v in 0..posed.len() {
        let expect = posed[v] - basis.neutral[v];
        let got = glam::Vec3::from(preset_happy[v]).as_dvec3();
        assert!(
            (got - expect).length() < 1e-7,
            "vertex {v}: {got} vs {expect}"
        );
    }
    // Animation is off by default; the skin material has metalness 0.
    assert_eq!(doc.animations().count(), 0);
    let material = prim.material();
    assert_eq!(material.name(), Some(facebem::export::MATERIAL_NAME));
    assert_eq!(material.pbr_metallic_roughness().metallic_factor(), 0.0);
}

#[test]
fn animation_gives_one_clip_per_expression_named_after_it() {
    let basis = grid_basis();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("animated.glb");
    let params = GltfParams {
        animation: true,
        names: facebem::expressions::NameSets::ALL,
        ..GltfParams::default()
    };
    write_gltf(&path, &basis, &params).unwrap();
    support::assert_valid(&path);
    let (doc, buffers, _) = gltf::import(&path).unwrap();
    let read = gltf_targets::read(&path);
    // Every preset but neutral (the base mesh) and angry, which in this two-muscle rig is
    // browInnerUp × −1 (frontalis_r at +0.45 against −0.45): a target left out as a negative
    // has no clip of its own.
    let expressions: Vec<&str> = facebem::expressions::presets::ALL
        .iter()
        .map(|p| p.name)
        .filter(|n| !matches!(*n, "neutral" | "angry"))
        .collect();
    let clips: Vec<String> = doc
        .animations()
        .map(|a| a.name().unwrap_or_default().to_string())
        .collect();
    assert_eq!(clips, expressions);
    let names = target_names(&doc);
    let targets = names.len();
    for (k, anim) in doc.animations().enumerate() {
        // The preset's target, or the VRM one it repeats (preset_happy is happy).
        let own = format!("preset_{}", expressions[k]);
        let target = read.extras["sameAs"][&own].as_str().unwrap_or(&own);
        let t = names.iter().position(|n| n == target).unwrap();
        let channel = anim.channels().next().unwrap();
        let reader = channel.reader(|b| Some(&buffers[b.index()]));
        let times: Vec<f32> = reader.read_inputs().unwrap().collect();
        assert_eq!(times, [0.0, 1.0, 2.0]);
        let weights: Vec<f32> = match reader.read_outputs().unwrap() {
            gltf::animation::util::ReadOutputs::MorphTargetWeights(w) => w.into_f32().collect(),
            _ => panic!("weights expected"),
        };
        // Neutral, then only this expression's target at 1, then neutral.
        assert_eq!(weights.len(), 3 * targets);
        for (i, w) in weights.iter().enumerate() {
            let want = if i == targets + t { 1.0 } else { 0.0 };
            assert_eq!(*w, want, "clip {k} weight {i}");
        }
    }
}

#[test]
fn glb_and_gltf_validate_and_reread_exactly() {
    let basis = grid_basis();
    let dir = tempfile::tempdir().unwrap();
    for name in ["grid.glb", "grid.gltf"] {
        let path = dir.path().join(name);
        let params = GltfParams {
            names: facebem::expressions::NameSets::ALL,
            ..GltfParams::default()
        };
        write_gltf(&path, &basis, &params).unwrap();
        check_file(&path, &basis);
    }
}
