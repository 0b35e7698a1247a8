//! Kelvin fundamental solutions of 3D isotropic elastostatics.
//!
//! Conventions (`docs/design/solve.md`): `r = x_Q − x_P` (field point Q minus load point P), `n` the outward
//! unit normal at Q, the row index is the direction of the unit point load.
//!
//! `U_ij = [(3−4ν) δ_ij + r_,i r_,j] / (16 π μ (1−ν) r)`
//!
//! `T_ij = −[∂r/∂n ((1−2ν) δ_ij + 3 r_,i r_,j) − (1−2ν)(r_,i n_j − r_,j n_i)] / (8 π (1−ν) r²)`

use std::f64::consts::PI;

use glam::DVec3;

use crate::Material;

/// A 3×3 block, `block[row][col]`, row = load direction.
pub type Block = [[f64; 3]; 3];

/// Displacement kernel U(P, Q) for `r = x_Q − x_P` (r ≠ 0).
pub fn kelvin_u(r: DVec3, material: &Material) -> Block {
    let nu = material.poisson();
    let len = r.length();
    let d = (r / len).to_array();
    let c = 1.0 / (16.0 * PI * material.shear_modulus() * (1.0 - nu) * len);
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            let delta = if i == j { 3.0 - 4.0 * nu } else { 0.0 };
            *v = c * (delta + d[i] * d[j]);
        }
    }
    out
}

/// Traction kernel T(P, Q) for `r = x_Q − x_P` (r ≠ 0) and outward unit normal `n` at Q.
pub fn kelvin_t(r: DVec3, n: DVec3, material: &Material) -> Block {
    let nu = material.poisson();
    let len = r.length();
    let rh = r / len;
    let drdn = rh.dot(n);
    let d = rh.to_array();
    let nn = n.to_array();
    let c = -1.0 / (8.0 * PI * (1.0 - nu) * len * len);
    let a = 1.0 - 2.0 * nu;
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            let delta = if i == j { 1.0 } else { 0.0 };
            *v = c * (drdn * (a * delta + 3.0 * d[i] * d[j]) - a * (d[i] * nn[j] - d[j] * nn[i]));
        }
    }
    out
}

/// Kernel moments of one flat element seen from one collocation point: the integrals that
/// U and T blocks are linear combinations of (the element normal is constant, so it factors out).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Moments {
    /// Σ w ∂r/∂n / r²
    pub t0: f64,
    /// Σ w ∂r/∂n r̂_i r̂_j / r² (xx, yy, zz, xy, xz, yz)
    pub t2: [f64; 6],
    /// Σ w r̂ / r²
    pub t1: [f64; 3],
    /// Σ w / r
    pub u0: f64,
    /// Σ w r̂_i r̂_j / r (xx, yy, zz, xy, xz, yz)
    pub u2: [f64; 6],
}

impl Moments {
    /// All components in one array (t0, t2, t1, u0, u2).
    fn to_array(self) -> [f64; 17] {
        let mut a = [0.0; 17];
        a[0] = self.t0;
        a[1..7].copy_from_slice(&self.t2);
        a[7..10].copy_from_slice(&self.t1);
        a[10] = self.u0;
        a[11..17].copy_from_slice(&self.u2);
        a
    }

    fn from_array(a: [f64; 17]) -> Self {
        let mut m = Self {
            t0: a[0],
            u0: a[10],
            ..Self::default()
        };
        m.t2.copy_from_slice(&a[1..7]);
        m.t1.copy_from_slice(&a[7..10]);
        m.u2.copy_from_slice(&a[11..17]);
        m
    }

    /// Adds another set of moments component-wise.
    pub fn add_moments(&mut self, other: &Moments) {
        let (a, b) = (self.to_array(), other.to_array());
        *self = Self::from_array(std::array::from_fn(|k| a[k] + b[k]));
    }

    /// Adds `|a − b|` component-wise (an error estimate).
    pub fn add_abs_diff(&mut self, a: &Moments, b: &Moments) {
        let (s, a, b) = (self.to_array(), a.to_array(), b.to_array());
        *self = Self::from_array(std::array::from_fn(|k| s[k] + (a[k] - b[k]).abs()));
    }

