//! The two lid margins of an eye loop: its corners (canthi), the upper and lower arcs between
//! them, and a parameter along the corner-to-corner chord that pairs each point of one margin
//! with a point of the other.

use glam::{DVec2, DVec3};

use crate::controls::ids::Side;

/// An eye loop split at its corners into the upper and the lower lid margin.
///
/// Both margins run from the medial corner (the canthus nearer the face's midline) to the
/// lateral corner and include both corners. Each margin vertex carries a parameter
/// `t ∈ [0, 1]`: its projection onto the corner-to-corner chord in the front plane (0 at the
/// medial corner, 1 at the lateral one), so the upper-margin point at `t` closes onto the
/// lower-margin point at the same `t`, straight across the opening, whatever the number of
/// vertices of either margin. (Pairing by arc length along each margin was tried first: on the
/// Lee Perry-Smith scan's slit right eye, 2.5 mm open, whose two margins curve differently, it
/// paired points up to several mm apart sideways, and a quarter blink already crossed the
/// margins by 0.5 mm.)
///
/// ```
/// use face_prep::Side;
/// use face_prep::eyelid::EyeMargins;
/// use glam::DVec3;
/// // An eye of the face's left (+x): a lens 4 wide, 1 high, centred at (3, 0).
/// let pts: Vec<DVec3> = (0..12)
///     .map(|k| {
///         let a = std::f64::consts::TAU * k as f64 / 12.0;
///         DVec3::new(3.0 + 2.0 * a.cos(), 0.5 * a.sin(), 0.0)
///     })
///     .collect();
/// let lp: Vec<u32> = (0..12).collect();
/// let m = EyeMargins::of_loop(&pts, &lp, Side::Left).unwrap();
/// assert_eq!(m.medial, 6); // smallest x: nearer the midline
/// assert_eq!(m.lateral, 0);
/// assert_eq!(m.upper.len(), 7);
/// assert!((m.opening_height(&pts) - 1.0).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct EyeMargins {
    /// The medial corner (inner canthus).
    pub medial: u32,
    /// The lateral corner (outer canthus).
    pub lateral: u32,
    /// Upper margin, medial → lateral, corners included.
    pub upper: Vec<u32>,
    /// Parameter of each upper-margin vertex (see [`EyeMargins`]).
    pub upper_t: Vec<f64>,
    /// Lower margin, medial → lateral, corners included.
    pub lower: Vec<u32>,
    /// Parameter of each lower-margin vertex.
    pub lower_t: Vec<f64>,
}

impl EyeMargins {
    /// Splits the eye loop `lp` (indices into `canonical`, positions in the canonical frame: the
    /// face looks toward +z, +y is up, +x the face's left) at its corners, the loop vertices of
    /// smallest and largest x; the medial corner is the one toward the midline (smaller x for
    /// the face's left eye). The upper margin is the arc whose mean height is larger. `None`
    /// for a loop of fewer than four vertices or with a margin of zero length.
    pub fn of_loop(canonical: &[DVec3], lp: &[u32], side: Side) -> Option<EyeMargins> {
        let n = lp.len();
        if n < 4 || lp.iter().any(|&v| v as usize >= canonical.len()) {
            return None;
        }
        let x = |k: usize| canonical[lp[k] as usize].x;
        let min_k = (0..n).min_by(|&a, &b| x(a).total_cmp(&x(b)))?;
        let max_k = (0..n).max_by(|&a, &b| x(a).total_cmp(&x(b)))?;
        if min_k == max_k {
            return None;
        }
        let (medial_k, lateral_k) = match side {
            Side::Left => (min_k, max_k),
            Side::Right => (max_k, min_k),
            Side::Center => return None,
        };
        // The two arcs from the medial corner to the lateral one, each way round the loop.
        let walk = |step: usize| {
            let mut arc = vec![lp[medial_k]];
            let mut k = medial_k;
            while k != lateral_k {
                k = (k + step) % n;
                arc.push(lp[k]);
            }
            arc
        };
        let forward = walk(1);
        let backward = walk(n - 1);
        let mean_y = |arc: &[u32]| {
            arc.iter().map(|&v| canonical[v as usize].y).sum::<f64>() / arc.len() as f64
        };
        let (upper, lower) = if mean_y(&forward) >= mean_y(&backward) {
            (forward, backward)
        } else {
            (backward, forward)
        };
        let upper_t = chord_parameters(canonical, &upper)?;
        let lower_t = chord_parameters(canonical, &lower)?;
        Some(EyeMargins {
            medial: lp[medial_k],
            lateral: lp[lateral_k],
            upper,
            upper_t,
            lower,
            lower_t,
        })
    }

