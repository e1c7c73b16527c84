//! Many runs at once: `shisen test` over a folder (exit codes, JUnit),
//! studies split into shards and merged (exactly the unsharded rows),
//! resuming, and refusing to mix results.

use std::path::{Path, PathBuf};
use std::process::Command;

fn shisen(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_shisen"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ),
    )
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("shisen-batch-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn test_runs_a_folder_reports_each_scene_and_exits_by_the_worst() {
    let d = dir("test");
    std::fs::write(d.join("a_ok.ron"), "Scene(duration: 0.2, expect: [Finite])").unwrap();
    std::fs::write(
        d.join("b_fails.ron"),
        "Scene(duration: 0.2, expect: [AngleReaches(joint: NeckYaw, min_deg: 60.0, from: 0.0, to: 0.2)])",
    )
    .unwrap();
    let (code, out) = shisen(&["test", s(&d), "--jobs", "2"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("PASS  a_ok") && out.contains("FAIL  b_fails"),
        "{out}"
    );
    assert!(
        out.contains("2 scenes: 1 passed, 1 failed, 0 could not be loaded"),
        "{out}"
    );

    // A broken scene is reported, the others still run, exit 2.
    std::fs::write(d.join("c_broken.ron"), "Scene(duration: -1.0)").unwrap();
    let junit = d.join("r.xml");
    let (code, out) = shisen(&["test", s(&d), "--junit", s(&junit)]);
    assert_eq!(code, 2, "{out}");
    assert!(
        out.contains("ERROR") && out.contains("c_broken.ron:1:"),
        "{out}"
    );
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(
        xml.contains("tests=\"3\" failures=\"1\" errors=\"1\""),
        "{xml}"
    );
    assert!(
        xml.contains("<failure type=\"expectation\" message=\"measured"),
        "{xml}"
    );

    // Two shards of the folder, merged, hold every scene once.
    let parts: Vec<PathBuf> = (0..2).map(|i| d.join(format!("r{i}.xml"))).collect();
    for (i, p) in parts.iter().enumerate() {
        shisen(&["test", s(&d), "--shard", &format!("{i}/2"), "--junit", s(p)]);
    }
    let merged = d.join("merged.xml");
    let (code, out) = shisen(&["merge", "--out", s(&merged), s(&parts[0]), s(&parts[1])]);
    assert_eq!(code, 0, "{out}");
    let m = std::fs::read_to_string(&merged).unwrap();
    assert!(m.contains("tests=\"3\" failures=\"1\" errors=\"1\""), "{m}");
    assert_eq!(m.matches("<testsuite ").count(), 3, "{m}");
}

#[test]
fn study_shards_merge_to_exactly_the_unsharded_rows() {
    let d = dir("study");
    std::fs::write(
        d.join("base.ron"),
        "Scene(duration: 0.3, timeline: [(at: 0.05, do: Wave(part: LeftGlove, amplitude: (0.1, 0.0, 0.0), frequency: 2.0, duration: 0.2))], expect: [Finite])",
    )
    .unwrap();
    let study = d.join("study.ron");
    std::fs::write(
        &study,
        "Study(scene: \"base.ron\", vary: [(field: \"vh.personality.a_face\", values: [1.0, 2.0]), (field: \"timeline[0].do.Wave.frequency\", range: (from: 1.0, to: 3.0, steps: 3))], seeds: List([4, 5]))",
    )
    .unwrap();
    let whole = d.join("whole.csv");
    let (code, out) = shisen(&["study", s(&study), "--out", s(&whole)]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("12 runs in all"), "{out}");
    let parts: Vec<PathBuf> = (0..3).map(|i| d.join(format!("part{i}.csv"))).collect();
    for (i, p) in parts.iter().enumerate() {
        let (code, out) = shisen(&[
            "study",
            s(&study),
            "--shard",
            &format!("{i}/3"),
            "--out",
            s(p),
        ]);
        assert_eq!(code, 0, "{out}");
    }
    let merged = d.join("merged.csv");
    let mut args = vec!["merge", "--out", s(&merged)];
    args.extend(parts.iter().map(|p| s(p)));
    let (code, out) = shisen(&args);
    assert_eq!(code, 0, "{out}");
    assert_eq!(
        std::fs::read_to_string(&merged).unwrap(),
        std::fs::read_to_string(&whole).unwrap()
    );

    // Resuming does no run twice; another study into the same file is refused.
    let (code, out) = shisen(&["study", s(&study), "--shard", "0/3", "--out", s(&parts[0])]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("0 run now, 4 resumed"), "{out}");
    std::fs::write(
        d.join("other.ron"),
        "Study(scene: \"base.ron\", vary: [(field: \"vh.personality.a_face\", values: [3.0])])",
    )
    .unwrap();
    let (code, out) = shisen(&["study", s(&d.join("other.ron")), "--out", s(&whole)]);
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("holds results of"), "{out}");

    // A misspelled field is a load error naming it.
    std::fs::write(
        d.join("typo.ron"),
        "Study(scene: \"base.ron\", vary: [(field: \"vh.personality.a_fcae\", values: [3.0])])",
    )
    .unwrap();
    let (code, out) = shisen(&[
        "study",
        s(&d.join("typo.ron")),
        "--out",
        s(&d.join("t.csv")),
    ]);
    assert_eq!(code, 2, "{out}");
    assert!(
        out.contains("a_fcae") && out.contains("vary[0].field"),
        "{out}"
    );
}

/// A study of `text` beside a tiny base scene, which must be refused:
/// exit 2, and nothing written. Returns the error.
fn refused_study(name: &str, text: &str) -> String {
    let d = dir(name);
    std::fs::write(d.join("base.ron"), "Scene(duration: 0.1, expect: [Finite])").unwrap();
    let study = d.join("study.ron");
    std::fs::write(&study, text).unwrap();
    let out = d.join("out.csv");
    let (code, err) = shisen(&["study", s(&study), "--out", s(&out)]);
    assert_eq!(code, 2, "{err}");
    assert!(!out.exists(), "a refused study writes no results file");
    err
}

#[test]
fn a_study_with_an_empty_seed_range_says_why_and_writes_nothing() {
    let err = refused_study(
        "study_seeds",
        "Study(scene: \"base.ron\", vary: [(field: \"vh.personality.a_face\", values: [1.0])],\n  seeds: Range(from: 5, to: 1))",
    );
    assert!(err.contains("study.ron:2:"), "{err}");
    assert!(err.contains("`to` must be at least `from`"), "{err}");
}

#[test]
fn a_study_that_varies_a_field_twice_is_refused_at_the_second() {
    let err = refused_study(
        "study_twice",
        "Study(scene: \"base.ron\", vary: [\n  (field: \"vh.personality.a_face\", values: [1.0]),\n  (field: \"vh.personality.a_face\", values: [2.0]),\n])",
    );
    assert!(err.contains("study.ron:3:"), "{err}");
    assert!(err.contains("varied twice"), "{err}");
}

#[test]
fn a_study_with_a_value_out_of_range_writes_nothing_to_block_its_rerun() {
    let err = refused_study(
        "study_range",
        "Study(scene: \"base.ron\", vary: [\n  (field: \"vh.personality.a_face\", values: [1.0, 200.0]),\n])",
    );
    assert!(err.contains("study.ron:2:"), "{err}");
    assert!(err.contains("must be <= 100, got 200"), "{err}");
}
