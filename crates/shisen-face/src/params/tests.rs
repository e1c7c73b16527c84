use super::*;

#[test]
fn default_parses_and_typical_matches_printed() {
    let p = FaceParams::default_params();
    assert_eq!(
        p.table_d(Expression::Surprise, MuscleKind::OculiUpperPalpebral),
        Some(-0.48)
    );
    assert_eq!(p.table_d(Expression::Anger, MuscleKind::Jaw), Some(3.5));
    // Printed typical columns of tables 5.9 / 5.10.
    let on = [
        (Expression::Happiness, 0.60),
        (Expression::Surprise, 0.40),
        (Expression::Anger, 0.50),
        (Expression::Sadness, 0.78),
        (Expression::Fear, 0.63),
        (Expression::Disgust, 0.63),
    ];
    for (e, t) in on {
        assert!((p.onset[&e].typical() - t).abs() < 0.006, "{e:?}");
    }
    let off = [
        (Expression::Happiness, 0.63),
        (Expression::Surprise, 0.71),
        (Expression::Anger, 1.70),
        (Expression::Sadness, 1.31),
        (Expression::Fear, 1.43),
        (Expression::Disgust, 0.97),
    ];
    for (e, t) in off {
        assert!((p.offset[&e].typical() - t).abs() < 0.006, "{e:?}");
    }
    assert!((p.offset_group2[&Expression::Sadness].typical() - 3.95).abs() < 0.006);
    assert_eq!(
        p.au_reference(ActionUnit::Au5, MuscleKind::OculiUpperPalpebral),
        Some(-0.48)
    );
    assert_eq!(
        p.au_reference(ActionUnit::Au45, MuscleKind::OculiUpperPalpebral),
        Some(2.9)
    );
}

#[test]
fn invalid_values_are_rejected_with_position() {
    let bad = DEFAULT_RON.replace("close_s: 0.080", "close_s: -0.080");
    let e = FaceParams::from_ron(&bad).unwrap_err().to_string();
    assert!(e.contains("must be >= 0.01"), "{e}");
    assert!(e.contains("blink.close_s"), "the field is named: {e}");
    let bad = DEFAULT_RON.replace("rf_ratio: 1.3)", "rf_ratio: 0.9)");
    let e = FaceParams::from_ron(&bad).unwrap_err().to_string();
    assert!(e.contains("rf_ratio: must be > 1"), "{e}");
    // The default database with one more top-level field.
    let with = |field: &str| {
        let end = DEFAULT_RON
            .trim_end()
            .strip_suffix(')')
            .expect("a RON struct");
        format!("{end}    {field},\n)\n")
    };
    // Skin fields after the two it needs: W4's are accepted; a
    // spacing in millimetres (not metres), a fade or thickening out of
    // range and a misspelt field are refused by name.
    let with_skin = |more: &str| {
        with(&format!(
            "skin: (wrinkle_onset_strain: 0.25, wrinkle_spacing_m: {more})"
        ))
    };
    assert!(
        FaceParams::from_ron(&with_skin("0.006, thickening: 0.5, domain_fade_m: 0.01")).is_ok()
    );
    for (more, named, why) in [
        ("6.0", "skin.wrinkle_spacing_m", "must be <= 0.03"),
        (
            "0.006, domain_fade_m: 12.0",
            "skin.domain_fade_m",
            "must be <=",
        ),
        ("0.006, thickening: 1.5", "skin.thickening", "must be <= 1"),
        (
            "0.006, thickenning: 0.5",
            "skin.thickenning",
            "Unexpected field",
        ),
    ] {
        let e = FaceParams::from_ron(&with_skin(more))
            .unwrap_err()
            .to_string();
        assert!(e.contains(named) && e.contains(why), "{more}: {e}");
    }
    // The lip seal (O1): a negative or NaN bound is refused, named.
    let with_lips = |lips: &str| with(&format!("lips: ({lips})"));
    let ok = FaceParams::from_ron(&with_lips("seal_k: None")).unwrap();
    assert_eq!(ok.lips.seal_k, None);
    for bad in [
        "seal_max_gap_m: -0.006",
        "seal_k: Some(-0.4)",
        "seal_k: Some(NaN)",
    ] {
        let e = FaceParams::from_ron(&with_lips(bad))
            .unwrap_err()
            .to_string();
        let field = bad.split(':').next().unwrap();
        assert!(e.contains(field), "{bad}: {e}");
    }
}

/// The error's `file:line:col: field` for a database with `from`
/// replaced by `to`.
fn refusal(from: &str, to: &str) -> String {
    assert!(DEFAULT_RON.contains(from), "{from}");
    let bad = DEFAULT_RON.replacen(from, to, 1);
    FaceParams::parse(&bad, std::path::Path::new("m.ron"))
        .unwrap_err()
        .to_string()
}

/// Line of the field at dotted `path` in the shipped database (1-based).
fn line_of(path: &str) -> usize {
    shisen_gaze::util::locate::locate(DEFAULT_RON, path).0
}

