//! egui_kittest tests of the real viewer app on wgpu with the default face's real rig (computed
//! by the pipeline into a fresh cache folder): the first run computes and caches it, the rig job
//! runs in the background while the face is shown, stale cache files and crossing shells.

mod common;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use facebem::FaceModel;
use viewer::ViewerApp;

#[test]
fn first_run_computes_and_caches_the_default_rig_and_the_second_run_loads_it() {
    let cache = tempfile::tempdir().unwrap();
    let options = viewer::ViewerOptions {
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let start = |options: viewer::ViewerOptions| {
        egui_kittest::Harness::builder()
            .with_size([1100.0, 1200.0])
            .wgpu()
            .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()))
    };
    let mut first = start(options.clone());
    // The neutral face appears while the rig is still being computed, with a progress bar:
    // the UI thread is not blocked by the precompute.
    wait_for_the_face(&mut first);
    assert!(
        first.state().is_rigging(),
        "the rig is computed in the background"
    );
    assert_eq!(first.state().basis().unwrap().muscle_count(), 0);
    assert_eq!(first.state().uploaded_vertices().len(), 468);
    first.step();
    first.get_by_role(Role::ProgressIndicator);
    first.get_by_label("Cancel");
    common::wait_idle(&mut first);
    let msg = first.state().message().cloned().unwrap();
    assert!(!msg.is_error, "{}", msg.text);
    assert!(msg.text.contains("computed"), "{}", msg.text);
    let model = first.state().model().expect("the rig is computed").clone();
    assert_eq!(model.basis.triangles.len(), 852);
    assert_eq!(model.basis.muscle_count(), face_prep::MuscleKind::ALL.len());
    assert_eq!(first.state().basis(), Some(&model.basis));
    let cached: Vec<_> = std::fs::read_dir(cache.path()).unwrap().collect();
    assert_eq!(cached.len(), 1, "one cache file");
    // Every slider is there.
    for kind in face_prep::MuscleKind::ALL {
        first.get_by_role_and_label(Role::Slider, kind.display_name());
    }
    the_muscle_overlay_follows_the_pose(&mut first, &model);
    first.get_by_label("Reset muscles").click();
    first.run();

    let mut second = start(options);
    common::wait_idle(&mut second);
    let msg = second.state().message().cloned().unwrap();
    assert!(msg.text.contains("loaded from the cache"), "{}", msg.text);
    assert_eq!(second.state().basis(), Some(&model.basis));

    // A saved rig opens directly, without recomputing.
    let rig_file = cached[0].as_ref().unwrap().path();
    common::open_via_path_field(&mut second, &rig_file);
    common::wait_idle(&mut second);
    let msg = second.state().message().cloned().unwrap();
    assert!(msg.text.contains("Opened the saved rig"), "{}", msg.text);
    assert_eq!(second.state().model().unwrap().basis, model.basis);

    a_glb_export_opens_as_a_face_whose_rig_job_cancels(&mut second, &model);
}

