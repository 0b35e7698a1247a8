//! Unit tests of the glTF export's checks and limits.
use super::*;

#[test]
fn bad_inputs_are_typed_errors() {
    let mut basis = MuscleBasis {
        muscle_ids: vec!["m".into()],
        neutral: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        triangles: vec![[0, 1, 3]],
        displacements: vec![vec![DVec3::ZERO; 3]],
    };
    let p = GltfParams {
        names: NameSets::ALL,
        ..GltfParams::default()
    };
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

/// Regression (issue 36, part 7): a 1.18 M-triangle face exported a 2.0 GB GLB using
/// 6.6 GB of memory. Above [`MAX_EXPORT_BYTES`] the export is refused from the counts,
/// before any target is built; here every control's target (every set, each muscle's field
/// its own) over a million glTF vertices (all but three of them positions no face uses, so
/// the test itself stays small).
#[test]
fn an_export_over_the_size_limit_is_refused_before_building_it() {
    let ids: Vec<String> = face_prep::MuscleKind::ALL
        .iter()
        .map(|k| k.id().to_string())
        .collect();
    let basis = MuscleBasis {
        displacements: (0..ids.len())
            .map(|k| vec![DVec3::X * (k + 1) as f64, DVec3::ZERO, DVec3::ZERO])
            .collect(),
        muscle_ids: ids,
        neutral: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        triangles: vec![[0, 1, 2]],
    };
    let mut layout = ExportLayout::welded(&basis.neutral, &basis.triangles);
    let unused = 1_000_000;
    layout.welded.extend(std::iter::repeat_n(None, unused));
    layout
        .positions
        .extend(std::iter::repeat_n(DVec3::Z, unused));
    layout.input_index.extend(3..3 + unused as u32);
    layout.input_count += unused;
    let params = GltfParams {
        names: NameSets::ALL,
        ..GltfParams::default()
    };
    match export_gltf_layout(&basis, &layout, &params) {
        Err(GltfExportError::TooLarge {
            bytes,
            targets,
            vertices,
        }) => {
            assert_eq!(vertices, unused + 3);
            assert!(targets > 60, "{targets}");
            assert!(bytes > MAX_EXPORT_BYTES, "{bytes}");
        }
        other => panic!("{:?}", other.map(|b| b.len())),
    }
    // The same basis on its three vertices exports.
    assert!(export_gltf(&basis, &GltfParams::default()).is_ok());
}
