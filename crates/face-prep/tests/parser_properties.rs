//! Property tests of the input parsers (seeded random cases, reproducible): they never panic on
//! mutated input, what they accept satisfies the mesh invariants, and writers round-trip.

use face_prep::{FaceMesh, InputLimits, Muscle, error::sig6, muscle_file};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const CASES: usize = 300;

fn mediapipe() -> String {
    std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../assets/mediapipe_canonical_4loop.obj"),
    )
    .unwrap()
}

/// A mesh the loaders accepted is welded, indexed in range, finite and has four loops.
fn assert_invariants(m: &FaceMesh) {
    let n = m.vertices.len();
    assert!(m.triangles.iter().flatten().all(|&i| (i as usize) < n));
    assert!(m.vertices.iter().all(|p| p.is_finite()));
    assert!(
        m.input_to_vertex
            .iter()
            .flatten()
            .all(|&i| (i as usize) < n)
    );
    let loops = face_prep::topology::validate(&m.vertices, &m.triangles).unwrap();
    assert_eq!(loops.len(), 4);
}

const SPECIAL: &[&str] = &[
    "0",
    "-1",
    "1e300",
    "nan",
    "inf",
    "4294967295",
    "-0",
    "1e-300",
    "2",
    "99999999999",
];

#[test]
fn mutated_obj_text_never_panics_and_accepted_meshes_are_valid() {
    let text = mediapipe();
    let lines: Vec<&str> = text.lines().collect();
    let mut rng = StdRng::seed_from_u64(13);
    let mut accepted = 0;
    for _ in 0..CASES {
        let mut l: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        for _ in 0..rng.random_range(1..4) {
            let i = rng.random_range(0..l.len());
            match rng.random_range(0..4) {
                0 => {
                    let j = rng.random_range(0..l.len());
                    l.swap(i, j);
                }
                1 => {
                    let dup = l[i].clone();
                    l.insert(i, dup);
                }
                2 => {
                    l.remove(i);
                }
                _ => {
                    let mut w: Vec<String> = l[i].split(' ').map(str::to_owned).collect();
                    let k = rng.random_range(0..w.len());
                    w[k] = SPECIAL[rng.random_range(0..SPECIAL.len())].to_owned();
                    l[i] = w.join(" ");
                }
            }
        }
        let bytes = l.join("\n").into_bytes();
        if let Ok(m) = FaceMesh::from_obj_bytes(&bytes, &InputLimits::default()) {
            assert_invariants(&m);
            accepted += 1;
        }
    }
    // Some mutations (swapped v lines, moved comments) keep a valid face.
    assert!(accepted > 10, "{accepted}");
}

#[test]
fn random_bytes_as_gltf_or_glb_never_panic() {
    let mut rng = StdRng::seed_from_u64(7);
    for _ in 0..CASES {
        let len = rng.random_range(0..400);
        let mut b: Vec<u8> = (0..len).map(|_| rng.random()).collect();
        if rng.random_bool(0.5) && b.len() >= 12 {
            b[..4].copy_from_slice(b"glTF");
            b[4..8].copy_from_slice(&2u32.to_le_bytes());
        }
        let _ = FaceMesh::from_gltf_slice(&b, None);
    }
}

fn random_muscles(rng: &mut StdRng) -> Vec<Muscle> {
    (0..rng.random_range(0..12))
        .map(|k| {
            let chain = |rng: &mut StdRng, n: usize| {
                let mut c: Vec<u32> = (0..n).map(|_| rng.random_range(0..5000)).collect();
                c.sort_unstable();
                c.dedup();
                c
            };
            let n_front = rng.random_range(0..30);
            let front = chain(rng, n_front);
            let n_back = rng.random_range(0..5);
            let back = chain(rng, n_back);
            Muscle {
                name: format!("muscle {k}"),
                kind: None,
                front_chain: front,
                back_chain: back,
            }
        })
        .collect()
}

#[test]
fn muscle_files_round_trip_and_mutations_never_panic() {
    let mut rng = StdRng::seed_from_u64(12);
    for _ in 0..CASES {
        let muscles = random_muscles(&mut rng);
        let text = muscle_file::to_string(&muscles).unwrap();
        assert_eq!(muscle_file::read_str(&text, 5000).unwrap(), muscles);
        // Mutate one line; the reader returns Ok or a typed error.
        let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
        if !lines.is_empty() {
            let i = rng.random_range(0..lines.len());
            lines[i] = SPECIAL[rng.random_range(0..SPECIAL.len())].to_owned();
            if let Ok(back) = muscle_file::read_str(&lines.join("\n"), 5000) {
                assert!(
                    back.iter()
                        .flat_map(|m| m.front_chain.iter().chain(&m.back_chain))
                        .all(|&e| e < 5000)
                );
            }
        }
    }
}

#[test]
fn sig6_keeps_six_significant_digits() {
    let mut rng = StdRng::seed_from_u64(6);
    for _ in 0..CASES * 10 {
        let x: f64 = rng.random_range(-1.0..1.0) * 10f64.powi(rng.random_range(-300..300));
        let s = sig6(x);
        assert!(s.len() <= 14, "{x} -> {s}");
        let back: f64 = s.parse().unwrap();
        assert!((back - x).abs() <= 5e-6 * x.abs(), "{x} -> {s}");
    }
}
