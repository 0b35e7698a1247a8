use super::*;

fn ids(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

/// The ten thesis muscles (the rig before jaw, eyelids and the further muscles).
const TEN: [&str; 10] = [
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
];

fn check_set(names: &[&str], expressions: &[NamedExpression], set: NameSet) {
    let mut seen = std::collections::HashSet::new();
    assert!(names.iter().all(|n| seen.insert(*n)), "duplicate name");
    // Defined names are the standard's, in its order; the rest are the not-modelled ones.
    let defined: Vec<&str> = expressions.iter().map(|e| e.name).collect();
    let expected: Vec<&str> = names
        .iter()
        .copied()
        .filter(|n| !NOT_MODELLED.iter().any(|(m, _)| m == n))
        .collect();
    assert_eq!(defined, expected);
    assert!(expressions.iter().all(|e| e.set == set));
}

#[test]
fn tables_cover_each_standard_except_what_needs_eyeballs_or_a_tongue() {
    check_set(&arkit::NAMES, &arkit::EXPRESSIONS, NameSet::Arkit);
    check_set(&vrm::NAMES, &vrm::EXPRESSIONS, NameSet::Vrm);
    assert_eq!(arkit::EXPRESSIONS.len(), 43);
    assert_eq!(vrm::EXPRESSIONS.len(), 14);
    // No name is in both standards, and none is one of facebem's own target names.
    for a in arkit::NAMES {
        assert!(!vrm::NAMES.iter().any(|v| v.eq_ignore_ascii_case(a)), "{a}");
        assert!(!a.starts_with("preset_") && !a.ends_with("_contract") && !a.ends_with("_relax"));
    }
    for (name, _) in NOT_MODELLED {
        assert!(arkit::NAMES.contains(&name) || vrm::NAMES.contains(&name));
    }
}

#[test]
fn definitions_use_agreed_ids_once_with_values_in_range() {
    for e in all() {
        match e.definition {
            Definition::Terms(_) | Definition::Fitted { .. } => {
                assert!(!e.action_units.is_empty(), "{}", e.name);
                for terms in recipes(e) {
                    for (k, (id, v)) in terms.iter().enumerate() {
                        assert!(AGREED_CONTROL_IDS.contains(id), "{}: {id}", e.name);
                        assert!((-1.0..=1.0).contains(v) && *v != 0.0, "{}: {id}", e.name);
                        assert!(!terms[..k].iter().any(|(j, _)| j == id), "{}: {id}", e.name);
                    }
                }
            }
            Definition::Preset(name) => {
                assert_eq!(name, e.name);
                let p = crate::expressions::presets::find(name).expect("a facebem preset");
                assert_eq!(e.action_units(), p.action_units);
            }
        }
    }
}

/// The control of the other side with the value that means the mirrored motion.
fn mirror((id, v): (&str, f64)) -> (String, f64) {
    mirrored_control(id, v)
}

fn sorted_terms(terms: impl Iterator<Item = (String, f64)>) -> Vec<(String, f64)> {
    let mut t: Vec<(String, f64)> = terms.collect();
    t.sort_by(|a, b| a.0.cmp(&b.0));
    t
}

/// Every recipe of a slider combination: its terms, or a fitted one's terms and fallback.
fn recipes(e: &NamedExpression) -> Vec<&'static [(&'static str, f64)]> {
    match e.definition {
        Definition::Terms(t) => vec![t],
        Definition::Fitted { terms, fallback } => vec![terms, fallback],
        Definition::Preset(_) => panic!("{} is not a slider combination", e.name),
    }
}

#[test]
fn left_and_right_are_exact_mirrors() {
    let mut pairs = 0;
    for e in all() {
        let Some(stem) = e.name.strip_suffix("Left") else {
            continue;
        };
        let right = find(&format!("{stem}Right")).expect("a Right for every Left");
        for (l, r) in recipes(e).into_iter().zip(recipes(right)) {
            let mirrored = sorted_terms(l.iter().map(|&t| mirror(t)));
            let right_terms = sorted_terms(r.iter().map(|(id, v)| (id.to_string(), *v)));
            assert_eq!(mirrored, right_terms, "{} vs {}", e.name, right.name);
        }
        pairs += 1;
    }
    // ARKit: 16 Left/Right pairs among the 43 (brow down/outer up, cheek squint, eye blink/
    // squint/wide, jaw, mouth dimple/frown/lower down/press/sideways/smile/stretch/upper up,
    // nose sneer); VRM: blink.
    assert_eq!(pairs, 16 + 1);
    // A Left name with a `_l`/`_r` control uses the subject's left: `_l`, never `_r`.
    for e in all().filter(|e| e.name.ends_with("Left")) {
        let paired: Vec<&str> = e
            .controls()
            .into_iter()
            .filter(|id| id.ends_with("_l") || id.ends_with("_r"))
            .collect();
        let fitted = match e.definition {
            Definition::Fitted { terms, .. } => terms.iter().map(|(id, _)| *id).collect(),
            _ => Vec::new(),
        };
        let paired_fitted = fitted
            .iter()
            .filter(|id| id.ends_with("_l") || id.ends_with("_r"));
        if e.name != "mouthLeft" {
            assert!(paired.iter().all(|id| id.ends_with("_l")), "{}", e.name);
            assert!(
                paired_fitted.clone().all(|id| id.ends_with("_l")),
                "{}",
                e.name
            );
        }
    }
}