/// Steps a starting app until it shows its first face (bounded: a hang fails the test).
fn wait_for_the_face(first: &mut Harness<'_, ViewerApp>) {
    let t0 = std::time::Instant::now();
    while first.state().basis().is_none() {
        assert!(
            t0.elapsed() < std::time::Duration::from_secs(60),
            "the face never appeared"
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
        first.step();
    }
}

/// The muscle overlay follows the pose: with one slider moved, the chain is drawn through the
/// posed element centroids.
fn the_muscle_overlay_follows_the_pose(first: &mut Harness<'_, ViewerApp>, model: &FaceModel) {
    // The muscle overlay is off by default.
    first.get_by_label("Muscles").click();
    first.run();
    let before = first.state().overlay_line_vertices().to_vec();
    assert!(!before.is_empty());
    first
        .get_by_role_and_label(Role::Slider, "Zygomaticus major L")
        .set_value_accesskit(-1.0);
    first.run();
    let after = first.state().overlay_line_vertices().to_vec();
    assert_eq!(before.len(), after.len());
    // (The BEM response is global: every vertex moves a little, the driven chain the most.)
    let largest = before
        .iter()
        .zip(&after)
        .map(|(a, b)| glam::Vec3::from(a.position).distance(glam::Vec3::from(b.position)))
        .fold(0.0f32, f32::max);
    assert!(
        f64::from(largest) > 0.01 * model.rig.face_size,
        "overlay moved by {largest} only"
    );
    // Posed shell vertices (user frame): each moves by its own response. The default face is
    // simulated without its rolled-in mouth corners, so the shell's front vertices are a
    // subset of the face's, and the response, not the face's pose, is what the overlay uses.
    let input_from_canonical = model.rig.input_from_canonical();
    let sliders = first.state().sliders().to_vec();
    let posed: Vec<glam::DVec3> = (0..model.rig.shell.vertices.len())
        .map(|v| {
            let u: glam::DVec3 = sliders
                .iter()
                .zip(&model.shell_vertex_response)
                .map(|(s, r)| *s * r[v])
                .sum();
            input_from_canonical.transform_point3(model.rig.shell.vertices[v])
                + input_from_canonical.matrix3 * u
        })
        .collect();
    let zyg = model
        .rig
        .muscles
        .iter()
        .find(|m| m.kind == Some(face_prep::MuscleKind::ZygomaticusMajorL))
        .unwrap();
    let e = zyg.front_chain[0] as usize;
    let centroid = model.rig.shell.triangles[e]
        .iter()
        .map(|&v| posed[v as usize])
        .sum::<glam::DVec3>()
        / 3.0;
    let want = centroid.as_vec3().to_array();
    assert!(
        after.iter().any(|l| l
            .position
            .iter()
            .zip(want)
            .all(|(a, b)| (a - b).abs() < 1e-4)),
        "no overlay vertex at the posed centroid {want:?} of the chain's first element"
    );
}

/// A GLB face opens too (here the viewer's own glTF export of `model`); its rig job can be
/// cancelled, and the preview holds the OBJ's vertices in order, in metres.
fn a_glb_export_opens_as_a_face_whose_rig_job_cancels(
    second: &mut Harness<'_, ViewerApp>,
    model: &FaceModel,
) {
    let out = tempfile::tempdir().unwrap();
    second.state_mut().set_export_dir(out.path());
    second.get_by_label("Export glTF").click();
    second.step();
    common::wait_idle(second);
    let msg = second.state().message().cloned().unwrap();
    assert!(msg.text.contains("Exported"), "{}", msg.text);
    let glb = std::fs::read_dir(out.path())
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    common::open_via_path_field(second, &glb);
    while second.state().basis().is_some_and(|b| b.muscle_count() > 0) {
        std::thread::sleep(std::time::Duration::from_millis(5));
        second.step();
    }
    second.step();
    second.get_by_label("Cancel").click();
    second.step();
    common::wait_idle(second);
    let basis = second.state().basis().unwrap();
    assert_eq!(basis.muscle_count(), 0, "rig cancelled: the preview stays");
    // The GLB holds the OBJ's `v` lines in order, in metres: its vertex i is the model's
    // vertex input_to_vertex[i].
    let itv: Vec<u32> = model
        .mesh
        .input_to_vertex
        .iter()
        .map(|w| w.unwrap())
        .collect();
    let mapped: Vec<[u32; 3]> = basis
        .triangles
        .iter()
        .map(|t| t.map(|i| itv[i as usize]))
        .collect();
    assert_eq!(mapped, model.basis.triangles);
    let metres = model.metres_per_unit();
    for (i, a) in basis.neutral.iter().enumerate() {
        let b = model.basis.neutral[itv[i] as usize] * metres;
        assert!((*a - b).length() < 1e-5 * metres, "{a} vs {b}");
    }
}

/// Regression: a cache file left by an older build (same name, payload no longer decodes) made
/// `cache::load` fail; the viewer must recompute and overwrite it, not report an error.
#[test]
fn a_stale_or_corrupt_cache_file_is_recomputed_and_replaced() {
    let cache = tempfile::tempdir().unwrap();
    let mesh = facebem::input::default_face().unwrap();
    let path =
        viewer::source::cache_file_for(cache.path(), &mesh, &facebem::PipelineParams::default());
    std::fs::write(&path, b"not a facebem rig at all").unwrap();
    let options = viewer::ViewerOptions {
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let mut harness = egui_kittest::Harness::builder()
        .with_size([900.0, 600.0])
        .wgpu()
        .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()));
    common::wait_idle(&mut harness);
    let msg = harness.state().message().cloned().unwrap();
    assert!(
        !msg.is_error && msg.text.contains("computed"),
        "{}",
        msg.text
    );
    let model = harness.state().model().expect("rig computed").clone();
    let reloaded = facebem::cache::load(&path).expect("the cache file was replaced");
    assert_eq!(reloaded.basis, model.basis);
}

