//! Named expression sets of other tools: Apple ARKit's 52 blendshape names ([`arkit`]) and the
//! VRM 1.0 expression presets ([`vrm`]), each a documented linear combination of the rig's
//! controls with the FACS action units it stands for.
//!
//! A definition names controls by their id (the agreed ids, [`AGREED_CONTROL_IDS`]) with a
//! slider value in [−1, 1] (−1 = full activation, as everywhere in facebem). It is resolved
//! against the controls a rig actually has ([`NamedExpression::resolve`]):
//!
//! - every control present: the expression as defined;
//! - some controls missing: the expression from the controls present, with the missing ones
//!   listed ([`Resolved::missing`]) — e.g. the viseme `aa` on a rig without a jaw is only its lip
//!   shape; the export and `pose` say so;
//! - all controls missing: the expression is not available ([`NamedExpression::resolve`] gives
//!   `None`); an export leaves it out and lists it in `meshes[0].extras.leftOutTargets`.
//!
//! So the same tables serve a rig with ten muscles and one with jaw, eyelids and the full set.
//! Names a face mesh cannot have at all (ARKit's eight `eyeLook*` and VRM's `look*`: no eyeballs;
//! ARKit's `tongueOut`: no tongue) are listed with the reason in [`NOT_MODELLED`].
//!
//! Left and right follow each standard: ARKit's `…Left` and VRM's `blinkLeft` are the subject's
//! own left, which is facebem's `_l` (+x in the canonical frame, the face looking toward +z).
//!
//! The VRM emotions `happy`, `angry`, `sad`, `surprised` and `neutral` are facebem's own presets
//! of the same name ([`crate::expressions::presets`]): one definition, so `pose --preset happy` and the
//! exported `happy` target are the same shape.
//!
//! ```
//! use facebem::expressions;
//! let smile = expressions::find("mouthSmileLeft").unwrap();
//! let ids = vec!["zygomaticus_major_l".to_string(), "zygomaticus_major_r".to_string()];
//! let r = smile.resolve(&ids).unwrap();
//! assert_eq!(r.sliders, vec![-1.0, 0.0]);
//! assert!(r.missing.is_empty());
//! // A blink needs an eyelid control this rig does not have.
//! assert!(expressions::find("eyeBlinkLeft").unwrap().resolve(&ids).is_none());
//! ```

pub mod arkit;
mod arkit_fitted;
pub mod vrm;

pub mod presets;

/// The naming standard an expression belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum NameSet {
    /// facebem's own targets: `<muscle id>_contract`/`_relax` and `preset_<name>`.
    Facebem,
    /// Apple ARKit blendshape names (`ARFaceAnchor.BlendShapeLocation`, e.g. `mouthSmileLeft`).
    Arkit,
    /// VRM 1.0 expression presets (`VRMC_vrm.expressions.preset`, e.g. `happy`, `aa`).
    Vrm,
}

impl NameSet {
    /// Lower-case name used on the command line (`facebem`, `arkit`, `vrm`).
    pub fn id(self) -> &'static str {
        match self {
            NameSet::Facebem => "facebem",
            NameSet::Arkit => "arkit",
            NameSet::Vrm => "vrm",
        }
    }

    /// Name for people (`facebem`, `ARKit`, `VRM 1.0`).
    pub fn display_name(self) -> &'static str {
        match self {
            NameSet::Facebem => "facebem",
            NameSet::Arkit => "ARKit",
            NameSet::Vrm => "VRM 1.0",
        }
    }

    /// Number of names the standard defines (ARKit 52, VRM 1.0 18; facebem: none fixed).
    pub fn standard_size(self) -> usize {
        match self {
            NameSet::Facebem => 0,
            NameSet::Arkit => arkit::NAMES.len(),
            NameSet::Vrm => vrm::NAMES.len(),
        }
    }
}

