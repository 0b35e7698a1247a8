//! A whole head's gaze and tongue (issue 32, items 5 and 7): `facebem export` of ICT-FaceKit's
//! generic head (`assets/heads/`) writes all 52 ARKit names and every VRM name; in the eight
//! `eyeLook*` targets each eyeball turns rigidly about its own centre the named way and the
//! lids follow, and no lid passes into an eyeball (nor in the blinks, squints and brow
//! targets); in `tongueOut` the tongue's tip comes forward past the lower lip while the
//! upper teeth stay and the gums stay with their teeth.
//!
//! The vertex ranges are ICT-FaceKit's own (`assets/heads/README.md`); the code finds the
//! parts without them.

use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "../../../tests/support/gltf_targets.rs"]
mod gltf_targets;
#[path = "../../../tests/support/mod.rs"]
mod support;

const SKIN: std::ops::Range<usize> = 0..14_062;
const GUMS_AND_TONGUE: std::ops::Range<usize> = 14_062..17_039;
const UPPER_TEETH: std::ops::Range<usize> = 17_039..19_247;
const LOWER_TEETH: std::ops::Range<usize> = 19_247..21_451;
const EYEBALL_LEFT: std::ops::Range<usize> = 21_451..23_021;
const EYEBALL_RIGHT: std::ops::Range<usize> = 23_021..24_591;
const LASHES: std::ops::Range<usize> = 25_351..26_719;

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn len(a: V3) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

#[test]
fn a_head_looks_and_sticks_its_tongue_out() {
    let out = tempfile::tempdir().unwrap();
    let glb = out.path().join("head.glb");
    let head: PathBuf = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/heads/ict_generic_head.obj"
    ))
    .to_path_buf();
    let run = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(["export", head.to_str().unwrap(), "--gltf"])
        .arg(&glb)
        .env("XDG_CACHE_HOME", out.path())
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    support::assert_valid(&glb);
    let targets = gltf_targets::read(&glb);
    // 52 of 52 ARKit names; every VRM name but `neutral` (all zero: the base mesh).
    for name in facebem::expressions::arkit::NAMES {
        assert!(targets.positions.contains_key(name), "ARKit {name}");
    }
    for name in facebem::expressions::vrm::NAMES {
        assert_eq!(
            targets.positions.contains_key(name),
            name != "neutral",
            "VRM {name}"
        );
    }
    // three.js: every primitive (a three.js mesh each, one per material) resolves every name.
    if let support::Validation::Report(r) = support::load_with_threejs(&glb) {
        let meshes = r["meshes"].as_array().unwrap();
        assert!(meshes.len() >= 10, "{} three.js meshes", meshes.len());
        for m in meshes {
            let names: Vec<&str> = m["morphTargets"]
                .as_array()
                .unwrap()
                .iter()
                .filter_map(|n| n.as_str())
                .collect();
            for name in facebem::expressions::arkit::NAMES {
                assert!(names.contains(&name), "three.js mesh {}: {name}", m["name"]);
            }
        }
    }
    // Positions in mm (the OBJ is in cm), deltas in mm (the glTF is in metres).
    let v: Vec<V3> = support::obj_v_lines(&head)
        .into_iter()
        .map(|p| p.map(|c| 10.0 * c))
        .collect();
    let field = |name: &str| -> Vec<V3> {
        targets.positions[name]
            .iter()
            .map(|d| d.map(|c| 1000.0 * f64::from(c)))
            .collect()
    };
    gaze(&head, &v, &field);
    tongue(&v, &field("tongueOut"), &field("jawOpen"));
    eyes_stay_behind_the_lids(&head, &v, &field);
    lashes_ride_the_lids(&head, &v, &field);
}

