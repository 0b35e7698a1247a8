//! Whether a computed rig can be trusted: the documented thresholds past which the command line
//! refuses to write a rig, a pose or an export (unless forced) and the viewer shows the rig in
//! red. Every threshold is far outside what a healthy rig of the bundled faces reaches, and
//! far inside what a broken one does (`docs/design/solve.md`, "Trust").

use super::{FaceModel, SUSPICIOUS_AMPLIFICATION};
use face_prep::{Generator, MuscleKind};

/// Largest motion, mm, of any control but the jaw's: no facial muscle moves skin further (the
/// bundled faces' controls other than the jaw's: 12.9–13.8 mm at most,
/// `cargo run --release -p facebem-tools --bin trust_report`).
pub const MAX_MOTION_OUTSIDE_JAW_MM: f64 = 60.0;

/// Largest motion, mm, of a jaw control: the mandible rotates about 25° at most, and its farthest
/// skin, the chin, lies 100–130 mm from the condyles, so no point of a jaw response moves
/// further than about 60 mm (the bundled faces' jaw_open: 43–50 mm at most).
pub const MAX_JAW_MOTION_MM: f64 = 100.0;

/// A muscle band's largest motion over its largest shortening (strain × length) above this is
/// not the muscle's doing: the skin a muscle pulls moves at most about as far as the muscle
/// shortens (1.00–1.02 at most on the bundled faces).
pub const MAX_MOTION_PER_SHORTENING: f64 = 3.0;

/// Why a rig is not to be trusted: one line per cause, empty for a rig within every threshold.
///
/// The causes: a near-singular solve ([`crate::PrecomputeReport::response_amplification`] above
/// [`SUSPICIOUS_AMPLIFICATION`]), a shell that crosses itself, a control whose largest motion
/// is past [`MAX_MOTION_OUTSIDE_JAW_MM`] (or [`MAX_JAW_MOTION_MM`] for the jaw) or past
/// [`MAX_MOTION_PER_SHORTENING`] times its muscle's shortening, and a field that is not finite.
///
/// ```no_run
/// let (model, _) = facebem::input::default_model(None, &facebem::Control::new())?;
/// assert!(facebem::model::distrust(&model).is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn distrust(model: &FaceModel) -> Vec<String> {
    let mut out = Vec::new();
    let report = &model.report;
    if report.response_amplification > SUSPICIOUS_AMPLIFICATION {
        out.push(format!(
            "near-singular solve: a response moves the face {:.0} times more than its muscle \
             (trusted below {SUSPICIOUS_AMPLIFICATION:.0})",
            report.response_amplification
        ));
    }
    if report.shell_self_intersections > 0 {
        out.push(format!(
            "the elastic shell crosses itself ({} element pairs)",
            report.shell_self_intersections
        ));
    }
    let mm_per_unit = model.rig.mm_per_unit();
    for (k, id) in model.basis.muscle_ids.iter().enumerate() {
        let Some(field) = model.basis.displacements.get(k) else {
            continue;
        };
        let largest_mm = field.iter().map(|d| d.length()).fold(0.0, |a: f64, b| {
            if b.is_nan() { f64::INFINITY } else { a.max(b) }
        }) * mm_per_unit;
        let kind = model.rig.muscles.get(k).and_then(|m| m.kind);
        if let Some(cause) = motion_cause(model, kind, largest_mm) {
            out.push(format!("{id}: {cause}"));
        }
    }
    out
}

/// The largest shortening, mm, of control `kind`'s muscle band on `model`'s face (its strain ×
/// its origin-to-insertion length); `None` for a control that is not a muscle band.
pub fn shortening_mm(model: &FaceModel, kind: MuscleKind) -> Option<f64> {
    let a = face_prep::muscle_kind::attachment(kind, &model.rig.boxes)?;
    Some(a.max_strain * (a.origin - a.insertion).length() * model.rig.mm_per_unit())
}

/// Why a control whose largest motion is `largest_mm` is not trusted, if it is not.
fn motion_cause(model: &FaceModel, kind: Option<MuscleKind>, largest_mm: f64) -> Option<String> {
    if !largest_mm.is_finite() {
        return Some("its motion is not finite".to_string());
    }
    let jaw = kind.is_some_and(|k| matches!(k.generator(), Generator::Jaw(_)));
    let limit_mm = if jaw {
        MAX_JAW_MOTION_MM
    } else {
        MAX_MOTION_OUTSIDE_JAW_MM
    };
    if largest_mm > limit_mm {
        return Some(format!(
            "moves the skin {largest_mm:.0} mm (trusted up to {limit_mm:.0} mm)"
        ));
    }
    let shortening_mm = shortening_mm(model, kind?)?;
    (shortening_mm > 0.0 && largest_mm > MAX_MOTION_PER_SHORTENING * shortening_mm).then(|| {
        format!(
            "moves the skin {largest_mm:.0} mm, {:.1} times its muscle's shortening \
             (trusted up to {MAX_MOTION_PER_SHORTENING:.0} times)",
            largest_mm / shortening_mm
        )
    })
}