    /// The point of the upper margin at parameter `t` (clamped to [0, 1]) for vertex positions
    /// `p` (any frame; a rigid or affine map of the positions maps the point alike).
    pub fn upper_at(&self, p: &[DVec3], t: f64) -> DVec3 {
        point_at(p, &self.upper, &self.upper_t, t)
    }

    /// The point of the lower margin at parameter `t` (clamped to [0, 1]).
    pub fn lower_at(&self, p: &[DVec3], t: f64) -> DVec3 {
        point_at(p, &self.lower, &self.lower_t, t)
    }

    /// The same interpolation for a per-vertex field (e.g. displacements) on the lower margin.
    pub(crate) fn lower_field_at(&self, field: &[DVec3], t: f64) -> DVec3 {
        point_at(field, &self.lower, &self.lower_t, t)
    }

    /// The closest point of the lower margin to `q` seen along `view` (a unit vector; the
    /// distance is measured in the plane normal to it; positions `p` in any frame): its
    /// parameter and that distance.
    pub(crate) fn closest_on_lower(&self, p: &[DVec3], q: DVec3, view: DVec3) -> (f64, f64) {
        let flat = |x: DVec3| x - view * x.dot(view);
        let q = flat(q);
        let mut best = (0.0, f64::INFINITY);
        for k in 0..self.lower.len().saturating_sub(1) {
            let (a, b) = (
                flat(p[self.lower[k] as usize]),
                flat(p[self.lower[k + 1] as usize]),
            );
            let d = b - a;
            let len2 = d.length_squared();
            let f = if len2 > 0.0 {
                ((q - a).dot(d) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let dist = q.distance(a + d * f);
            if dist < best.1 {
                let (t0, t1) = (self.lower_t[k], self.lower_t[k + 1]);
                best = (t0 + f * (t1 - t0), dist);
            }
        }
        best
    }

    /// The opening at `t`: the vector from the upper-margin point to the lower-margin point.
    pub fn opening(&self, p: &[DVec3], t: f64) -> DVec3 {
        self.lower_at(p, t) - self.upper_at(p, t)
    }

    /// Vertical gap (canonical y of the upper margin minus that of the lower margin at the same
    /// parameter) at every upper-margin vertex, for canonical positions `p`. Negative where the
    /// upper margin lies below the lower one.
    pub fn gaps(&self, p: &[DVec3]) -> Vec<f64> {
        self.upper
            .iter()
            .zip(&self.upper_t)
            .map(|(&v, &t)| p[v as usize].y - self.lower_at(p, t).y)
            .collect()
    }

    /// Vertical gap measured straight up and down (canonical y), for canonical positions `p`:
    /// for every upper-margin vertex between the corners, its height above the lower margin at
    /// the same x (the highest lower-margin point there, if the margin doubles back); `None`
    /// for an upper vertex beyond the lower margin's x-range. Negative where the upper margin
    /// lies below the lower one: the lids have crossed.
    ///
    /// ```
    /// use face_prep::Side;
    /// use face_prep::eyelid::EyeMargins;
    /// use glam::DVec3;
    /// let p = [
    ///     DVec3::new(0.0, 0.0, 0.0),
    ///     DVec3::new(1.0, 0.5, 0.0),
    ///     DVec3::new(2.0, 0.0, 0.0),
    ///     DVec3::new(1.5, -0.2, 0.0),
    ///     DVec3::new(0.5, -0.2, 0.0),
    /// ];
    /// let m = EyeMargins::of_loop(&p, &[0, 1, 2, 3, 4], Side::Left).unwrap();
    /// let g = m.vertical_gaps(&p);
    /// assert_eq!(g.len(), 1);
    /// assert!((g[0].unwrap() - 0.7).abs() < 1e-12);
    /// ```
    pub fn vertical_gaps(&self, p: &[DVec3]) -> Vec<Option<f64>> {
        let n = self.upper.len();
        self.upper[1..n.saturating_sub(1).max(1)]
            .iter()
            .map(|&v| self.lower_under(p, p[v as usize]).map(|(_, gap)| gap))
            .collect()
    }

    /// The segment of the lower margin under the point `q` seen from the front (of the
    /// segments spanning `q.x`, the one highest there, as [`EyeMargins::vertical_gaps`] reads
    /// it): the index in [`EyeMargins::lower`] of its first vertex, and `q`'s height above it.
    /// `None` beyond the lower margin's x-range.
    ///
    /// ```
    /// use face_prep::Side;
    /// use face_prep::eyelid::EyeMargins;
    /// use glam::DVec3;
    /// let p = [
    ///     DVec3::new(0.0, 0.0, 0.0),
    ///     DVec3::new(1.0, 0.5, 0.0),
    ///     DVec3::new(2.0, 0.0, 0.0),
    ///     DVec3::new(1.0, -0.5, 0.0),
    /// ];
    /// let m = EyeMargins::of_loop(&p, &[0, 1, 2, 3], Side::Left).unwrap();
    /// let (i, gap) = m.lower_under(&p, DVec3::new(1.5, 0.0, 0.0)).unwrap();
    /// assert_eq!((m.lower[i], m.lower[i + 1]), (3, 2));
    /// assert!((gap - 0.25).abs() < 1e-12);
    /// ```
    pub fn lower_under(&self, p: &[DVec3], q: DVec3) -> Option<(usize, f64)> {
        self.lower
            .windows(2)
            .enumerate()
            .filter_map(|(i, w)| {
                let (a, b) = (p[w[0] as usize], p[w[1] as usize]);
                let (lo, hi) = (a.x.min(b.x), a.x.max(b.x));
                if q.x < lo || q.x > hi {
                    return None;
                }
                let f = if hi > lo {
                    (q.x - a.x) / (b.x - a.x)
                } else {
                    0.5
                };
                Some((i, a.y + f * (b.y - a.y)))
            })
            .reduce(|best, c| if c.1 > best.1 { c } else { best })
            .map(|(i, y)| (i, q.y - y))
    }

    /// The largest vertical gap ([`EyeMargins::gaps`]): the eye's opening height.
    pub fn opening_height(&self, p: &[DVec3]) -> f64 {
        self.gaps(p).into_iter().fold(0.0, f64::max)
    }

    /// Margin length (mean of the two margins' lengths, the corner-to-corner width along the
    /// lids), for positions `p`.
    pub fn width(&self, p: &[DVec3]) -> f64 {
        let len = |arc: &[u32]| {
            arc.windows(2)
                .map(|w| p[w[0] as usize].distance(p[w[1] as usize]))
                .sum::<f64>()
        };
        0.5 * (len(&self.upper) + len(&self.lower))
    }

    /// Where a point of the front plane lies relative to the lids: on the upper side (closer to
    /// the upper margin than to the lower one, and above it) or the lower side, with the
    /// parameter of its closest margin point and its distance from the margin (in the plane).
    /// `None` for a point inside the eye opening (between the margins).
    pub(crate) fn locate(&self, p: &[DVec3], q: DVec2) -> Option<LidPoint> {
        let up: Vec<DVec2> = self
            .upper
            .iter()
            .map(|&v| p[v as usize].truncate())
            .collect();
        let lo: Vec<DVec2> = self
            .lower
            .iter()
            .map(|&v| p[v as usize].truncate())
            .collect();
        let (tu, du, su) = closest_on_polyline(&up, &self.upper_t, q);
        let (tl, dl, sl) = closest_on_polyline(&lo, &self.lower_t, q);
        // `s` is the side of the margin (its direction medial → lateral) the point lies on;
        // above the upper margin and below the lower one are opposite sides for the two
        // eyes, so compare with the side of the other margin's midpoint.
        let mid_lower = self.lower_at(p, 0.5).truncate();
        let mid_upper = self.upper_at(p, 0.5).truncate();
        let inside_upper = side_of(&up, &self.upper_t, mid_lower);
        let inside_lower = side_of(&lo, &self.lower_t, mid_upper);
        if du <= dl {
            (su != inside_upper || du == 0.0).then_some(LidPoint {
                lid: Lid::Upper,
                t: tu,
                distance: du,
            })
        } else {
            (sl != inside_lower).then_some(LidPoint {
                lid: Lid::Lower,
                t: tl,
                distance: dl,
            })
        }
    }
}

/// Which lid a point belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub(crate) enum Lid {
    /// The upper lid (above the upper margin).
    Upper,
    /// The lower lid (below the lower margin).
    Lower,
}

/// A point located relative to the lid margins ([`EyeMargins::locate`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LidPoint {
    /// The lid it lies on.
    pub lid: Lid,
    /// Parameter of its closest point on that lid's margin.
    pub t: f64,
    /// Distance from that margin in the front plane.
    pub distance: f64,
}