/// The lashes ride on the lids: in every target that moves the lids, no lash edge stretches
/// past 1.75 times its length or shrinks below 0.4 (the lid skin they are rooted in strains
/// 0.44–2.45 in `eyeBlinkLeft`, 1st to 99th percentile of its edges within 1.3 eyeball radii,
/// so a card along the margin cannot stay rigid; each lash vertex rides on the skin at its
/// root, turned with the lid about the eye's centre). Regression (issue 32): each lash vertex
/// took the motion of the skin it lay nearest, and the lash edges stretched and shrank to
/// 0.37–3.22 of their length in `eyeBlinkLeft` (the strip folded into flaps at the closed
/// eye's corners), 0.61–2.34 in `eyeLookDownLeft`, 0.54–1.77 in `eyeSquintLeft`, 0.90–1.62
/// in `eyeWideLeft`.
fn lashes_ride_the_lids(head: &Path, v: &[V3], field: &dyn Fn(&str) -> Vec<V3>) {
    let mut edges: Vec<(usize, usize)> = triangles_in(head, LASHES)
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    assert!(edges.len() > 2000, "{} lash edges", edges.len());
    for name in [
        "eyeBlinkLeft",
        "eyeBlinkRight",
        "eyeSquintLeft",
        "eyeWideLeft",
        "eyeLookUpLeft",
        "eyeLookDownLeft",
        "blink",
    ] {
        let d = field(name);
        let at = |i: usize| [v[i][0] + d[i][0], v[i][1] + d[i][1], v[i][2] + d[i][2]];
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for &(a, b) in &edges {
            let before = len(sub(v[a], v[b]));
            if before > 1e-6 {
                let ratio = len(sub(at(a), at(b))) / before;
                lo = lo.min(ratio);
                hi = hi.max(ratio);
            }
        }
        eprintln!("{name}: lash edges {lo:.3}–{hi:.3} of their length");
        assert!(
            lo >= 0.4 && hi <= 1.75,
            "{name}: lash edges {lo:.3}–{hi:.3} of their length"
        );
    }
}

/// No lid passes into an eyeball: in every target that moves the eyes or the lids (ARKit's
/// eye, cheek-squint, brow and smile targets, VRM's gaze, blink and emotions), at full weight,
/// no skin vertex near an eye comes more than 0.1 mm inside the eyeball, or deeper than it
/// lies in the neutral (ICT-FaceKit's inner lids are modelled a little through the sclera).
/// The eyeball's surface is measured the way each skin vertex
/// looks from the eye's centre (the radius of the eyeball vertex nearest that direction, the
/// cornea's bulge included), as the target leaves the eyeball.
fn eyes_stay_behind_the_lids(head: &Path, v: &[V3], field: &dyn Fn(&str) -> Vec<V3>) {
    let scene = face_prep::parts::Scene::read(head, &Default::default()).unwrap();
    let parts = face_prep::parts::find_parts(&scene).unwrap();
    let [left, right] = parts.eyeballs.unwrap();
    let unit = |a: V3| a.map(|x| x / len(a));
    let dot = |a: V3, b: V3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // Per eye: its centre, and the skin within 1.5 radii of it.
    let eyes: Vec<(std::ops::Range<usize>, V3, Vec<usize>)> =
        [(EYEBALL_LEFT, left), (EYEBALL_RIGHT, right)]
            .into_iter()
            .map(|(eye, sphere)| {
                let c = (sphere.centre * 10.0).to_array();
                let r = 10.0 * sphere.radius;
                let skin = SKIN.filter(|&i| len(sub(v[i], c)) < 1.5 * r).collect();
                (eye, c, skin)
            })
            .collect();
    // How far each skin vertex lies outside the eyeball (negative: inside), with positions `at`.
    let clearance = |at: &dyn Fn(usize) -> V3| -> Vec<(usize, f64)> {
        let mut out = Vec::new();
        for (eye, c, skin) in &eyes {
            let dirs: Vec<(V3, f64)> = eye
                .clone()
                .map(|i| (unit(sub(at(i), *c)), len(sub(at(i), *c))))
                .collect();
            for &s in skin {
                let u = unit(sub(at(s), *c));
                let surface = dirs
                    .iter()
                    .max_by(|a, b| dot(a.0, u).total_cmp(&dot(b.0, u)))
                    .unwrap()
                    .1;
                out.push((s, len(sub(at(s), *c)) - surface));
            }
        }
        out
    };
    let neutral = clearance(&|i| v[i]);
    let skin_triangles = skin_triangles(head);
    let neutral_through = cornea_hits(&eyes, &skin_triangles, v, &|i| v[i]);
    let covered: std::collections::HashSet<usize> = neutral_through.into_iter().collect();
    let mut names: Vec<&str> = facebem::expressions::arkit::NAMES
        .iter()
        .copied()
        .filter(|n| n.starts_with("eye") || n.starts_with("cheekSquint") || n.starts_with("brow"))
        .collect();
    names.extend([
        "mouthSmileLeft",
        "mouthSmileRight",
        "lookUp",
        "lookDown",
        "lookLeft",
        "lookRight",
        "blink",
        "happy",
        "angry",
        "sad",
        "relaxed",
        "surprised",
    ]);
    for name in names {
        let f = field(name);
        let moved = |i: usize| [0, 1, 2].map(|k| v[i][k] + f[i][k]);
        let now = clearance(&moved);
        let (mut entered, mut deepest) = (0, 0.0f64);
        for (&(_, before), &(_, after)) in neutral.iter().zip(&now) {
            let deeper = before.min(0.0) - after;
            if deeper > 0.1 {
                entered += 1;
                deepest = deepest.max(deeper);
            }
        }
        let through = cornea_through_lids(&eyes, &skin_triangles, v, &moved, &covered);
        eprintln!(
            "{name}: {entered} skin vertices into the eyeball, deepest {deepest:.2} mm; {through} eyeball vertices through a skin triangle"
        );
        assert_eq!(
            through, 0,
            "{name}: {through} eyeball vertices through the lids"
        );
        assert_eq!(
            entered, 0,
            "{name}: {entered} skin vertices into the eyeball, {deepest:.2} mm"
        );
    }
}