/// Which name sets an export writes (`--names facebem|arkit|vrm|all`, comma-separated
/// combinations allowed). Default: [`NameSets::USERS`], ARKit and VRM: the names tools consume.
///
/// ```
/// use facebem::expressions::NameSets;
/// assert_eq!(NameSets::parse("all"), Ok(NameSets::ALL));
/// assert_eq!(NameSets::default(), NameSets::parse("arkit,vrm").unwrap());
/// let s = NameSets::parse("arkit,vrm").unwrap();
/// assert!(s.arkit && s.vrm && !s.facebem);
/// assert!(NameSets::parse("blender").is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NameSets {
    /// facebem's muscle and preset targets.
    pub facebem: bool,
    /// ARKit-named targets.
    pub arkit: bool,
    /// VRM-named targets.
    pub vrm: bool,
}

impl Default for NameSets {
    fn default() -> Self {
        NameSets::USERS
    }
}

impl NameSets {
    /// Every set.
    pub const ALL: NameSets = NameSets {
        facebem: true,
        arkit: true,
        vrm: true,
    };
    /// ARKit and VRM: what avatars, engines and face-capture apps consume (the default; issue
    /// 34: facebem's own muscle targets mostly repeat them and tripled the file).
    pub const USERS: NameSets = NameSets {
        facebem: false,
        arkit: true,
        vrm: true,
    };
    /// facebem's own targets only (the export before named sets existed).
    pub const FACEBEM: NameSets = NameSets {
        facebem: true,
        arkit: false,
        vrm: false,
    };

    /// Parses `facebem`, `arkit`, `vrm`, `all` or a comma-separated list of them
    /// (case-insensitive).
    pub fn parse(s: &str) -> Result<NameSets, String> {
        let mut out = NameSets {
            facebem: false,
            arkit: false,
            vrm: false,
        };
        for part in s.split(',').map(str::trim) {
            match part.to_ascii_lowercase().as_str() {
                "all" => out = NameSets::ALL,
                "facebem" => out.facebem = true,
                "arkit" => out.arkit = true,
                "vrm" => out.vrm = true,
                _ => {
                    return Err(format!(
                        "unknown name set {part:?}: use facebem, arkit, vrm or all"
                    ));
                }
            }
        }
        Ok(out)
    }

    /// Whether `set` is included.
    pub fn contains(&self, set: NameSet) -> bool {
        match set {
            NameSet::Facebem => self.facebem,
            NameSet::Arkit => self.arkit,
            NameSet::Vrm => self.vrm,
        }
    }
}

/// How a named expression is made from the rig's controls.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Definition {
    /// Slider values of control ids ([`AGREED_CONTROL_IDS`]); controls not named are 0.
    Terms(&'static [(&'static str, f64)]),
    /// facebem's own preset of this name ([`crate::expressions::presets::find`]).
    Preset(&'static str),
    /// Slider values fitted to a captured expression (`terms`, used when the rig has every
    /// control they name), and the hand-made recipe for a rig that lacks one (`fallback`,
    /// resolved as [`Definition::Terms`]). See [`arkit`]'s calibration.
    Fitted {
        /// The fitted recipe.
        terms: &'static [(&'static str, f64)],
        /// The hand-made recipe.
        fallback: &'static [(&'static str, f64)],
    },
}

/// One named expression of a standard.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NamedExpression {
    /// The standard's exact name (e.g. `mouthSmileLeft`, `aa`).
    pub name: &'static str,
    /// The standard it belongs to.
    pub set: NameSet,
    /// FACS action units it stands for (for a [`Definition::Preset`], see the preset's own).
    pub action_units: &'static str,
    /// What it does, in words.
    pub description: &'static str,
    /// The linear combination of controls.
    pub definition: Definition,
}

/// A named expression resolved against a rig's controls.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolved {
    /// One slider value per control of the rig, in the rig's order.
    pub sliders: Vec<f64>,
    /// Controls of the definition the rig does not have (left at 0).
    pub missing: Vec<&'static str>,
}

