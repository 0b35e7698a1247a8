//! Length units of a face mesh: what one coordinate unit of the input is in millimetres.
//!
//! Mesh files carry no unit. The rig needs one to place muscles in physical sizes (band widths
//! in mm, shortening as a strain of a length in mm), to report displacements in mm and to
//! write glTF in metres. [`Units::Auto`] (the default) estimates it from the face itself: the
//! distance between the centres of the two eye loops is the adult interpupillary distance,
//! 63 mm on average (Dodgson 2004, *Variation and extrema of human interpupillary distance*:
//! mean 63.4 mm, 95 % of adults 54–72 mm), so the unit chosen is the one of
//! [`LengthUnit::ALL`] that makes it closest to 63 mm (by ratio), as long as that is plausible
//! for an adult ([`PLAUSIBLE_INTEROCULAR_MM`]); a face in model units none of them fits (e.g.
//! the Lee Perry-Smith scan, whose eyes are 1.3 units apart) gets [`LengthUnit::Scaled`], the
//! scale that puts its eyes 63 mm apart. Three bundled faces are in centimetres and are
//! detected as such.

use serde::{Deserialize, Serialize};

/// Mean adult interpupillary distance in mm: the yardstick of [`Units::Auto`].
pub const MEAN_INTEROCULAR_MM: f64 = 63.0;

/// Interocular distances (mm, after choosing the unit) outside this range are implausible for
/// an adult human face: [`UnitChoice::plausible`] is false (a child's face, a stylised head, or
/// a face in units none of [`LengthUnit::ALL`] fits).
pub const PLAUSIBLE_INTEROCULAR_MM: (f64, f64) = (40.0, 95.0);

/// A length unit of mesh coordinates.
///
/// ```
/// use face_prep::units::LengthUnit;
/// assert_eq!(LengthUnit::Centimetre.mm(), 10.0);
/// assert_eq!(LengthUnit::Inch.metres(), 0.0254);
/// assert_eq!(LengthUnit::parse("cm"), Some(LengthUnit::Centimetre));
/// assert_eq!(LengthUnit::Millimetre.symbol(), "mm");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub enum LengthUnit {
    /// 1 unit = 1 mm.
    Millimetre,
    /// 1 unit = 1 cm.
    Centimetre,
    /// 1 unit = 1 m.
    Metre,
    /// 1 unit = 1 inch (25.4 mm).
    Inch,
    /// Model units of a face none of the others fits: 1 unit = this many mm (estimated).
    Scaled(f64),
}

impl LengthUnit {
    /// Every unit [`Units::Auto`] chooses from.
    pub const ALL: [LengthUnit; 4] = [
        LengthUnit::Millimetre,
        LengthUnit::Centimetre,
        LengthUnit::Metre,
        LengthUnit::Inch,
    ];

    /// Millimetres per unit.
    pub fn mm(self) -> f64 {
        match self {
            LengthUnit::Millimetre => 1.0,
            LengthUnit::Centimetre => 10.0,
            LengthUnit::Metre => 1000.0,
            LengthUnit::Inch => 25.4,
            LengthUnit::Scaled(mm) => mm,
        }
    }

    /// Metres per unit (the scale to glTF, whose unit is the metre).
    pub fn metres(self) -> f64 {
        self.mm() / 1000.0
    }

    /// The unit's symbol: `mm`, `cm`, `m`, `in`, or `units` for [`LengthUnit::Scaled`].
    pub fn symbol(self) -> &'static str {
        match self {
            LengthUnit::Millimetre => "mm",
            LengthUnit::Centimetre => "cm",
            LengthUnit::Metre => "m",
            LengthUnit::Inch => "in",
            LengthUnit::Scaled(_) => "units",
        }
    }

    /// Parses a symbol (`mm`, `cm`, `m`, `in`; also `inch`), case-insensitively.
    pub fn parse(s: &str) -> Option<LengthUnit> {
        match s.to_ascii_lowercase().as_str() {
            "mm" => Some(LengthUnit::Millimetre),
            "cm" => Some(LengthUnit::Centimetre),
            "m" => Some(LengthUnit::Metre),
            "in" | "inch" => Some(LengthUnit::Inch),
            _ => None,
        }
    }
}

impl std::fmt::Display for LengthUnit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            // Four significant digits at any scale: a face written in micrometres-of-a-
            // millimetre showed "1 unit = 0.000 mm" (issue 36).
            LengthUnit::Scaled(mm) if (0.1..1e6).contains(&mm.abs()) => {
                write!(f, "model units (1 unit = {mm:.3} mm)")
            }
            LengthUnit::Scaled(mm) => write!(f, "model units (1 unit = {mm:.3e} mm)"),
            u => f.write_str(u.symbol()),
        }
    }
}

#[cfg(test)]
mod display_tests {
    use super::LengthUnit;

    /// Regression (issue 36): `info` on a face scaled by 1e6 said "1 unit = 0.000 mm".
    #[test]
    fn tiny_and_huge_model_units_keep_their_digits() {
        assert_eq!(
            LengthUnit::Scaled(6.3e-5).to_string(),
            "model units (1 unit = 6.300e-5 mm)"
        );
        assert_eq!(
            LengthUnit::Scaled(2.5e7).to_string(),
            "model units (1 unit = 2.500e7 mm)"
        );
        assert_eq!(
            LengthUnit::Scaled(0.254).to_string(),
            "model units (1 unit = 0.254 mm)"
        );
    }
}

