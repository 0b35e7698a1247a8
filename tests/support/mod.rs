//! Helpers shared by the end-to-end tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// The bundled faces, smallest first.
pub const FACES: [&str; 4] = [
    "mediapipe_canonical_4loop.obj",
    "ict_narrow_face_dec2500_4loop.obj",
    "leeperrysmith_face_open_4loop.obj",
    "ict_narrow_face_4loop.obj",
];

/// The workspace root (these helpers are shared by the root package's tests and the CLI's).
pub fn root() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.ancestors()
        .find(|p| p.join("assets").is_dir() && p.join("Cargo.lock").is_file())
        .unwrap_or(here)
        .to_path_buf()
}

/// Every file under `dir` (recursively, sorted) whose name ends with `.{extension}`.
pub fn files_with_extension(dir: &Path, extension: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            out.extend(files_with_extension(&path, extension));
        } else if path.extension().is_some_and(|e| e == extension) {
            out.push(path);
        }
    }
    out
}

/// Path of a bundled face.
pub fn asset(name: &str) -> PathBuf {
    root().join("assets").join(name)
}

/// Outcome of running a node tool (the Khronos glTF-Validator, three.js).
pub enum Validation {
    /// node is not installed: the caller skips with a message (CI has node).
    NodeMissing,
    /// The tool's JSON report.
    Report(serde_json::Value),
}