/// Each `eyeLook*`: the named eyeball turns rigidly about its centre by 15–35° the named way
/// (+x is the subject's left), the other stays; the lid skin never comes nearer the centre
/// (0.01 mm), rides out over the cornea's bulge where it turns under the lid (less than 3 mm:
/// the cornea rises about 2.5 mm above the sclera's sphere), and follows the gaze.
fn gaze(head: &Path, v: &[V3], field: &dyn Fn(&str) -> Vec<V3>) {
    // The eyeballs' spheres as the code finds them (in cm, here in mm).
    let scene = face_prep::parts::Scene::read(head, &Default::default()).unwrap();
    let parts = face_prep::parts::find_parts(&scene).unwrap();
    let [mut left, mut right] = parts.eyeballs.unwrap();
    for s in [&mut left, &mut right] {
        s.centre *= 10.0;
        s.radius *= 10.0;
    }
    // The fitted centres lie inside ICT-FaceKit's own eyeball ranges.
    for (s, eye) in [(left, EYEBALL_LEFT), (right, EYEBALL_RIGHT)] {
        let mean = eye
            .clone()
            .fold([0.0; 3], |m, i| [0, 1, 2].map(|k| m[k] + v[i][k]));
        let mean = mean.map(|c| c / eye.len() as f64);
        assert!(len(sub(s.centre.to_array(), mean)) < 0.3 * s.radius);
    }
    for (name, axis, sign) in [
        ("eyeLookUpLeft", 1, 1.0),
        ("eyeLookUpRight", 1, 1.0),
        ("eyeLookDownLeft", 1, -1.0),
        ("eyeLookDownRight", 1, -1.0),
        ("eyeLookOutLeft", 0, 1.0),
        ("eyeLookInRight", 0, 1.0),
        ("eyeLookInLeft", 0, -1.0),
        ("eyeLookOutRight", 0, -1.0),
    ] {
        let f = field(name);
        let is_left = name.ends_with("Left");
        let (eye, still, sphere) = if is_left {
            (EYEBALL_LEFT, EYEBALL_RIGHT, left)
        } else {
            (EYEBALL_RIGHT, EYEBALL_LEFT, right)
        };
        let c = sphere.centre.to_array();
        assert!(
            still.clone().all(|i| f[i] == [0.0; 3]),
            "{name}: the other eye"
        );
        // Rigid about the centre: every distance from it and between samples kept.
        let moved = |i: usize| [0, 1, 2].map(|k| v[i][k] + f[i][k]);
        let samples: Vec<usize> = eye.clone().step_by(23).collect();
        for &a in &samples {
            let radial = len(sub(moved(a), c)) - len(sub(v[a], c));
            assert!(
                radial.abs() < 0.05,
                "{name}: vertex {a} off the sphere by {radial} mm"
            );
            for &b in &samples {
                let kept = len(sub(moved(a), moved(b))) - len(sub(v[a], v[b]));
                assert!(kept.abs() < 0.05, "{name}: {a}–{b} stretched {kept} mm");
            }
        }
        // The front of the eye (most +z) turns the named way by 15–35°.
        let front = eye
            .clone()
            .max_by(|&a, &b| v[a][2].total_cmp(&v[b][2]))
            .unwrap();
        let (r0, r1) = (sub(v[front], c), sub(moved(front), c));
        let cos = (r0[0] * r1[0] + r0[1] * r1[1] + r0[2] * r1[2]) / (len(r0) * len(r1));
        let degrees = cos.clamp(-1.0, 1.0).acos().to_degrees();
        assert!((15.0..=35.0).contains(&degrees), "{name}: {degrees}°");
        assert!(
            sign * f[front][axis] > 3.0,
            "{name}: the front moves {:?} mm",
            f[front]
        );
        // The lid skin around the eye: distances from the centre kept (0.01 mm), and the
        // upper lid (above the centre, within 1.3 radii) follows vertical gaze.
        let lid: Vec<usize> = SKIN
            .filter(|&i| len(sub(v[i], c)) < 1.3 * sphere.radius)
            .collect();
        assert!(lid.len() > 50, "{name}: {} lid vertices", lid.len());
        let mut lifted = 0.0f64;
        for &i in &lid {
            let radial = len(sub(moved(i), c)) - len(sub(v[i], c));
            assert!(
                (-0.01..3.0).contains(&radial),
                "{name}: lid vertex {i} moves {radial} mm radially"
            );
            lifted = lifted.max(radial);
        }
        let upper: Vec<usize> = lid
            .iter()
            .copied()
            .filter(|&i| v[i][1] > c[1] + 0.3 * sphere.radius && v[i][2] > c[2])
            .collect();
        let mean_dy = upper.iter().map(|&i| f[i][1]).sum::<f64>() / upper.len() as f64;
        eprintln!(
            "{name}: front of the eye turned {degrees:.1}°, upper lid dy {mean_dy:.2} mm, lifted over the cornea by up to {lifted:.2} mm"
        );
        if axis == 1 {
            assert!(sign * mean_dy > 1.0, "{name}: upper lid dy {mean_dy} mm");
        }
    }
}