impl NamedExpression {
    /// The control ids the definition uses (empty for a preset or `neutral`; a fitted recipe's
    /// hand-made one, whose controls decide whether a rig can make it at all).
    pub fn controls(&self) -> Vec<&'static str> {
        match self.definition {
            Definition::Terms(terms)
            | Definition::Fitted {
                fallback: terms, ..
            } => terms.iter().map(|(id, _)| *id).collect(),
            Definition::Preset(_) => Vec::new(),
        }
    }

    /// FACS action units: the table's, or the preset's for a [`Definition::Preset`].
    pub fn action_units(&self) -> &'static str {
        match self.definition {
            Definition::Preset(name) => {
                presets::find(name).map_or(self.action_units, |p| p.action_units)
            }
            Definition::Terms(_) | Definition::Fitted { .. } => self.action_units,
        }
    }

    /// Resolves the expression for a rig whose controls are `control_ids` (e.g.
    /// [`crate::MuscleBasis::muscle_ids`]): `None` when the definition has controls and none of
    /// them is in the rig. Control ids are matched case-insensitively.
    pub fn resolve(&self, control_ids: &[String]) -> Option<Resolved> {
        match self.definition {
            Definition::Preset(name) => {
                let preset = presets::find(name)?;
                Some(Resolved {
                    sliders: preset.sliders_for(control_ids),
                    missing: Vec::new(),
                })
            }
            Definition::Fitted { terms, fallback } => {
                let has = |id: &str| control_ids.iter().any(|c| c.eq_ignore_ascii_case(id));
                let chosen = if terms.iter().all(|(id, _)| has(id)) {
                    terms
                } else {
                    fallback
                };
                Self::resolve_terms(chosen, control_ids)
            }
            Definition::Terms(terms) => Self::resolve_terms(terms, control_ids),
        }
    }

    /// [`Self::resolve`] of a [`Definition::Terms`].
    fn resolve_terms(
        terms: &'static [(&'static str, f64)],
        control_ids: &[String],
    ) -> Option<Resolved> {
        let mut sliders = vec![0.0; control_ids.len()];
        let mut missing = Vec::new();
        for &(id, value) in terms {
            match control_ids.iter().position(|c| c.eq_ignore_ascii_case(id)) {
                Some(k) => sliders[k] = value,
                None => missing.push(id),
            }
        }
        if !terms.is_empty() && missing.len() == terms.len() {
            None
        } else {
            Some(Resolved { sliders, missing })
        }
    }
}

/// The control of the other side with the slider value that makes the mirrored motion:
/// `_l` ↔ `_r`, `jaw_lateral` negated, unpaired controls as they are.
///
/// ```
/// use facebem::expressions::mirrored_control;
/// assert_eq!(mirrored_control("risorius_l", -0.5), ("risorius_r".to_string(), -0.5));
/// assert_eq!(mirrored_control("jaw_lateral", -1.0), ("jaw_lateral".to_string(), 1.0));
/// assert_eq!(mirrored_control("procerus", -0.2), ("procerus".to_string(), -0.2));
/// ```
pub fn mirrored_control(id: &str, value: f64) -> (String, f64) {
    if id == "jaw_lateral" {
        (id.to_string(), -value)
    } else if let Some(stem) = id.strip_suffix("_l") {
        (format!("{stem}_r"), value)
    } else if let Some(stem) = id.strip_suffix("_r") {
        (format!("{stem}_l"), value)
    } else {
        (id.to_string(), value)
    }
}

/// Every named expression facebem defines: the ARKit ones ([`arkit::EXPRESSIONS`]) then the VRM
/// ones ([`vrm::EXPRESSIONS`]), the order of an export.
pub fn all() -> impl Iterator<Item = &'static NamedExpression> {
    arkit::EXPRESSIONS.iter().chain(vrm::EXPRESSIONS.iter())
}