/// Serialises the one-time `npm ci` between test threads of one binary.
static VALIDATOR_INSTALL: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Runs the Khronos glTF-Validator (npm `gltf-validator`, pinned by
/// `tests/gltf-validator/package-lock.json`) on `file`. `.ci/run` installs it with `npm ci`;
/// elsewhere the first test that needs it does (or set `$GLTF_VALIDATOR_DIR` to a directory
/// holding `node_modules/gltf-validator`). With `FACEBEM_REQUIRE_GLTF_VALIDATOR=1` (CI) a
/// missing node is a failure instead of a skip.
pub fn validate_gltf(file: &Path) -> Validation {
    run_node_script("validate_gltf.cjs", file, &[])
}

/// Loads `file` with three.js's GLTFLoader in node (npm `three`, pinned by the same
/// `tests/gltf-validator/package-lock.json`) and returns what a three.js app gets (see
/// `tests/support/three_load.mjs`).
pub fn load_with_threejs(file: &Path) -> Validation {
    run_node_script("three_load.mjs", file, &[])
}

/// [`load_with_threejs`], after running the JavaScript `snippet` file on the loaded `gltf`.
pub fn load_with_threejs_running(file: &Path, snippet: &Path) -> Validation {
    run_node_script("three_load.mjs", file, &[snippet])
}

/// Loads the VRM `file` with three.js and three-vrm (npm `@pixiv/three-vrm`, pinned by the same
/// lock file) and reports how far each of `expressions` moves it (`tests/support/three_vrm.mjs`).
pub fn load_with_three_vrm(file: &Path, expressions: &[&str]) -> Validation {
    let names: Vec<&Path> = expressions.iter().map(Path::new).collect();
    run_node_script("three_vrm.mjs", file, &names)
}

/// Runs `tests/support/<script> <npm dir> <file> <extra>…` with node and parses its JSON
/// output.
fn run_node_script(script: &str, file: &Path, extra: &[&Path]) -> Validation {
    if Command::new("node").arg("--version").output().is_err() {
        assert!(
            std::env::var_os("FACEBEM_REQUIRE_GLTF_VALIDATOR").is_none(),
            "FACEBEM_REQUIRE_GLTF_VALIDATOR is set but node is not installed"
        );
        return Validation::NodeMissing;
    }
    let dir = std::env::var_os("GLTF_VALIDATOR_DIR")
        .map_or_else(|| root().join("tests/gltf-validator"), PathBuf::from);
    {
        let _guard = VALIDATOR_INSTALL
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let installed = ["gltf-validator", "three", "@pixiv/three-vrm"]
            .iter()
            .all(|p| {
                dir.join("node_modules")
                    .join(p)
                    .join("package.json")
                    .exists()
            });
        if !installed {
            let status = Command::new("npm")
                .args(["ci", "--no-audit", "--no-fund"])
                .current_dir(&dir)
                .status()
                .expect("node is installed but npm is not");
            assert!(status.success(), "npm ci in {} failed", dir.display());
        }
    }
    let script = root().join("tests/support").join(script);
    let out = Command::new("node")
        .arg(&script)
        .arg(&dir)
        .arg(file)
        .args(extra)
        .output()
        .expect("cannot run node");
    assert!(
        out.status.success(),
        "{} failed: {}",
        script.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    Validation::Report(serde_json::from_slice(&out.stdout).expect("node script output is JSON"))
}

/// Asserts that a validator report has no errors and no warnings, printing its messages
/// otherwise (infos and hints are allowed).
pub fn assert_valid(file: &Path) {
    match validate_gltf(file) {
        Validation::NodeMissing => {
            eprintln!(
                "SKIPPED glTF-Validator check of {}: node is not installed",
                file.display()
            );
        }
        Validation::Report(report) => {
            let errors = report["issues"]["numErrors"].as_u64();
            assert_eq!(
                errors,
                Some(0),
                "{}: glTF-Validator errors: {}",
                file.display(),
                report["issues"]["messages"]
            );
            assert_eq!(
                report["issues"]["numWarnings"].as_u64(),
                Some(0),
                "{}: glTF-Validator warnings: {}",
                file.display(),
                report["issues"]["messages"]
            );
        }
    }
}

/// A face written differently: rotated about an odd axis, scaled ×10 and moved
/// (`input_from_original`), its vertices renumbered by a fixed permutation (new index `i` holds
/// original vertex `(i · step) mod n`, `new_of_old` maps back), its triangles in reverse order
/// and each started at its second corner (same winding).
pub struct Rewritten {
    pub mesh: face_prep::FaceMesh,
    pub new_of_old: Vec<u32>,
    pub input_from_original: glam::DAffine3,
}

pub fn rewritten(mesh: &face_prep::FaceMesh) -> Rewritten {
    use glam::{DAffine3, DQuat, DVec3};
    fn gcd(a: usize, b: usize) -> usize {
        if b == 0 { a } else { gcd(b, a % b) }
    }
    let n = mesh.vertices.len();
    let step = (1..n)
        .map(|s| s * 7 + 3)
        .find(|&s| gcd(s, n) == 1)
        .unwrap_or(1);
    let mut new_of_old = vec![0u32; n];
    for new in 0..n {
        new_of_old[(new * step) % n] = new as u32;
    }
    let input_from_original = DAffine3::from_scale_rotation_translation(
        DVec3::splat(10.0),
        DQuat::from_axis_angle(DVec3::new(0.3, -0.8, 0.5).normalize(), 2.1),
        DVec3::new(40.0, -7.0, 3.0),
    );
    let vertices: Vec<DVec3> = (0..n)
        .map(|new| input_from_original.transform_point3(mesh.vertices[(new * step) % n]))
        .collect();
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .rev()
        .map(|t| {
            let t = t.map(|v| new_of_old[v as usize]);
            [t[1], t[2], t[0]]
        })
        .collect();
    Rewritten {
        mesh: face_prep::FaceMesh::from_triangles(&vertices, &triangles).unwrap(),
        new_of_old,
        input_from_original,
    }
}

/// Canonical y above which a face's outer contour is off the jaw segment: the jaw's hinge plus
/// the rig's longest contour edge (a rim element whose centroid is in the segment reaches up to
/// one edge above it; a large face's contour is interpolated from its simplified copy's).
pub fn above_the_jaw_y(m: &facebem::FaceModel) -> f64 {
    let contour = &m.rig.loops.face;
    let longest_edge = (0..contour.len())
        .map(|i| {
            let a = m.rig.shell.vertices[contour[i] as usize];
            let b = m.rig.shell.vertices[contour[(i + 1) % contour.len()] as usize];
            a.distance(b)
        })
        .fold(0.0, f64::max);
    m.rig.jaw().hinge.y + longest_edge
}

/// Displacement field (input frame, mesh units) of a named expression — a facebem preset, an
/// ARKit name or a VRM preset — on a model.
pub fn named_field(m: &facebem::FaceModel, name: &str) -> Vec<glam::DVec3> {
    let (sliders, _) = facebem::expressions::sliders_for_name(name, m.muscle_ids()).unwrap();
    let posed = m.pose(&sliders).unwrap();
    posed
        .iter()
        .zip(&m.mesh.vertices)
        .map(|(p, v)| *p - *v)
        .collect()
}

/// `mesh` with interior edges flipped at random (seeded): each triangle at most once, only
/// where both new triangles face the old ones' way — a quad mesh split along other
/// diagonals. The vertices stay where they are, so the shape changes only by how far the
/// flipped quads are from planar.
pub fn retriangulated(mesh: &face_prep::FaceMesh, seed: u64) -> face_prep::FaceMesh {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 33) as u32
    };
    let mut triangles = mesh.triangles.clone();
    let mut edges: std::collections::BTreeMap<(u32, u32), Vec<usize>> = Default::default();
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edges.entry((a.min(b), a.max(b))).or_default().push(t);
        }
    }
    let mut interior: Vec<(u32, u32)> = edges
        .iter()
        .filter(|(_, ts)| ts.len() == 2)
        .map(|(&e, _)| e)
        .collect();
    for i in (1..interior.len()).rev() {
        interior.swap(i, next() as usize % (i + 1));
    }
    let normal = |v: &[glam::DVec3], t: [u32; 3]| {
        (v[t[1] as usize] - v[t[0] as usize]).cross(v[t[2] as usize] - v[t[0] as usize])
    };
    let mut used = vec![false; triangles.len()];
    for (a, b) in interior {
        let [t1, t2] = [edges[&(a, b)][0], edges[&(a, b)][1]];
        if used[t1] || used[t2] || next() % 2 == 0 {
            continue;
        }
        let (p, q) = (triangles[t1], triangles[t2]);
        let c = p.into_iter().find(|&v| v != a && v != b).unwrap();
        let d = q.into_iter().find(|&v| v != a && v != b).unwrap();
        if edges.contains_key(&(c.min(d), c.max(d))) {
            continue;
        }
        let i = p.iter().position(|&v| v == c).unwrap();
        let (x, y) = (p[(i + 1) % 3], p[(i + 2) % 3]);
        let (n1, n2) = ([c, x, d], [c, d, y]);
        let old = [normal(&mesh.vertices, p), normal(&mesh.vertices, q)];
        let new = [normal(&mesh.vertices, n1), normal(&mesh.vertices, n2)];
        if old.iter().any(|o| new.iter().any(|n| o.dot(*n) <= 0.0)) {
            continue;
        }
        triangles[t1] = n1;
        triangles[t2] = n2;
        used[t1] = true;
        used[t2] = true;
        edges.insert((c.min(d), c.max(d)), vec![t1, t2]);
    }
    face_prep::FaceMesh {
        vertices: mesh.vertices.clone(),
        triangles,
        input_to_vertex: mesh.input_to_vertex.clone(),
        lip_line: None,
        lid_lines: Vec::new(),
        mouth_bag_vertices: 0,
    }
}