/// `tongueOut`: the tongue's front comes forward at least 10 mm and ends in front of the lower
/// lip; upper teeth still; gums within 1 mm of a tooth move with it.
fn tongue(v: &[V3], out: &[V3], open: &[V3]) {
    let moved = |i: usize| [0, 1, 2].map(|k| v[i][k] + out[i][k]);
    assert!(UPPER_TEETH.clone().all(|i| out[i] == [0.0; 3]));
    let forward = GUMS_AND_TONGUE
        .clone()
        .map(|i| out[i][2])
        .fold(f64::NEG_INFINITY, f64::max);
    let tongue_front = GUMS_AND_TONGUE
        .clone()
        .map(|i| moved(i)[2])
        .fold(f64::NEG_INFINITY, f64::max);
    // The lower lip and chin at the midline (|x| < 3 mm, 35–55 mm below the eyes' level).
    let lip_front = SKIN
        .filter(|&i| v[i][0].abs() < 3.0 && (-55.0..-35.0).contains(&v[i][1]))
        .map(|i| moved(i)[2])
        .fold(f64::NEG_INFINITY, f64::max);
    eprintln!(
        "tongueOut: tongue forward {forward:.1} mm, front at z {tongue_front:.1} mm, lower lip at {lip_front:.1} mm"
    );
    assert!(forward >= 10.0, "the tongue comes forward {forward} mm");
    assert!(
        tongue_front > lip_front,
        "tongue front {tongue_front}, lower lip {lip_front}"
    );
    // The jaw opens with the tongue: the lower teeth go as in half of jawOpen.
    for i in LOWER_TEETH.step_by(41) {
        let half = open[i].map(|c| 0.5 * c);
        assert!(len(sub(out[i], half)) < 1e-3, "lower tooth {i}");
    }
    let (upper, lower): (Vec<usize>, Vec<usize>) = (UPPER_TEETH.collect(), LOWER_TEETH.collect());
    let nearest = |row: &[usize], p: V3| {
        row.iter()
            .copied()
            .min_by(|&a, &b| len(sub(v[a], p)).total_cmp(&len(sub(v[b], p))))
            .unwrap()
    };
    let mut checked = 0;
    for g in GUMS_AND_TONGUE.step_by(7) {
        for row in [&upper, &lower] {
            let t = nearest(row, v[g]);
            if len(sub(v[t], v[g])) < 1.0 {
                checked += 1;
                // Within a tenth of the tooth's own motion (+0.5 mm): the gums' share of the
                // jaw's motion is smooth, not a step at the tooth.
                let apart = len(sub(out[g], out[t]));
                let allowed = 0.1 * len(out[t]) + 0.5;
                assert!(
                    apart < allowed,
                    "gum vertex {g} leaves tooth vertex {t} by {apart} mm"
                );
            }
        }
    }
    assert!(checked > 20, "{checked} gum vertices at a tooth");
}