/// Every number has a range, and the checks across fields name the
/// field at fault, at its line.
#[test]
fn ranges_and_cross_field_checks_name_the_field() {
    // A blink interval of 1e-300 s once made the scheduler loop
    // forever; a human's is seconds.
    let e = refusal("mean_interval_s: 4.0", "mean_interval_s: 1e-300");
    let at = line_of("blink.mean_interval_s");
    assert!(
        e.starts_with(&format!("m.ron:{at}:"))
            && e.contains("blink.mean_interval_s: must be >= 0.5"),
        "{e}"
    );
    for (from, to, field) in [
        (
            "Jaw: 8.1",
            "Jaw: 80.0",
            "expressions.Happiness.Jaw: must be <= 30",
        ),
        (
            "ZygomaticMajor: 0.19",
            "ZygomaticMajor: 1.9",
            "expressions.Happiness.ZygomaticMajor: must be <= 1",
        ),
        (
            "cone_deg: 35.0",
            "cone_deg: 200.0",
            "cone_deg: must be <= 90",
        ),
        (
            "shape_s: 13.94",
            "shape_s: 1e300",
            "blink.shape_s: must be <= 1000",
        ),
        (
            "lid_follow_gain: 0.8",
            "lid_follow_gain: 1e9",
            "blink.lid_follow_gain: must be <= 2",
        ),
        (
            "Anger: (upper: 3.00",
            "Anger: (upper: 300.0",
            "offset.Anger.upper: must be <= 30",
        ),
    ] {
        let e = refusal(from, to);
        assert!(e.contains(field), "{to}: {e}");
    }
    // Across fields: the field at fault and its line, not line 1.
    let e = refusal("gaze_trigger_max_deg: 60.0", "gaze_trigger_max_deg: 10.0");
    let at = line_of("blink.gaze_trigger_max_deg");
    assert!(
        e.starts_with(&format!("m.ron:{at}:"))
            && e.contains("blink.gaze_trigger_max_deg: must exceed gaze_trigger_min_deg"),
        "{e}"
    );
    let e = refusal(
        "Happiness: {",
        "Neutral: { Jaw: 1.0 },\n        Happiness: {",
    );
    assert!(
        e.contains("expressions.Neutral: Neutral must not drive"),
        "{e}"
    );
    let e = refusal(
        "Surprise: (upper: 1.00, lower: 0.16)",
        "Surprise: (upper: 0.1, lower: 0.16)",
    );
    assert!(e.contains("onset.Surprise.upper: the slow bound"), "{e}");
    let e = refusal("Risorius: (cone_deg: 23.0, rf_ratio: 1.3),", "");
    assert!(e.contains("influence: missing Risorius"), "{e}");
    // Parameters built in code are checked against the same ranges.
    let mut p = FaceParams::default_params();
    assert!(p.validate().is_ok());
    p.blink.mean_interval_s = 1e-300;
    match p.validate().unwrap_err() {
        FaceError::Invalid { field, message } => {
            assert_eq!(field, "blink.mean_interval_s");
            assert!(message.contains(">= 0.5"), "{message}");
        }
        other => panic!("{other}"),
    }
    // A NaN is refused where a map or an option holds it.
    let e = refusal("Jaw: 8.1", "Jaw: NaN");
    assert!(
        e.contains("expressions.Happiness.Jaw: must be a finite number"),
        "{e}"
    );
    let e = refusal("mean_interval_s: 4.0", "mean_interval_s: inf");
    assert!(
        e.contains("blink.mean_interval_s: must be a finite number"),
        "{e}"
    );
    let e = refusal(
        "engaged_interval_scale: 3.0",
        "engaged_interval_scale: 3.0, levator_max_raise_m: Some(NaN)",
    );
    assert!(
        e.contains("blink.levator_max_raise_m: must be a finite number"),
        "{e}"
    );
    // The prototypes' AU levels are 0-1.
    let mut p = FaceParams::default_params();
    p.prototypes
        .as_mut()
        .unwrap()
        .get_mut(&Expression::Fear)
        .unwrap()
        .insert(ActionUnit::Au20, 3.0);
    let e = p.validate().unwrap_err().to_string();
    assert!(e.contains("prototypes.Fear.Au20: must be <= 1"), "{e}");
}

/// The schema's rows name exactly the muscles and AUs the tables
/// define (the rows' keys are checked against them).
#[test]
fn schema_rows_match_the_tables() {
    let schema = shisen_gaze::util::schema::schema_of::<FaceParams>();
    let keys = |def: &str| -> Vec<String> {
        let mut k: Vec<String> = schema["$defs"][def]["properties"]
            .as_object()
            .unwrap_or_else(|| panic!("{def}: {schema:#}"))
            .keys()
            .cloned()
            .collect();
        k.sort();
        k
    };
    let names = |it: &mut dyn Iterator<Item = String>| {
        let mut v: Vec<String> = it.collect();
        v.sort();
        v
    };
    assert_eq!(
        keys("TableDRow"),
        names(&mut MuscleKind::ALL.iter().map(|m| format!("{m:?}")))
    );
    assert_eq!(
        keys("PrototypeRow"),
        names(&mut ActionUnit::ALL.iter().map(|a| format!("{a:?}")))
    );
}