/// The first ```` ```lang ```` block of README.md, its lines unindented (the README indents
/// blocks inside its numbered steps): what a user copies.
pub fn readme_block(lang: &str) -> String {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let fence = format!("```{lang}\n");
    let start = readme
        .find(&fence)
        .unwrap_or_else(|| panic!("the README has no {lang} block"))
        + fence.len();
    let end = start + readme[start..].find("```").unwrap();
    readme[start..end]
        .lines()
        .map(|l| l.trim_start())
        .collect::<Vec<_>>()
        .join("\n")
}

/// The positions of the `v` lines of the OBJ file `path`, in file order.
pub fn obj_v_lines(path: &Path) -> Vec<[f64; 3]> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let c: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            [c[0], c[1], c[2]]
        })
        .collect()
}

/// The JSON of a `.glb` (its JSON chunk) or `.gltf` file.
pub fn glb_json(path: &Path) -> serde_json::Value {
    let bytes = std::fs::read(path).unwrap();
    if bytes.starts_with(b"glTF") {
        let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        serde_json::from_slice(&bytes[20..20 + len]).unwrap()
    } else {
        serde_json::from_slice(&bytes).unwrap()
    }
}

/// `meshes[0].extras.targetNames` of a glTF export.
pub fn glb_target_names(path: &Path) -> Vec<String> {
    let json = glb_json(path);
    json["meshes"][0]["extras"]["targetNames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect()
}