#[test]
fn with_every_agreed_control_all_57_expressions_are_complete() {
    let all_ids = ids(&AGREED_CONTROL_IDS);
    let (made, left_out) = for_rig(NameSets::ALL, &all_ids);
    assert!(left_out.is_empty(), "{left_out:?}");
    assert!(made.iter().all(|m| m.resolved.missing.is_empty()));
    let count = |set| made.iter().filter(|m| m.expression.set == set).count();
    assert_eq!((count(NameSet::Arkit), count(NameSet::Vrm)), (43, 14));
}

#[test]
fn with_the_ten_thesis_muscles_the_expressions_without_them_are_left_out() {
    let ten = ids(&TEN);
    let (made, left_out) = for_rig(NameSets::ALL, &ten);
    let names: Vec<&str> = made.iter().map(|m| m.expression.name).collect();
    for n in [
        "mouthSmileLeft",
        "browOuterUpRight",
        "mouthShrugLower",
        "happy",
        "neutral",
    ] {
        assert!(names.contains(&n), "{n}: {names:?}");
    }
    for n in [
        "eyeBlinkLeft",
        "jawOpen",
        "mouthPucker",
        "blink",
        "ou",
        "oh",
    ] {
        assert!(left_out.iter().any(|(e, _)| e.name == n), "{n}");
        assert!(!names.contains(&n), "{n}");
    }
    // Partial: aa is its lip shape without the jaw, and says so.
    let aa = made.iter().find(|m| m.expression.name == "aa").unwrap();
    assert_eq!(aa.resolved.missing, vec!["jaw_open"]);
    assert_eq!(made.len() + left_out.len(), 57);
    // Exactly what the tables say: an expression is made iff one of its controls is there.
    for e in all() {
        let has_one = e.controls().is_empty() || e.controls().iter().any(|c| TEN.contains(c));
        assert_eq!(names.contains(&e.name), has_one, "{}", e.name);
    }
}

#[test]
fn sliders_go_to_the_rigs_own_order() {
    // A rig without the fitted smile's other controls gets the hand-made recipe.
    let rig = ids(&["zygomaticus_major_r", "jaw_open", "zygomaticus_major_l"]);
    let r = find("MOUTHSMILELEFT").unwrap().resolve(&rig).unwrap();
    assert_eq!(r.sliders, vec![0.0, 0.0, -1.0]);
    // With every control, the fitted recipe, in the rig's order.
    let all_ids = ids(&AGREED_CONTROL_IDS);
    let smile = find("mouthSmileLeft").unwrap();
    let Definition::Fitted { terms, .. } = smile.definition else {
        panic!("the smile is fitted");
    };
    let r = smile.resolve(&all_ids).unwrap();
    assert!(r.missing.is_empty());
    assert_eq!(r.sliders.iter().filter(|v| **v != 0.0).count(), terms.len());
    for (id, v) in terms {
        let k = AGREED_CONTROL_IDS.iter().position(|c| c == id).unwrap();
        assert_eq!(r.sliders[k], *v, "{id}");
    }
    let r = find(" aa ").unwrap().resolve(&rig).unwrap();
    assert_eq!(r.sliders, vec![0.0, -0.7, 0.0]);
    assert_eq!(r.missing.len(), 4);
}

#[test]
fn lookup_prefers_facebem_presets_then_arkit_then_vrm() {
    let ten = ids(&TEN);
    let happy = crate::expressions::presets::find("happy")
        .unwrap()
        .sliders_for(&ten);
    assert_eq!(sliders_for_name("happy", &ten), Ok((happy, vec![])));
    assert_eq!(
        sliders_for_name("hate", &ten).map(|r| r.0),
        Ok(crate::expressions::presets::find("disgust")
            .unwrap()
            .sliders_for(&ten))
    );
    let (s, missing) = sliders_for_name("mouthSmileRight", &ten).unwrap();
    assert_eq!(s[5], -1.0);
    assert_eq!(s.iter().filter(|v| **v != 0.0).count(), 1);
    assert!(missing.is_empty());
    assert_eq!(
        sliders_for_name("blinkLeft", &ten),
        Err(LookupError::NoControls {
            name: "blinkLeft",
            missing: vec!["orbicularis_oculi_palpebral_l"],
        })
    );
    assert_eq!(
        sliders_for_name("grin", &ten),
        Err(LookupError::Unknown("grin".into()))
    );
}

