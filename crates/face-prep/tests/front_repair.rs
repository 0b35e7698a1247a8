//! The front repair on synthetic sheets: crossing sheets are pushed apart, clean ones untouched.

use face_prep::FrontRepair;
use face_prep::shell::{intersecting_pairs, repair_front_intersections};
use glam::DVec3;

/// An `m`×`m`-vertex grid over the unit square (shifted by 0.031 in y for `offset` > 0, so that two
/// sheets' edges do not meet exactly), lifted by `z(x, y)`, facing +z or −z.
fn sheet(
    m: u32,
    z: impl Fn(f64, f64) -> f64,
    up: bool,
    offset: u32,
) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let h = 1.0 / f64::from(m - 1);
    let v = (0..m)
        .flat_map(|j| (0..m).map(move |i| (f64::from(i) * h, f64::from(j) * h)))
        .map(|(x, y)| DVec3::new(x, y + 0.031 * f64::from(offset.min(1)), z(x, y)))
        .collect();
    let id = |i: u32, j: u32| offset + i + m * j;
    let mut t = Vec::new();
    for j in 0..m - 1 {
        for i in 0..m - 1 {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if up {
                t.extend([[a, b, c], [a, c, d]]);
            } else {
                t.extend([[a, c, b], [a, d, c]]);
            }
        }
    }
    (v, t)
}

#[test]
fn crossing_facing_sheets_are_pushed_apart() {
    // A flat sheet facing up and a tilted one above it facing down, dipping 0.07 below it
    // at x = 1 (like a lip crossing the other lip).
    let m = 7;
    let (mut v, mut t) = sheet(m, |_, _| 0.0, true, 0);
    let (v2, t2) = sheet(m, |x, _| 0.1 - 0.17 * x, false, m * m);
    v.extend(v2);
    t.extend(t2);
    let before = intersecting_pairs(&v, &t);
    assert!(!before.is_empty());
    let input = v.clone();
    let r = repair_front_intersections(&mut v, &t, 30);
    assert_eq!(r.input_intersections, before.len());
    assert_eq!(r.remaining_intersections, 0, "{r:?}");
    assert!(intersecting_pairs(&v, &t).is_empty());
    let moves: Vec<f64> = v.iter().zip(&input).map(|(p, q)| p.distance(*q)).collect();
    assert_eq!(
        moves.iter().copied().fold(0.0, f64::max),
        r.max_displacement
    );
    // Edge length 1/6: the sheets overlap by at most 0.07 and must end 0.3 edges = 0.05 apart,
    // so nothing moves by more than one edge length (the hard limit), and where they are
    // more than 0.05 apart to begin with (x ≤ 1/6: 0.072 apart) nothing moves at all.
    assert!(r.max_displacement <= 1.0 / 6.0 + 1e-12, "{r:?}");
    for (i, (p, q)) in v.iter().zip(&input).enumerate() {
        if q.x <= 1.0 / 6.0 + 1e-9 {
            assert_eq!(p, q, "vertex {i}");
        }
    }
    // The lower sheet moved down or stayed, the upper one up or stayed.
    for (i, (p, q)) in v.iter().zip(&input).enumerate() {
        if i < (m * m) as usize {
            assert!(p.z <= q.z + 1e-12, "vertex {i}");
        } else {
            assert!(p.z >= q.z - 1e-12, "vertex {i}");
        }
    }
}

#[test]
fn sheets_far_apart_are_left_bit_for_bit() {
    let m = 6;
    let (mut v, mut t) = sheet(m, |x, y| 0.1 * x * y, true, 0);
    let (v2, t2) = sheet(m, |_, _| 0.5, false, m * m);
    v.extend(v2);
    t.extend(t2);
    let input = v.clone();
    let r = repair_front_intersections(&mut v, &t, 30);
    assert_eq!(r, FrontRepair::default());
    for (p, q) in v.iter().zip(&input) {
        assert_eq!(
            p.to_array().map(f64::to_bits),
            q.to_array().map(f64::to_bits)
        );
    }
}

#[test]
fn zero_rounds_leave_crossing_sheets_as_they_are() {
    let m = 5;
    let (mut v, mut t) = sheet(m, |_, _| 0.0, true, 0);
    let (v2, t2) = sheet(m, |x, _| 0.1 - 0.17 * x, false, m * m);
    v.extend(v2);
    t.extend(t2);
    let input = v.clone();
    let r = repair_front_intersections(&mut v, &t, 0);
    assert!(r.input_intersections > 0);
    assert_eq!(r.remaining_intersections, r.input_intersections);
    assert_eq!(
        (r.rounds, r.moved_vertices, r.max_displacement),
        (0, 0, 0.0)
    );
    assert_eq!(v, input);
}

/// Regression (issue 13, fuzz find `obj_fuzz_lee_perry_smith_scrambled_slow_front_repair.obj`):
/// scrambled geometry — vertex positions shuffled, so triangles span the sheet and cross each
/// other everywhere — is not a fold the local pushes can open, and every round cost O(n²). It is
/// returned unchanged after one intersection pass.
#[test]
fn scrambled_sheet_is_left_unrepaired_after_one_pass() {
    use face_prep::shell::MAX_REPAIRABLE_CROSSINGS;
    let m = 15;
    let (mut v, t) = sheet(m, |x, y| 0.05 * (3.0 * x).sin() * (2.0 * y).cos(), true, 0);
    // Reverse the order of the positions of every third vertex among themselves.
    let picked: Vec<usize> = (0..v.len()).step_by(3).collect();
    let positions: Vec<DVec3> = picked.iter().map(|&i| v[i]).collect();
    for (&i, p) in picked.iter().zip(positions.iter().rev()) {
        v[i] = *p;
    }
    let pairs = intersecting_pairs(&v, &t);
    let most = (0..t.len() as u32)
        .map(|k| pairs.iter().filter(|p| p.contains(&k)).count())
        .max()
        .unwrap_or(0);
    assert!(
        most > MAX_REPAIRABLE_CROSSINGS,
        "at most {most} crossings per triangle: not scrambled enough for this test"
    );
    let input = v.clone();
    let r = repair_front_intersections(&mut v, &t, 30);
    assert_eq!(r.rounds, 0, "{r:?}");
    assert_eq!(r.input_intersections, pairs.len());
    assert_eq!(r.remaining_intersections, pairs.len());
    assert_eq!(v, input);
}
