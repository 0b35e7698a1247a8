//! The fixed heat-map scale of displacement magnitude in millimetres.
//!
//! Skin that moves less than [`EDGES_MM`]`[0]` = 0.5 mm is drawn in neutral grey: that is the
//! tolerance the project allows the face contour (issue 10's acceptance), below the ≈ 1.5 mm noise
//! floor of human facial motion capture. Above it, ten colour bins (blue → green → yellow → red
//! → dark magenta) with edges at 0.5, 1, 2, 3, 4, 6, 8, 10, 12 and 15 mm: fine steps where the
//! small and unwanted motions are (a contour that should not move, the opposite mouth corner) and
//! coarser ones over the range of real expressions (posed smile: mouth corner 9.3 ± 2.8 mm; brow
//! raise 10.6 ± 2.5 mm; Jorge Jr. et al. 2012). Everything at or above 15 mm, the upper end of the
//! range the issue accepts for a full zygomaticus contraction, is the last colour.
//!
//! The scale is the same on every sheet and every face (in physical units, via the face's
//! millimetres per unit), so sheets can be compared with each other.
//!
//! ```
//! use facebem::report::contact_sheet::heat;
//! assert_eq!(heat::bin(0.3), None); // grey: does not move
//! assert_eq!(heat::bin(0.5), Some(0));
//! assert_eq!(heat::bin(9.3), Some(6)); // [8, 10) mm
//! assert_eq!(heat::bin(40.0), Some(heat::COLOURS.len() - 1));
//! // A shaded pixel of a bin's colour is recognised as that bin.
//! let c = heat::COLOURS[4].map(|v| (f64::from(v) * 0.6) as u8);
//! assert_eq!(heat::classify(c), Some(4));
//! assert_eq!(heat::classify([120, 120, 120]), None);
//! ```

/// Lower edges of the colour bins in mm; bin `i` is `[EDGES_MM[i], EDGES_MM[i + 1])`, the last
/// bin is open above.
pub const EDGES_MM: [f64; 10] = [0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 10.0, 12.0, 15.0];

/// sRGB colour of each bin (before shading).
pub const COLOURS: [[u8; 3]; 10] = [
    [48, 70, 190],  // 0.5–1
    [30, 130, 235], // 1–2
    [20, 190, 215], // 2–3
    [40, 200, 120], // 3–4
    [150, 215, 40], // 4–6
    [250, 220, 30], // 6–8
    [250, 150, 20], // 8–10
    [235, 80, 25],  // 10–12
    [195, 20, 35],  // 12–15
    [125, 10, 110], // ≥ 15
];

/// Colour of skin that moves less than [`EDGES_MM`]`[0]` (before shading).
pub const SKIN: [u8; 3] = [205, 205, 205];

/// The bin of a displacement magnitude in mm, `None` below [`EDGES_MM`]`[0]` (or not finite).
pub fn bin(displacement_mm: f64) -> Option<usize> {
    if displacement_mm.is_nan() || displacement_mm < EDGES_MM[0] {
        return None;
    }
    Some(
        EDGES_MM
            .iter()
            .rposition(|&e| displacement_mm >= e)
            .unwrap_or(0),
    )
}

/// The unshaded colour of a displacement magnitude in mm.
pub fn colour(displacement_mm: f64) -> [u8; 3] {
    bin(displacement_mm).map_or(SKIN, |b| COLOURS[b])
}

/// Chroma (max − min channel) below which a pixel counts as grey in [`classify`].
pub const GREY_CHROMA: u8 = 24;

/// The bin whose colour a rendered (shaded, possibly anti-aliased) pixel shows, `None` for grey
/// pixels (skin, background, text, arrows). A rendered pixel is `a · shade · colour + grey`
/// (shading scales all channels alike; anti-aliasing mixes in grey skin or white background),
/// so the pixel and each bin colour are compared after removing their smallest channel and
/// scaling the rest to a largest value of 1, which cancels both.
pub fn classify(rgb: [u8; 3]) -> Option<usize> {
    let max = rgb.iter().copied().max().unwrap_or(0);
    let min = rgb.iter().copied().min().unwrap_or(0);
    if max - min < GREY_CHROMA {
        return None;
    }
    let norm = |c: [u8; 3]| {
        let lo = f64::from(c.iter().copied().min().unwrap_or(0));
        let hi = f64::from(c.iter().copied().max().unwrap_or(0));
        let span = (hi - lo).max(1.0);
        c.map(|v| (f64::from(v) - lo) / span)
    };
    let p = norm(rgb);
    (0..COLOURS.len()).min_by(|&a, &b| {
        let d = |i: usize| {
            let q = norm(COLOURS[i]);
            (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()
        };
        d(a).total_cmp(&d(b))
    })
}

/// Legend text of bin `i`'s lower edge (e.g. `"0.5"`, `"15"`).
pub fn edge_label(i: usize) -> String {
    let e = EDGES_MM[i];
    if e.fract() == 0.0 {
        format!("{e:.0}")
    } else {
        format!("{e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_bin_colour_classifies_as_itself_at_any_shade() {
        for (i, c) in COLOURS.iter().enumerate() {
            for shade in [0.35, 0.5, 0.75, 1.0] {
                let s = c.map(|v| (f64::from(v) * shade).round() as u8);
                assert_eq!(classify(s), Some(i), "bin {i} at shade {shade}: {s:?}");
                // Anti-aliased against white background or grey skin, half and half.
                for grey in [255.0, 0.8 * f64::from(SKIN[0])] {
                    let m = c.map(|v| (0.5 * f64::from(v) * shade + 0.5 * grey).round() as u8);
                    if m.iter().max().unwrap() - m.iter().min().unwrap() >= GREY_CHROMA {
                        assert_eq!(classify(m), Some(i), "bin {i} blended with {grey}: {m:?}");
                    }
                }
            }
        }
        assert_eq!(classify(SKIN), None);
        assert_eq!(classify([0, 0, 0]), None);
    }

    #[test]
    fn bins_follow_the_edges() {
        for (i, &e) in EDGES_MM.iter().enumerate() {
            assert_eq!(bin(e), Some(i));
            assert_eq!(bin(e - 1e-9), i.checked_sub(1));
        }
        assert_eq!(bin(f64::NAN), None);
        assert_eq!(bin(f64::INFINITY), Some(9));
    }
}