    /// `self` as an error estimate relative to `total`: the larger of the traction-kernel and
    /// (with `need_u`) displacement-kernel groups' 1-norm ratios.
    pub fn relative_to(&self, total: &Moments, need_u: bool) -> f64 {
        let (e, t) = (self.to_array(), total.to_array());
        let ratio = |r: std::ops::Range<usize>| {
            let num: f64 = e[r.clone()].iter().map(|v| v.abs()).sum();
            let den: f64 = t[r].iter().map(|v| v.abs()).sum();
            if num == 0.0 { 0.0 } else { num / den }
        };
        let t_part = ratio(0..10);
        if need_u {
            t_part.max(ratio(10..17))
        } else {
            t_part
        }
    }

    /// Adds one quadrature point `q` with weight `w` (area included) for load point `p`
    /// (skipped if it coincides with `p`, which only a self-intersecting surface produces).
    #[inline(always)]
    pub fn add(&mut self, p: DVec3, q: DVec3, w: f64, n: DVec3, need_u: bool) {
        let r = q - p;
        let r2 = r.length_squared();
        if r2 == 0.0 {
            return;
        }
        let inv_r = 1.0 / r2.sqrt();
        let rh = r * inv_r;
        let w_r2 = w * inv_r * inv_r;
        let drdn = rh.dot(n);
        let wt = w_r2 * drdn;
        let (x, y, z) = (rh.x, rh.y, rh.z);
        let (xx, yy, zz, xy, xz, yz) = (x * x, y * y, z * z, x * y, x * z, y * z);
        self.t0 += wt;
        self.t2[0] += wt * xx;
        self.t2[1] += wt * yy;
        self.t2[2] += wt * zz;
        self.t2[3] += wt * xy;
        self.t2[4] += wt * xz;
        self.t2[5] += wt * yz;
        self.t1[0] += w_r2 * x;
        self.t1[1] += w_r2 * y;
        self.t1[2] += w_r2 * z;
        if need_u {
            let wu = w * inv_r;
            self.u0 += wu;
            self.u2[0] += wu * xx;
            self.u2[1] += wu * yy;
            self.u2[2] += wu * zz;
            self.u2[3] += wu * xy;
            self.u2[4] += wu * xz;
            self.u2[5] += wu * yz;
        }
    }
}

/// Precomputed material constants turning [`Moments`] into blocks.
#[derive(Debug, Clone, Copy)]
pub(crate) struct KernelConstants {
    /// −1 / (8π(1−ν))
    t_scale: f64,
    /// 1 − 2ν
    a: f64,
    /// 1 / (16 π μ (1−ν))
    u_scale: f64,
    /// 3 − 4ν
    b: f64,
}

impl KernelConstants {
    pub fn new(material: &Material) -> Self {
        let nu = material.poisson();
        Self {
            t_scale: -1.0 / (8.0 * PI * (1.0 - nu)),
            a: 1.0 - 2.0 * nu,
            u_scale: 1.0 / (16.0 * PI * material.shear_modulus() * (1.0 - nu)),
            b: 3.0 - 4.0 * nu,
        }
    }

    /// H block from the moments of an element with normal `n`.
    #[inline(always)]
    pub fn t_block(&self, m: &Moments, n: DVec3) -> Block {
        let s = self.t_scale;
        let a = self.a;
        let d = a * m.t0;
        let [sxx, syy, szz, sxy, sxz, syz] = m.t2;
        let [vx, vy, vz] = m.t1;
        // antisymmetric part: a (v_i n_j − v_j n_i)
        let axy = a * (vx * n.y - vy * n.x);
        let axz = a * (vx * n.z - vz * n.x);
        let ayz = a * (vy * n.z - vz * n.y);
        [
            [
                s * (d + 3.0 * sxx),
                s * (3.0 * sxy - axy),
                s * (3.0 * sxz - axz),
            ],
            [
                s * (3.0 * sxy + axy),
                s * (d + 3.0 * syy),
                s * (3.0 * syz - ayz),
            ],
            [
                s * (3.0 * sxz + axz),
                s * (3.0 * syz + ayz),
                s * (d + 3.0 * szz),
            ],
        ]
    }

    /// G block from the moments.
    #[inline(always)]
    pub fn u_block(&self, m: &Moments) -> Block {
        let s = self.u_scale;
        let d = self.b * m.u0;
        let [xx, yy, zz, xy, xz, yz] = m.u2;
        [
            [s * (d + xx), s * xy, s * xz],
            [s * xy, s * (d + yy), s * yz],
            [s * xz, s * yz, s * (d + zz)],
        ]
    }
}
