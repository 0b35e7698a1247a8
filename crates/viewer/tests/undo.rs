//! Undo and redo of the pose (issue 35) in the real viewer app on wgpu: sliders moved through
//! the accessibility tree, a preset button, then Ctrl+Z / Ctrl+Shift+Z / Ctrl+Y as a user
//! presses them; every step restores the earlier slider values exactly, and the uploaded
//! vertices follow.

mod common;

use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::kittest::Queryable;

/// Presses `key` with `modifiers` and runs the frames that follow.
fn press(
    harness: &mut egui_kittest::Harness<'_, viewer::ViewerApp>,
    modifiers: Modifiers,
    key: Key,
) {
    harness.key_press_modifiers(modifiers, key);
    harness.run();
}

#[test]
fn undo_and_redo_restore_each_earlier_pose_exactly() {
    common::test_env();
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    let neutral = harness.state().sliders().to_vec();
    let mut states = vec![neutral.clone()];
    for (label, value) in [
        ("Zygomaticus major L", -0.6),
        ("Frontalis R", 0.25),
        ("Zygomaticus major L", -0.2),
    ] {
        harness
            .get_by_role_and_label(Role::Slider, label)
            .set_value_accesskit(value);
        harness.run();
        states.push(harness.state().sliders().to_vec());
    }
    assert_eq!(harness.state().history_depth(), (3, 0));
    assert_ne!(states[2], states[3]);

    // Undo after three edits: the state before the third, exactly; then the others.
    for back in [2, 1, 0] {
        press(&mut harness, Modifiers::COMMAND, Key::Z);
        assert_eq!(
            harness.state().sliders(),
            &states[back][..],
            "undo to {back}"
        );
    }
    // Nothing more to undo.
    press(&mut harness, Modifiers::COMMAND, Key::Z);
    assert_eq!(harness.state().sliders(), &neutral[..]);
    // Redo twice (both shortcuts), and the vertices follow the sliders.
    press(&mut harness, Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    assert_eq!(harness.state().sliders(), &states[1][..]);
    press(&mut harness, Modifiers::COMMAND, Key::Y);
    assert_eq!(harness.state().sliders(), &states[2][..]);
    let expected = basis.pose(&states[2]).unwrap();
    for (u, e) in harness.state().uploaded_vertices().iter().zip(&expected) {
        assert_eq!(u.position, e.as_vec3().to_array());
    }
    assert_eq!(harness.state().history_depth(), (2, 1));

    // A new edit drops the redo steps; a preset is one step and undoes to the sliders before.
    harness.get_by_role_and_label(Role::Button, "Happy").click();
    harness.run();
    assert_eq!(harness.state().active_preset(), Some("happy"));
    assert_eq!(harness.state().history_depth(), (3, 0));
    press(&mut harness, Modifiers::COMMAND, Key::Z);
    assert_eq!(harness.state().sliders(), &states[2][..]);
    assert_eq!(harness.state().active_preset(), None);
    press(&mut harness, Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    assert_eq!(harness.state().active_preset(), Some("happy"));
}
