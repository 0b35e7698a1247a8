//! A whole head (issue 32): `facebem info` lists the parts it finds in ICT-FaceKit's generic
//! head (`assets/heads/`), and every command refuses the head with one line that says why,
//! writing nothing.

use std::path::{Path, PathBuf};
use std::process::Command;

fn head() -> PathBuf {
    Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/heads/ict_generic_head.obj"
    ))
    .to_path_buf()
}

fn facebem(args: &[&str], cache: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(args)
        .env("XDG_CACHE_HOME", cache)
        .output()
        .unwrap()
}

#[test]
fn info_lists_the_parts_of_a_head_and_every_command_refuses_it_in_one_line() {
    let out = tempfile::tempdir().unwrap();
    let head = head();
    let head = head.to_str().unwrap();
    let info = facebem(&["info", head], out.path());
    assert_eq!(info.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&info.stdout);
    for line in [
        "skin: 1 component, 14062 vertices",
        "eyeball (subject's left): 2 components, 1570 vertices",
        "eyeball (subject's right): 2 components, 1570 vertices",
        "upper teeth: 16 components",
        "lower teeth: 16 components",
        "gums and tongue: 1 component, 2977 vertices",
        "lid parts (lashes, occlusion, tear film)",
        "front face cut from the skin: ",
        "triangles, 4 openings",
    ] {
        assert!(stdout.contains(line), "{line:?} missing from:\n{stdout}");
    }
    assert!(!stdout.contains("other"), "{stdout}");
    let glb = out.path().join("head.glb");
    let rig = out.path().join("head.rig");
    for args in [
        vec!["info", head],
        vec!["rig", head, "-o", rig.to_str().unwrap()],
        vec!["export", head, "--gltf", glb.to_str().unwrap()],
    ] {
        let run = facebem(&args, out.path());
        assert_eq!(run.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains("a head or avatar of 42 parts"), "{stderr}");
    }
    assert!(!glb.exists() && !rig.exists());
    // The same in JSON: every component with its part, and every vertex in one.
    let json = facebem(&["info", "--json", head], out.path());
    let report: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    let components = report["components"].as_array().unwrap();
    assert_eq!(components.len(), 42);
    let vertices: u64 = components
        .iter()
        .map(|c| c["vertices"].as_u64().unwrap())
        .sum();
    assert_eq!(vertices, 26_719);
    let teeth = components
        .iter()
        .filter(|c| c["part"].as_str().unwrap().ends_with("teeth"))
        .count();
    assert_eq!(teeth, 32);
}