#[test]
fn name_sets_parse() {
    assert_eq!(NameSets::parse("ALL"), Ok(NameSets::ALL));
    assert_eq!(NameSets::parse("facebem"), Ok(NameSets::FACEBEM));
    let v = NameSets::parse(" vrm ").unwrap();
    assert!(v.vrm && !v.arkit && !v.facebem);
    assert!(NameSets::parse("arkit,,vrm").is_err());
    assert_eq!(NameSets::default(), NameSets::USERS);
}

/// ARKit's raw location strings (`ARFaceAnchor.BlendShapeLocation.rawValue`, what Live Link
/// Face and Face Cap send), in the order of [`arkit::NAMES`].
const RAW: [&str; 52] = [
    "browDown_L",
    "browDown_R",
    "browInnerUp",
    "browOuterUp_L",
    "browOuterUp_R",
    "cheekPuff",
    "cheekSquint_L",
    "cheekSquint_R",
    "eyeBlink_L",
    "eyeBlink_R",
    "eyeLookDown_L",
    "eyeLookDown_R",
    "eyeLookIn_L",
    "eyeLookIn_R",
    "eyeLookOut_L",
    "eyeLookOut_R",
    "eyeLookUp_L",
    "eyeLookUp_R",
    "eyeSquint_L",
    "eyeSquint_R",
    "eyeWide_L",
    "eyeWide_R",
    "jawForward",
    "jawLeft",
    "jawOpen",
    "jawRight",
    "mouthClose",
    "mouthDimple_L",
    "mouthDimple_R",
    "mouthFrown_L",
    "mouthFrown_R",
    "mouthFunnel",
    "mouthLeft",
    "mouthLowerDown_L",
    "mouthLowerDown_R",
    "mouthPress_L",
    "mouthPress_R",
    "mouthPucker",
    "mouthRight",
    "mouthRollLower",
    "mouthRollUpper",
    "mouthShrugLower",
    "mouthShrugUpper",
    "mouthSmile_L",
    "mouthSmile_R",
    "mouthStretch_L",
    "mouthStretch_R",
    "mouthUpperUp_L",
    "mouthUpperUp_R",
    "noseSneer_L",
    "noseSneer_R",
    "tongueOut",
];

/// Issue 34, item 5: every ARKit name has its raw spelling, and the raw spelling finds the same
/// expression (or the same reason it is not modelled).
#[test]
fn arkit_raw_names_match_arkits_strings_and_find_the_same_expression() {
    for (name, raw) in arkit::NAMES.iter().zip(RAW) {
        assert_eq!(arkit::raw_name(name).as_deref(), Some(raw));
        assert_eq!(arkit::from_raw(raw), Some(*name));
        match find(name) {
            Some(e) => assert!(std::ptr::eq(e, find(raw).unwrap()), "{raw}"),
            None => {
                assert!(find(raw).is_none(), "{raw}");
                assert_eq!(not_modelled(raw), not_modelled(name));
                assert!(not_modelled(raw).is_some(), "{raw}");
            }
        }
    }
    let ten = ids(&TEN);
    assert_eq!(
        sliders_for_name("eyeLookIn_R", &ten),
        Err(LookupError::NotModelled {
            name: "eyeLookInRight",
            reason: "no eyeballs"
        })
    );
    assert_eq!(
        sliders_for_name("mouthSmile_L", &ten),
        sliders_for_name("mouthSmileLeft", &ten)
    );
}

/// VRM's `sad` (facebem's preset) is the sum of the fitted ARKit browInnerUp, mouthFrownLeft and
/// mouthFrownRight (issue 33's ICT sum for it), so a refit that changes those changes it too.
#[test]
fn sad_is_the_sum_of_the_fitted_inner_brow_raise_and_frowns() {
    let mut sum: Vec<(String, f64)> = Vec::new();
    for name in ["browInnerUp", "mouthFrownLeft", "mouthFrownRight"] {
        let Definition::Fitted { terms, .. } = find(name).unwrap().definition else {
            panic!("{name} is fitted");
        };
        for (id, v) in terms {
            match sum.iter_mut().find(|(i, _)| i == id) {
                Some((_, s)) => *s += v,
                None => sum.push((id.to_string(), *v)),
            }
        }
    }
    let sad = crate::expressions::presets::find("sad").unwrap();
    let preset = sorted_terms(sad.sliders.iter().map(|(id, v)| (id.to_string(), *v)));
    let sum = sorted_terms(sum.into_iter());
    assert_eq!(preset.len(), sum.len(), "{preset:?} against {sum:?}");
    for ((a, x), (b, y)) in preset.iter().zip(&sum) {
        assert_eq!(a, b);
        assert!((x - y).abs() < 1e-12, "{a}: {x} against {y}");
    }
}