/// Parameter of each vertex of `arc` (from the medial corner, its first vertex, to the lateral
/// corner, its last): its projection onto the corner-to-corner chord in the front plane (x-y),
/// 0 at the medial corner and 1 at the lateral one, made non-decreasing along the arc. `None`
/// if the corners coincide in the front plane.
fn chord_parameters(p: &[DVec3], arc: &[u32]) -> Option<Vec<f64>> {
    let a = p[*arc.first()? as usize].truncate();
    let b = p[*arc.last()? as usize].truncate();
    let chord = b - a;
    let len2 = chord.length_squared();
    if len2 <= 0.0 {
        return None;
    }
    let mut last = 0.0f64;
    let mut ts: Vec<f64> = arc
        .iter()
        .map(|&v| {
            let t = ((p[v as usize].truncate() - a).dot(chord) / len2).clamp(0.0, 1.0);
            last = last.max(t);
            last
        })
        .collect();
    ts[0] = 0.0;
    if let Some(t) = ts.last_mut() {
        *t = 1.0;
    }
    Some(ts)
}

/// Linear interpolation of `values[arc[k]]` at parameter `t` along `arc` (parameters `ts`).
fn point_at(values: &[DVec3], arc: &[u32], ts: &[f64], t: f64) -> DVec3 {
    let t = t.clamp(0.0, 1.0);
    let k = ts.partition_point(|&x| x < t).clamp(1, arc.len() - 1);
    let (t0, t1) = (ts[k - 1], ts[k]);
    let f = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
    values[arc[k - 1] as usize].lerp(values[arc[k] as usize], f)
}