/// A face whose shell crosses itself is rigged, but the user is told, in red, that responses
/// there are unreliable — the count is the pipeline's own. The crossing shell: the ICT
/// 2500-triangle face with its rolled-in lips kept and simplified by position only with every
/// border vertex locked, which folds the lips into a pleat at the right mouth corner (the
/// defaults peel the lips, weight normals, resample the borders, and are clean).
#[test]
fn a_rig_with_intersecting_shell_elements_is_flagged() {
    let cache = tempfile::tempdir().unwrap();
    let options = viewer::ViewerOptions {
        start_empty: true,
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let mut harness = egui_kittest::Harness::builder()
        .with_size([1100.0, 1500.0])
        .wgpu()
        .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()));
    harness.run();
    let face = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/ict_narrow_face_dec2500_4loop.obj");
    common::open_via_path_field(&mut harness, &face);
    common::wait_idle(&mut harness);
    let clean = harness.state().model().expect("rig computed").clone();
    assert_eq!(clean.report.shell_self_intersections, 0);
    assert!(!harness.state().message().is_some_and(|m| m.is_error));
    // The status line says how the large face was simplified (the decimated ICT face is not
    // mirror-symmetric).
    let status = harness.state().message().cloned().unwrap().text;
    assert!(
        status.contains(&format!(
            "{} triangles simulated, simplified in the face's canonical frame and order",
            clean.report.simulated_triangles
        )),
        "{status}"
    );
    let params = harness.state_mut().params_mut();
    params.peel_rolled_in = false;
    params.large_face.normal_weight = 0.0;
    params.large_face.border_spacing = 0.0;
    harness.get_by_label("Rebuild rig").click();
    // One frame, not `run()`: the job repaints while it works, so `run()` could exceed its
    // step limit (it did once, "would have settled after 6 steps"); `wait_idle` steps it out.
    harness.step();
    common::wait_idle(&mut harness);
    let model = harness.state().model().expect("rig computed").clone();
    let crossings = model.report.shell_self_intersections;
    assert!(
        crossings > 0,
        "the position-only ICT copy no longer crosses itself: update this test"
    );
    let msg = harness.state().message().cloned().unwrap();
    assert!(msg.is_error, "{}", msg.text);
    assert!(
        msg.text
            .contains(&format!("{crossings} pairs of shell elements intersect")),
        "{}",
        msg.text
    );
    // Past the trust thresholds (issue 30): the refusal the command line would give, in red.
    assert!(
        msg.text.contains("This rig is not trustworthy")
            && msg
                .text
                .contains(&format!("crosses itself ({crossings} element pairs)")),
        "{}",
        msg.text
    );
}

#[test]
fn the_face_is_drawn_at_once_exports_wait_for_the_rig_and_the_legend_names_every_muscle() {
    use egui_kittest::kittest::NodeT;
    let cache = tempfile::tempdir().unwrap();
    let options = viewer::ViewerOptions {
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let mut harness = egui_kittest::Harness::builder()
        .with_size([1100.0, 1200.0])
        .wgpu()
        .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()));
    // The first frame already holds the default face (the rig is computed in the background).
    assert_eq!(harness.state().uploaded_vertices().len(), 468);
    assert!(harness.state().is_rigging());
    harness.step();
    for label in ["Export OBJ pose", "Export glTF", "Save muscle file"] {
        assert!(
            harness.get_by_label(label).accesskit_node().is_disabled(),
            "{label} is enabled while the rig computes"
        );
    }
    // One progress bar over all stages, with the elapsed time and no estimate of the rest
    // (issue 35: the linear one stalled).
    let bar = harness.get_by_role(Role::ProgressIndicator);
    let label = bar.accesskit_node().label().unwrap_or_default();
    assert!(
        label.contains("elapsed") && !label.contains("left"),
        "{label}"
    );
    let why = harness.state().exports_ready().unwrap_err();
    assert!(why.contains("being computed"), "{why}");
    // Clicking a disabled button does nothing; calling export directly is refused.
    let out = tempfile::tempdir().unwrap();
    harness.state_mut().set_export_dir(out.path());
    harness.get_by_label("Export glTF").click();
    harness.step();
    assert_eq!(std::fs::read_dir(out.path()).unwrap().count(), 0);

    common::wait_idle(&mut harness);
    let model = harness.state().model().expect("rig computed").clone();
    for label in ["Export OBJ pose", "Export glTF", "Save muscle file"] {
        assert!(!harness.get_by_label(label).accesskit_node().is_disabled());
    }
    // With the muscle overlay on (off by default), the legend (collapsed at first) names every
    // muscle of the rig with its colour.
    harness.get_by_label("Muscles").click();
    harness.run();
    let header = format!("Muscle colours ({})", model.rig.muscles.len());
    let first = model.rig.muscles[0]
        .kind
        .expect("a standard muscle")
        .display_name();
    let first = format!("{first}: {}", viewer::overlay::muscle_color_name(0));
    assert!(harness.query_by_label(&first).is_none());
    harness.get_by_label(&header).click();
    harness.run();
    assert!(!model.rig.muscles.is_empty());
    for (i, m) in model.rig.muscles.iter().enumerate() {
        let kind = m.kind.expect("standard muscles on the default face");
        let colour = viewer::overlay::muscle_color_name(i);
        harness.get_by_label(&format!("{}: {colour}", kind.display_name()));
    }
    // Every standard muscle has its own colour name.
    let mut names: Vec<String> = (0..model.rig.muscles.len())
        .map(viewer::overlay::muscle_color_name)
        .collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), model.rig.muscles.len());

    // A muscle file that cannot be read is reported (the dialog's answer goes through here).
    let ctx = harness.ctx.clone();
    let missing = out.path().join("missing.muscles");
    harness.state_mut().load_muscle_file_from(&ctx, &missing);
    let msg = harness.state().message().cloned().unwrap();
    assert!(
        msg.is_error && msg.text.contains("missing.muscles"),
        "{}",
        msg.text
    );
    assert!(!harness.state().is_rigging());
}
