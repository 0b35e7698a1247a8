//! The expression browser (issue 35) in the real viewer app on wgpu, driven through the
//! accessibility tree: the ARKit tab searched for "smile" lists exactly mouthSmileLeft and
//! mouthSmileRight; mouthSmileLeft at 1 poses the face exactly as the library's ARKit
//! definition does (what `facebem pose --preset mouthSmileLeft` writes); two expressions add up;
//! a name the rig cannot make is greyed; undo restores the mix.

mod common;

use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::kittest::{NodeT, Queryable};
use facebem::expressions;

/// The labels of the sliders shown that are names of `names`.
fn shown(harness: &egui_kittest::Harness<'_, viewer::ViewerApp>, names: &[&str]) -> Vec<String> {
    harness
        .get_all_by_role(Role::Slider)
        .filter_map(|n| n.accesskit_node().label())
        .filter(|l| names.contains(&l.as_str()))
        .collect()
}

#[test]
fn the_browser_finds_mixes_and_poses_named_expressions() {
    common::test_env();
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    let arkit = expressions::arkit::NAMES;
    // The section opens on the ARKit tab; the list scrolls, so some names show before the search.
    assert!(shown(&harness, &arkit).is_empty());
    harness
        .get_by_label("Expressions: ARKit, VRM, presets")
        .click();
    harness.run();
    assert!(!shown(&harness, &arkit).is_empty());
    harness.get_by_label("Search").focus();
    harness.get_by_label("Search").type_text("smile");
    harness.run();
    assert_eq!(
        shown(&harness, &arkit),
        ["mouthSmileLeft", "mouthSmileRight"]
    );

    harness
        .get_by_role_and_label(Role::Slider, "mouthSmileLeft")
        .set_value_accesskit(1.0);
    harness.run();
    let ids = &basis.muscle_ids;
    let smile = expressions::find("mouthSmileLeft")
        .unwrap()
        .resolve(ids)
        .unwrap();
    assert_eq!(harness.state().sliders(), &smile.sliders[..]);
    let expected = basis.pose(&smile.sliders).unwrap();
    for (u, e) in harness.state().uploaded_vertices().iter().zip(&expected) {
        assert_eq!(u.position, e.as_vec3().to_array());
    }

    // A second expression adds its controls at its weight.
    harness
        .get_by_role_and_label(Role::Slider, "mouthSmileRight")
        .set_value_accesskit(0.5);
    harness.run();
    let right = expressions::find("mouthSmileRight")
        .unwrap()
        .resolve(ids)
        .unwrap();
    let want: Vec<f64> = smile
        .sliders
        .iter()
        .zip(&right.sliders)
        .map(|(a, b)| (a + 0.5 * b).clamp(-1.0, 1.0))
        .collect();
    assert_eq!(harness.state().sliders(), &want[..]);
    assert_eq!(
        harness.state().expression_mix(),
        &[("mouthSmileLeft", 1.0), ("mouthSmileRight", 0.5)]
    );

    // Undo takes the second expression out again (once the search field has let go of the
    // keyboard: there Ctrl+Z is the text's own undo).
    harness.key_press(Key::Escape);
    harness.run();
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    harness.run();
    assert_eq!(harness.state().sliders(), &smile.sliders[..]);
    assert_eq!(harness.state().expression_mix(), &[("mouthSmileLeft", 1.0)]);

    // A name the rig cannot make is listed, disabled.
    let entries = viewer::app::browser::browser_entries(
        viewer::app::browser::BrowserTab::Arkit,
        "eyeLook",
        ids,
    );
    assert_eq!(entries.len(), 8);
    assert!(
        entries
            .iter()
            .all(|e| e.unavailable.as_deref() == Some("not modelled: no eyeballs"))
    );
}

#[test]
fn the_muscles_tab_lists_the_muscle_sliders_matching_the_search() {
    common::test_env();
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    harness
        .get_by_label("Expressions: ARKit, VRM, presets")
        .click();
    harness.run();
    // The tab (the overlay's checkbox has the same label).
    harness
        .get_all_by_label("Muscles")
        .find(|n| n.accesskit_node().role() != Role::CheckBox)
        .unwrap()
        .click();
    harness.run();
    harness.get_by_label("Search").focus();
    harness
        .get_by_label("Search")
        .type_text("zygomaticus major");
    harness.run();
    // Each muscle slider is listed twice now: in the muscle list and in the tab.
    for name in ["Zygomaticus major L", "Zygomaticus major R"] {
        let n = harness
            .get_all_by_role(Role::Slider)
            .filter(|s| s.accesskit_node().label().as_deref() == Some(name))
            .count();
        assert_eq!(n, 2, "{name}");
    }
    let frontalis = harness
        .get_all_by_role(Role::Slider)
        .filter(|s| s.accesskit_node().label().as_deref() == Some("Frontalis L"))
        .count();
    assert_eq!(frontalis, 1);
    // Moving one in the tab moves that muscle (−1 … 1).
    let k = basis
        .muscle_ids
        .iter()
        .position(|id| id == "zygomaticus_major_r")
        .unwrap();
    harness
        .get_all_by_role(Role::Slider)
        .rfind(|s| s.accesskit_node().label().as_deref() == Some("Zygomaticus major R"))
        .unwrap()
        .set_value_accesskit(-0.7);
    harness.run();
    assert_eq!(harness.state().sliders()[k], -0.7);
}