/// The skin's triangles of the OBJ `head` (its `f` lines, fans split, 0-based) whose corners
/// all lie in `SKIN`.
fn skin_triangles(head: &Path) -> Vec<[usize; 3]> {
    triangles_in(head, SKIN)
}

/// The triangles of the OBJ `head` (its `f` lines, fans split, 0-based) whose corners all lie
/// in `range`.
fn triangles_in(head: &Path, range: std::ops::Range<usize>) -> Vec<[usize; 3]> {
    let text = std::fs::read_to_string(head).unwrap();
    let mut out = Vec::new();
    for l in text.lines().filter_map(|l| l.strip_prefix("f ")) {
        let c: Vec<usize> = l
            .split_whitespace()
            .map(|t| t.split('/').next().unwrap().parse::<usize>().unwrap() - 1)
            .collect();
        for k in 1..c.len() - 1 {
            let t = [c[0], c[k], c[k + 1]];
            if t.iter().all(|i| range.contains(i)) {
                out.push(t);
            }
        }
    }
    out
}

/// Whether the segment from `a` to `b` crosses the triangle `t` (Möller–Trumbore).
fn segment_crosses(a: V3, b: V3, t: [V3; 3]) -> bool {
    let cross = |u: V3, w: V3| {
        [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ]
    };
    let dot = |u: V3, w: V3| u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
    let (e1, e2, d) = (sub(t[1], t[0]), sub(t[2], t[0]), sub(b, a));
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-12 {
        return false;
    }
    let s = sub(a, t[0]);
    let (u, q) = (dot(s, p) / det, cross(s, e1));
    let (w, along) = (dot(d, q) / det, dot(e2, q) / det);
    (0.0..=1.0).contains(&u) && w >= 0.0 && u + w <= 1.0 && (0.0..=1.0).contains(&along)
}

type Eyes = [(std::ops::Range<usize>, V3, Vec<usize>)];

/// The eyeball vertices of the front of each eye (more than half a radius forward of its
/// centre in the neutral `v`) that lie outside the skin, positions by `at`: the segment from
/// the eye's centre to the vertex crosses a skin triangle within two radii of the centre.
fn cornea_hits(eyes: &Eyes, skin: &[[usize; 3]], v: &[V3], at: &dyn Fn(usize) -> V3) -> Vec<usize> {
    let mut out = Vec::new();
    for (eye, c, _) in eyes {
        let reach = 2.0 * eye.clone().map(|i| len(sub(v[i], *c))).fold(0.0, f64::max);
        let triangles: Vec<[V3; 3]> = skin
            .iter()
            .map(|t| t.map(at))
            .filter(|t| t.iter().all(|p| len(sub(*p, *c)) < reach))
            .collect();
        out.extend(eye.clone().filter(|&i| {
            let front = sub(v[i], *c)[2] > 0.25 * reach;
            front && triangles.iter().any(|t| segment_crosses(*c, at(i), *t))
        }));
    }
    out
}

/// How many front eyeball vertices come out through the skin that did not lie outside it in
/// the neutral (`covered`).
fn cornea_through_lids(
    eyes: &Eyes,
    skin: &[[usize; 3]],
    v: &[V3],
    at: &dyn Fn(usize) -> V3,
    covered: &std::collections::HashSet<usize>,
) -> usize {
    cornea_hits(eyes, skin, v, at)
        .into_iter()
        .filter(|i| !covered.contains(i))
        .count()
}
