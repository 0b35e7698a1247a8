//! The sphere through a point set: the algebraic least-squares fit (Pratt 1987, "Direct
//! least-squares fitting of algebraic surfaces"; the linear form `|p|² + D·p + e = 0`), on
//! coordinates centred on their mean for conditioning, with the RMS geometric distance of the
//! points from the sphere found.

use glam::{DMat3, DVec3};

/// A fitted sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Its centre.
    pub centre: DVec3,
    /// Its radius.
    pub radius: f64,
    /// The RMS distance of the fitted points from the sphere.
    pub rms: f64,
}

/// The least-squares sphere through `points`; `None` for fewer than four points, points on a
/// plane or a line, or non-finite input.
///
/// ```
/// use face_prep::parts::fit_sphere;
/// use glam::DVec3;
/// let c = DVec3::new(1.0, -2.0, 3.0);
/// let pts: Vec<DVec3> = (0..40)
///     .map(|i| {
///         let (t, f) = (i as f64 * 0.7, i as f64 * 0.37);
///         c + 2.5 * DVec3::new(t.cos() * f.sin(), t.sin() * f.sin(), f.cos())
///     })
///     .collect();
/// let s = fit_sphere(&pts).unwrap();
/// assert!((s.radius - 2.5).abs() < 1e-9 && s.centre.distance(c) < 1e-9 && s.rms < 1e-9);
/// assert!(fit_sphere(&[DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE.with_z(0.0)]).is_none());
/// ```
pub fn fit_sphere(points: &[DVec3]) -> Option<Sphere> {
    if points.len() < 4 {
        return None;
    }
    let n = points.len() as f64;
    let mean = points.iter().sum::<DVec3>() / n;
    // With q = p − mean: |q|² = 2 c·q + k (c the centre's offset, k = r² − |c|²). Normal
    // equations in (c, k): [Σ 4 q qᵀ, Σ 2 q; Σ 2 qᵀ, n] (c, k) = (Σ 2 q |q|², Σ |q|²).
    // Σ q = 0 on centred coordinates, so the system decouples: 4 A c = 2 s and n k = t, with
    // A = Σ q qᵀ, s = Σ q |q|², t = Σ |q|².
    let (mut a, mut s, mut t) = (DMat3::ZERO, DVec3::ZERO, 0.0);
    for p in points {
        let q = *p - mean;
        let qq = q.length_squared();
        a += DMat3::from_cols(q * q.x, q * q.y, q * q.z);
        s += q * qq;
        t += qq;
    }
    // det A is about (t / 3)³ for points spread in 3D and rounding noise for coplanar ones.
    let det = a.determinant().abs();
    if det.is_nan() || det <= 1e-9 * t * t * t {
        return None;
    }
    let c = a.inverse() * (0.5 * s);
    let k = t / n;
    let r2 = k + c.length_squared();
    if !(r2.is_finite() && r2 > 0.0 && c.is_finite()) {
        return None;
    }
    let radius = r2.sqrt();
    let centre = mean + c;
    let rms = (points
        .iter()
        .map(|p| (p.distance(centre) - radius).powi(2))
        .sum::<f64>()
        / n)
        .sqrt();
    Some(Sphere {
        centre,
        radius,
        rms,
    })
}