/// The expressions of one set (empty for [`NameSet::Facebem`]).
pub fn of_set(set: NameSet) -> &'static [NamedExpression] {
    match set {
        NameSet::Facebem => &[],
        NameSet::Arkit => &arkit::EXPRESSIONS,
        NameSet::Vrm => &vrm::EXPRESSIONS,
    }
}

/// Finds a named expression by its exact name, ignoring ASCII case and surrounding spaces
/// (ARKit first: no name is in both standards); ARKit's raw location strings (`eyeBlink_L`,
/// [`arkit::raw_name`]) name their expressions too.
pub fn find(name: &str) -> Option<&'static NamedExpression> {
    let name = arkit::from_raw(name).unwrap_or(name.trim());
    all().find(|e| e.name.eq_ignore_ascii_case(name))
}

/// The standard name and the reason when `name` (any ASCII case; ARKit's raw spelling too) is
/// one facebem cannot make ([`NOT_MODELLED`]).
///
/// ```
/// use facebem::expressions::not_modelled;
/// assert_eq!(not_modelled("eyeLookUp_L"), Some(("eyeLookUpLeft", "no eyeballs")));
/// assert_eq!(not_modelled("TONGUEOUT"), Some(("tongueOut", "no tongue")));
/// assert_eq!(not_modelled("eyeBlinkLeft"), None);
/// ```
pub fn not_modelled(name: &str) -> Option<(&'static str, &'static str)> {
    let name = arkit::from_raw(name).unwrap_or(name.trim());
    NOT_MODELLED
        .iter()
        .copied()
        .find(|(n, _)| n.eq_ignore_ascii_case(name))
}

/// Names of a standard facebem cannot make, with the reason.
pub const NOT_MODELLED: [(&str, &str); 13] = [
    ("eyeLookDownLeft", "no eyeballs"),
    ("eyeLookDownRight", "no eyeballs"),
    ("eyeLookInLeft", "no eyeballs"),
    ("eyeLookInRight", "no eyeballs"),
    ("eyeLookOutLeft", "no eyeballs"),
    ("eyeLookOutRight", "no eyeballs"),
    ("eyeLookUpLeft", "no eyeballs"),
    ("eyeLookUpRight", "no eyeballs"),
    ("tongueOut", "no tongue"),
    ("lookUp", "no eyeballs"),
    ("lookDown", "no eyeballs"),
    ("lookLeft", "no eyeballs"),
    ("lookRight", "no eyeballs"),
];

/// The control ids agreed for the whole face (the ten thesis muscles, jaw, eyelids and the
/// further muscles), the only ids the definitions use. A rig has some of them (see the module
/// docs). Slider signs: −1 contracts (jaw: opens, protrudes, shifts the chin to the face's left;
/// eyelids: blink, squint, wide; orbicularis oris: pucker).
pub const AGREED_CONTROL_IDS: [&str; 44] = [
    "frontalis_l",
    "frontalis_r",
    "levator_labii_superioris_l",
    "levator_labii_superioris_r",
    "zygomaticus_major_l",
    "zygomaticus_major_r",
    "mentalis_l",
    "mentalis_r",
    "depressor_labii_inferioris_l",
    "depressor_labii_inferioris_r",
    "jaw_open",
    "jaw_forward",
    "jaw_lateral",
    "orbicularis_oculi_palpebral_l",
    "orbicularis_oculi_palpebral_r",
    "orbicularis_oculi_orbital_l",
    "orbicularis_oculi_orbital_r",
    "levator_palpebrae_l",
    "levator_palpebrae_r",
    "orbicularis_oris_upper",
    "orbicularis_oris_lower",
    "depressor_anguli_oris_l",
    "depressor_anguli_oris_r",
    "corrugator_supercilii_l",
    "corrugator_supercilii_r",
    "procerus",
    "risorius_l",
    "risorius_r",
    "levator_labii_superioris_alaeque_nasi_l",
    "levator_labii_superioris_alaeque_nasi_r",
    "zygomaticus_minor_l",
    "zygomaticus_minor_r",
    "levator_anguli_oris_l",
    "levator_anguli_oris_r",
    "buccinator_l",
    "buccinator_r",
    "cheek_puff",
    "lip_seal",
    "orbicularis_oculi_malar_l",
    "orbicularis_oculi_malar_r",
    "orbicularis_oris_marginal_upper",
    "orbicularis_oris_marginal_lower",
    "orbicularis_oculi_superior_l",
    "orbicularis_oculi_superior_r",
];

