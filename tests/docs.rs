//! Every equation the code cites has its explanation in `docs/model/`:
//! a comment naming `(M7)`, `(H2)` or `(F6)` resolves to an anchor `m7` /
//! `h2` / `f6` there (gaze equations, T1 and the human-timing laws H1-H5
//! in gaze.md, face equations in face.md).

use std::collections::BTreeSet;
use std::path::Path;

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Equation labels written as `(M7)`, `(F6)`, `(T1)`, or `M2-M6` ranges'
/// ends, in the source.
fn cited(text: &str) -> BTreeSet<String> {
    let b = text.as_bytes();
    let mut out = BTreeSet::new();
    for i in 0..b.len().saturating_sub(2) {
        let prev_ok = i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        if prev_ok && matches!(b[i], b'M' | b'F' | b'T' | b'H') && b[i + 1].is_ascii_digit() {
            let mut j = i + 1;
            while j < b.len() && b[j].is_ascii_digit() {
                j += 1;
            }
            let next_ok = j == b.len() || !(b[j].is_ascii_alphanumeric() || b[j] == b'_');
            // Only in parentheses: `(M7)`, `(M8 with ...`, `(F7),`.
            if next_ok && i > 0 && b[i - 1] == b'(' {
                out.insert(text[i..j].to_lowercase());
            }
        }
    }
    out
}

#[test]
fn every_cited_equation_is_documented() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    let mut labels = BTreeSet::new();
    for f in &files {
        labels.extend(cited(&std::fs::read_to_string(f).unwrap()));
    }
    let docs: String = ["gaze.md", "face.md"]
        .iter()
        .map(|d| std::fs::read_to_string(root.join("docs/model").join(d)).unwrap())
        .collect();
    assert!(
        labels.contains("m1") && labels.contains("f7") && labels.contains("h1"),
        "{labels:?}"
    );
    let missing: Vec<_> = labels
        .iter()
        .filter(|l| !docs.contains(&format!("<a id=\"{l}\">")))
        .collect();
    assert!(
        missing.is_empty(),
        "cited but not in docs/model: {missing:?}"
    );
}