/// How the unit of a face is decided: given by the user, or estimated from the face.
///
/// ```
/// use face_prep::units::{LengthUnit, Units};
/// assert_eq!(Units::parse("auto"), Some(Units::Auto));
/// assert_eq!(Units::parse("in"), Some(Units::Fixed(LengthUnit::Inch)));
/// assert_eq!(Units::default(), Units::Auto);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub enum Units {
    /// Estimated from the distance between the eye-loop centres ([`detect_unit`]).
    #[default]
    Auto,
    /// Given.
    Fixed(LengthUnit),
}

impl Units {
    /// Parses `auto` or a unit symbol ([`LengthUnit::parse`]).
    pub fn parse(s: &str) -> Option<Units> {
        if s.eq_ignore_ascii_case("auto") {
            Some(Units::Auto)
        } else {
            LengthUnit::parse(s).map(Units::Fixed)
        }
    }
}

/// The unit a rig uses, and how it came about.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct UnitChoice {
    /// The unit of the mesh coordinates.
    pub unit: LengthUnit,
    /// True when it was estimated ([`Units::Auto`]), false when given.
    pub detected: bool,
    /// Distance between the eye-loop centres in mm, in that unit.
    pub interocular_mm: f64,
}

impl UnitChoice {
    /// Decides the unit of a face whose eye-loop centres are `interocular` units apart.
    ///
    /// ```
    /// use face_prep::units::{LengthUnit, UnitChoice, Units};
    /// let c = UnitChoice::decide(Units::Auto, 6.1);
    /// assert_eq!(c.unit, LengthUnit::Centimetre);
    /// assert!(c.detected && c.plausible());
    /// let given = UnitChoice::decide(Units::Fixed(LengthUnit::Millimetre), 6.1);
    /// assert!(!given.plausible()); // 6.1 mm between the eyes
    /// ```
    pub fn decide(units: Units, interocular: f64) -> UnitChoice {
        let (unit, detected) = match units {
            Units::Auto => (detect_unit(interocular), true),
            Units::Fixed(u) => (u, false),
        };
        UnitChoice {
            unit,
            detected,
            interocular_mm: interocular * unit.mm(),
        }
    }

    /// Whether the interocular distance is that of an adult human face
    /// ([`PLAUSIBLE_INTEROCULAR_MM`]).
    pub fn plausible(&self) -> bool {
        (PLAUSIBLE_INTEROCULAR_MM.0..=PLAUSIBLE_INTEROCULAR_MM.1).contains(&self.interocular_mm)
    }

    /// One line for reports, e.g. `unit cm (detected: eyes 61.2 mm apart)`.
    pub fn describe(&self) -> String {
        let how = if self.detected { "detected" } else { "given" };
        let mut s = format!(
            "unit {} ({how}: eyes {:.1} mm apart)",
            self.unit, self.interocular_mm
        );
        if !self.plausible() {
            s.push_str(&format!(
                "; an adult's are {:.0}–{:.0} mm: check --units",
                PLAUSIBLE_INTEROCULAR_MM.0, PLAUSIBLE_INTEROCULAR_MM.1
            ));
        }
        s
    }
}

/// The unit of [`LengthUnit::ALL`] that brings an interocular distance of `interocular` units
/// closest, by ratio, to [`MEAN_INTEROCULAR_MM`], if that distance is then plausible
/// ([`PLAUSIBLE_INTEROCULAR_MM`]); otherwise [`LengthUnit::Scaled`] to exactly 63 mm.
/// Non-finite or non-positive distances give centimetres (the unit of most bundled faces).
///
/// ```
/// use face_prep::units::{LengthUnit, detect_unit};
/// assert_eq!(detect_unit(63.0), LengthUnit::Millimetre);
/// assert_eq!(detect_unit(6.3), LengthUnit::Centimetre);
/// assert_eq!(detect_unit(0.063), LengthUnit::Metre);
/// assert_eq!(detect_unit(2.48), LengthUnit::Inch);
/// assert_eq!(detect_unit(1.26), LengthUnit::Scaled(50.0)); // 1.26 cm or in: no adult
/// ```
pub fn detect_unit(interocular: f64) -> LengthUnit {
    if !(interocular.is_finite() && interocular > 0.0) {
        return LengthUnit::Centimetre;
    }
    let misfit = |u: LengthUnit| (interocular * u.mm() / MEAN_INTEROCULAR_MM).ln().abs();
    let best = LengthUnit::ALL
        .into_iter()
        .min_by(|a, b| misfit(*a).total_cmp(&misfit(*b)))
        .unwrap_or(LengthUnit::Centimetre);
    let mm = interocular * best.mm();
    if (PLAUSIBLE_INTEROCULAR_MM.0..=PLAUSIBLE_INTEROCULAR_MM.1).contains(&mm) {
        best
    } else {
        LengthUnit::Scaled(MEAN_INTEROCULAR_MM / interocular)
    }
}
