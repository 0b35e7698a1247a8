//! `facebem pose --help` and `export --help` list every preset with its FACS action units, as
//! the README promises.

use std::process::Command;

#[test]
fn pose_and_export_help_list_presets_with_their_action_units() {
    for sub in ["pose", "export"] {
        let out = Command::new(env!("CARGO_BIN_EXE_facebem"))
            .args([sub, "--help"])
            .output()
            .expect("runs facebem");
        assert!(out.status.success());
        let text = String::from_utf8_lossy(&out.stdout);
        for p in &facebem::expressions::presets::ALL {
            let line = text
                .lines()
                .find(|l| l.split_whitespace().next() == Some(p.name))
                .unwrap_or_else(|| panic!("{sub} --help does not list {}:\n{text}", p.name));
            assert!(line.contains(p.action_units), "{line}");
        }
    }
    let out = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(["export", "--help"])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&out.stdout).contains("--animation"));
}