/// A named expression resolved for one rig, ready to export or pose.
#[derive(Clone, Debug, PartialEq)]
pub struct RigExpression {
    /// The expression.
    pub expression: &'static NamedExpression,
    /// Its sliders and missing controls on this rig.
    pub resolved: Resolved,
}

/// The expressions of `sets` a rig with `control_ids` can make, in export order (ARKit then
/// VRM), and those it cannot: each with the controls it lacks.
pub fn for_rig(
    sets: NameSets,
    control_ids: &[String],
) -> (
    Vec<RigExpression>,
    Vec<(&'static NamedExpression, Vec<&'static str>)>,
) {
    let mut made = Vec::new();
    let mut left_out = Vec::new();
    for e in all().filter(|e| sets.contains(e.set)) {
        match e.resolve(control_ids) {
            Some(resolved) => made.push(RigExpression {
                expression: e,
                resolved,
            }),
            None => left_out.push((e, e.controls())),
        }
    }
    (made, left_out)
}

/// Errors looking up an expression by name for a rig.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum LookupError {
    /// No facebem preset, ARKit name or VRM preset has this name.
    #[error("unknown preset or expression name {0:?}")]
    Unknown(String),
    /// A standard name facebem cannot make ([`NOT_MODELLED`]).
    #[error("{name} is not modelled: the face has {reason} (facebem moves the skin only)")]
    NotModelled {
        /// The standard's name.
        name: &'static str,
        /// Why ("no eyeballs", "no tongue").
        reason: &'static str,
    },
    /// The expression exists, but the rig has none of its controls.
    #[error("{name} needs controls this rig does not have: {}", missing.join(", "))]
    NoControls {
        /// The expression's name.
        name: &'static str,
        /// Its controls.
        missing: Vec<&'static str>,
    },
}

/// Sliders for `name` on a rig with `control_ids`: a facebem preset (or alias) first, then an
/// ARKit name, then a VRM preset — the names `pose --preset` accepts. The second value lists the
/// expression's controls the rig lacks (they stay 0).
pub fn sliders_for_name(
    name: &str,
    control_ids: &[String],
) -> Result<(Vec<f64>, Vec<&'static str>), LookupError> {
    if let Some(p) = presets::find(name) {
        return Ok((p.sliders_for(control_ids), Vec::new()));
    }
    if let Some((name, reason)) = not_modelled(name) {
        return Err(LookupError::NotModelled { name, reason });
    }
    let e = find(name).ok_or_else(|| LookupError::Unknown(name.trim().to_string()))?;
    let r = e
        .resolve(control_ids)
        .ok_or_else(|| LookupError::NoControls {
            name: e.name,
            missing: e.controls(),
        })?;
    Ok((r.sliders, r.missing))
}

#[cfg(test)]
mod tests;

/// The expression a corrective shape is defined over, when `name` is one: ARKit's `mouthClose`
/// is added to `jawOpen` (the lips together over the open jaw; alone it lifts the lower lip
/// through the upper one, as ICT-FaceKit's capture of it does). A corrective is drawn and judged
/// on top of its base; it is exported and posed as it is.
///
/// ```
/// use facebem::expressions::corrective_base;
/// assert_eq!(corrective_base("mouthClose"), Some("jawOpen"));
/// assert_eq!(corrective_base("jawOpen"), None);
/// ```
pub fn corrective_base(name: &str) -> Option<&'static str> {
    (name == "mouthClose").then_some("jawOpen")
}