/// Closest point of a polyline to `q`: its parameter, the distance, and the side of the
/// polyline `q` lies on (sign of the cross product with the closest segment's direction).
fn closest_on_polyline(line: &[DVec2], ts: &[f64], q: DVec2) -> (f64, f64, bool) {
    let mut best = (0.0, f64::INFINITY, true);
    for k in 0..line.len().saturating_sub(1) {
        let (a, b) = (line[k], line[k + 1]);
        let d = b - a;
        let len2 = d.length_squared();
        let f = if len2 > 0.0 {
            ((q - a).dot(d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let dist = q.distance(a + d * f);
        if dist < best.1 {
            best = (
                ts[k] + f * (ts[k + 1] - ts[k]),
                dist,
                d.perp_dot(q - a) >= 0.0,
            );
        }
    }
    best
}

/// The side of the polyline `q` lies on (see [`closest_on_polyline`]).
fn side_of(line: &[DVec2], ts: &[f64], q: DVec2) -> bool {
    closest_on_polyline(line, ts, q).2
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lens-shaped eye loop of `n` vertices, `w` wide and `h` high, centred at (cx, 0); the
    /// loop starts at an arbitrary vertex `start` and runs clockwise if `reverse`.
    fn lens(
        n: usize,
        cx: f64,
        w: f64,
        h: f64,
        start: usize,
        reverse: bool,
    ) -> (Vec<DVec3>, Vec<u32>) {
        let pts: Vec<DVec3> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                DVec3::new(cx + 0.5 * w * a.cos(), 0.5 * h * a.sin(), 0.1 * a.sin())
            })
            .collect();
        let mut lp: Vec<u32> = (0..n as u32)
            .map(|k| (k + start as u32) % n as u32)
            .collect();
        if reverse {
            lp.reverse();
        }
        (pts, lp)
    }

    #[test]
    fn margins_are_found_whatever_the_loop_start_and_direction() {
        for (start, reverse) in [(0, false), (5, false), (3, true), (11, true)] {
            let (p, lp) = lens(16, 3.0, 4.0, 1.0, start, reverse);
            let m = EyeMargins::of_loop(&p, &lp, Side::Left).unwrap();
            assert_eq!(m.medial, 8);
            assert_eq!(m.lateral, 0);
            assert_eq!(m.upper.len(), 9);
            assert_eq!(m.lower.len(), 9);
            assert!(m.upper.iter().all(|&v| p[v as usize].y >= -1e-12));
            assert!(m.lower.iter().all(|&v| p[v as usize].y <= 1e-12));
            assert_eq!((m.upper_t[0], m.upper_t[8]), (0.0, 1.0));
            // Mirror eye on the face's right: the medial corner is the larger x.
            let (p, lp) = lens(16, -3.0, 4.0, 1.0, start, reverse);
            let m = EyeMargins::of_loop(&p, &lp, Side::Right).unwrap();
            assert_eq!(m.medial, 0);
            assert_eq!(m.lateral, 8);
        }
    }

    #[test]
    fn upper_and_lower_points_pair_across_the_chord() {
        // Upper margin 3 vertices, lower margin 6: the upper midpoint pairs with the lower
        // margin's midpoint, not with a vertex.
        let p = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.5, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(1.6, -0.2, 0.0),
            DVec3::new(1.2, -0.3, 0.0),
            DVec3::new(0.8, -0.3, 0.0),
            DVec3::new(0.4, -0.2, 0.0),
        ];
        let lp = [0, 1, 2, 3, 4, 5, 6];
        let m = EyeMargins::of_loop(&p, &lp, Side::Left).unwrap();
        assert_eq!(m.upper, vec![0, 1, 2]);
        assert_eq!(m.lower, vec![0, 6, 5, 4, 3, 2]);
        let mid = m.lower_at(&p, 0.5);
        assert!((mid - DVec3::new(1.0, -0.3, 0.0)).length() < 1e-12);
        assert!((m.opening_height(&p) - 0.8).abs() < 1e-12);
        let o = m.opening(&p, 0.5);
        assert!((o - DVec3::new(0.0, -0.8, 0.0)).length() < 1e-12);
    }

    #[test]
    fn points_are_located_on_their_lid() {
        let (p, lp) = lens(24, 3.0, 4.0, 1.0, 0, false);
        let m = EyeMargins::of_loop(&p, &lp, Side::Left).unwrap();
        let above = m.locate(&p, DVec2::new(3.0, 1.5)).unwrap();
        assert_eq!(above.lid, Lid::Upper);
        assert!((above.t - 0.5).abs() < 0.02);
        assert!((above.distance - 1.0).abs() < 0.02);
        let below = m.locate(&p, DVec2::new(2.0, -1.0)).unwrap();
        assert_eq!(below.lid, Lid::Lower);
        assert!(below.t < 0.5);
        assert!(m.locate(&p, DVec2::new(3.0, 0.1)).is_none());
        // The same for the mirrored eye on the right.
        let (p, lp) = lens(24, -3.0, 4.0, 1.0, 7, true);
        let m = EyeMargins::of_loop(&p, &lp, Side::Right).unwrap();
        assert_eq!(m.locate(&p, DVec2::new(-3.0, 1.5)).unwrap().lid, Lid::Upper);
        assert_eq!(
            m.locate(&p, DVec2::new(-3.5, -1.0)).unwrap().lid,
            Lid::Lower
        );
        assert!(m.locate(&p, DVec2::new(-3.0, -0.1)).is_none());
    }

    #[test]
    fn degenerate_loops_are_rejected() {
        let p = vec![DVec3::ZERO; 5];
        assert!(EyeMargins::of_loop(&p, &[0, 1, 2, 3, 4], Side::Left).is_none());
        assert!(EyeMargins::of_loop(&p, &[0, 1, 2], Side::Left).is_none());
        assert!(EyeMargins::of_loop(&p, &[0, 1, 2, 9], Side::Left).is_none());
    }
}
