//! The same scene and seed give the same trace on every x86-64 machine:
//! the trace hashes of every shipped scene are compared between builds for
//! different CPU feature levels (the baseline x86-64 and, say, x86-64-v3
//! with AVX2 and FMA, which lets the compiler and the SIMD crates use wider
//! and fused instructions), and with the C library's CPU dispatch narrowed
//! to a machine without AVX2, FMA or AVX-512 (its libm picks other code
//! for sin, exp, atan2...). docs/headless.md "Determinism" says what is
//! guaranteed.
//!
//! `.ci/run` builds `crates/shisen/examples/trace_hashes.rs` twice and runs
//! this test with the two builds in `SHISEN_HASH_BUILDS` (`A:B`).

use std::path::{Path, PathBuf};
use std::process::Command;

fn scenes() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("scenes/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    v.sort();
    v
}

/// The hash lines of `build` over `scenes`, with `env` set.
fn hashes(build: &str, scenes: &[PathBuf], env: &[(&str, &str)]) -> Vec<String> {
    let out = Command::new(build)
        .args(scenes)
        .envs(env.iter().copied())
        .output()
        .unwrap_or_else(|e| panic!("{build}: {e}"));
    assert!(
        out.status.success(),
        "{build} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .expect("utf-8")
        .lines()
        .map(String::from)
        .collect()
}

#[test]
#[ignore = "needs trace_hashes built for two CPU feature levels: .ci/run builds them"]
fn traces_are_the_same_at_every_cpu_feature_level() {
    let builds = std::env::var("SHISEN_HASH_BUILDS")
        .expect("SHISEN_HASH_BUILDS=A:B, two builds of the trace_hashes example");
    let (a, b) = builds
        .split_once(':')
        .expect("SHISEN_HASH_BUILDS=A:B, two builds of the trace_hashes example");
    let scenes = scenes();
    assert!(scenes.len() >= 20, "the shipped scenes");
    let base = hashes(a, &scenes, &[]);
    assert_eq!(base.len(), scenes.len());
    let narrowed = hashes(
        a,
        &scenes,
        &[("GLIBC_TUNABLES", "glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F")],
    );
    let wider = hashes(b, &scenes, &[]);
    let differ = |other: &[String]| -> Vec<String> {
        base.iter()
            .zip(other)
            .filter(|(x, y)| x != y)
            .map(|(x, y)| format!("{x} / {y}"))
            .collect()
    };
    assert_eq!(
        differ(&narrowed),
        Vec::<String>::new(),
        "libm dispatch narrowed"
    );
    assert_eq!(differ(&wider), Vec::<String>::new(), "the other CPU level");
}
