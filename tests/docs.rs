//! Every equation the code cites has its explanation in `docs/model/`: a
//! comment naming `(M7)`, `(H2)`, `(F6)` or a range `(W1-W3)` resolves to
//! an anchor `m7` / `h2` / `f6` / `w1`..`w3` there. Every capital letter
//! followed by digits in parentheses counts as a citation, in the crates'
//! sources and examples, the tests and the benches; only the attention
//! amounts `(A0)`..`(A2)` are not equations. No anchor appears twice in one
//! file.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Every Rust file of the workspace's crates (their `src`, `examples`), the
/// tests and the benches.
fn workspace_sources() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut dirs = vec![root.join("src"), root.join("tests"), root.join("benches")];
    for c in std::fs::read_dir(root.join("crates")).unwrap() {
        let c = c.unwrap().path();
        dirs.extend(
            ["src", "examples"]
                .map(|d| c.join(d))
                .into_iter()
                .filter(|d| d.is_dir()),
        );
    }
    let mut files = Vec::new();
    for d in &dirs {
        rust_files(d, &mut files);
    }
    // This file's own examples of the citation syntax are not citations.
    files.retain(|f| !f.ends_with("tests/docs.rs"));
    assert!(files.len() > 50, "found only {} sources", files.len());
    files
}

/// A label `X12` at `i` (a capital letter, digits, then a non-word
/// character): its lowercase form and its end.
fn label_at(text: &str, i: usize) -> Option<(String, usize)> {
    let b = text.as_bytes();
    if !b.get(i)?.is_ascii_uppercase() {
        return None;
    }
    let mut j = i + 1;
    while j < b.len() && b[j].is_ascii_digit() {
        j += 1;
    }
    let next_ok = j == b.len() || !(b[j].is_ascii_alphanumeric() || b[j] == b'_');
    (j > i + 1 && next_ok).then(|| (text[i..j].to_lowercase(), j))
}

/// Equation labels cited in parentheses: `(M7)`, `(M8 with ...`, `(F7),`,
/// and both ends of a range `(W1-W3)` with every label between.
fn cited(text: &str) -> BTreeSet<String> {
    let b = text.as_bytes();
    let mut out = BTreeSet::new();
    for i in 1..b.len() {
        if b[i - 1] != b'(' {
            continue;
        }
        let Some((first, end)) = label_at(text, i) else {
            continue;
        };
        out.insert(first.clone());
        if b.get(end) == Some(&b'-')
            && let Some((last, _)) = label_at(text, end + 1)
            && last[..1] == first[..1]
        {
            let (a, z): (u32, u32) = (first[1..].parse().unwrap(), last[1..].parse().unwrap());
            out.extend((a..=z).map(|n| format!("{}{n}", &first[..1])));
        }
    }
    out
}

/// Anchors `<a id="...">` of each docs/model file, with how often each appears.
fn anchors() -> BTreeMap<String, BTreeMap<String, usize>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/model");
    let mut out = BTreeMap::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_none_or(|x| x != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&p).unwrap();
        let mut ids = BTreeMap::new();
        for part in text.split("<a id=\"").skip(1) {
            let id = part.split('"').next().unwrap().to_string();
            *ids.entry(id).or_insert(0) += 1;
        }
        out.insert(p.file_name().unwrap().to_string_lossy().into_owned(), ids);
    }
    out
}

/// Equation anchors: a letter and digits (`m7`, `w2`).
fn is_equation(id: &str) -> bool {
    let mut c = id.chars();
    c.next().is_some_and(|l| l.is_ascii_lowercase())
        && id.len() > 1
        && c.all(|d| d.is_ascii_digit())
}

#[test]
fn every_cited_equation_is_documented() {
    let docs = anchors();
    let documented: BTreeSet<String> = docs
        .values()
        .flat_map(|ids| ids.keys())
        .filter(|id| is_equation(id))
        .cloned()
        .collect();
    let families: BTreeSet<char> = documented
        .iter()
        .map(|l| l.chars().next().unwrap())
        .collect();
    for f in ['m', 'f', 't', 'h', 's', 'o', 'l', 'w'] {
        assert!(
            families.contains(&f),
            "no equation family {f} in docs/model: {families:?}"
        );
    }
    // Every capital letter counts: a citation of an undocumented family
    // fails below. Only the attention amounts A0-A2 (M8's A1, A2; the
    // blink's A0) are parameters, not equations.
    let mut labels = BTreeSet::new();
    for f in workspace_sources() {
        labels.extend(cited(&std::fs::read_to_string(f).unwrap()));
    }
    labels.retain(|l| !l.starts_with('a'));
    for l in ["m1", "f7", "h1", "s1", "o1", "l1", "w1", "w3", "t1"] {
        assert!(labels.contains(l), "{l} not cited: {labels:?}");
    }
    let missing: Vec<_> = labels.difference(&documented).collect();
    assert!(
        missing.is_empty(),
        "cited but not in docs/model: {missing:?}"
    );
}

#[test]
fn anchors_are_unique_in_each_file() {
    for (file, ids) in anchors() {
        let twice: Vec<_> = ids.iter().filter(|(_, n)| **n > 1).collect();
        assert!(
            twice.is_empty(),
            "docs/model/{file}: anchors repeated: {twice:?}"
        );
    }
}

#[test]
fn ranges_and_families_are_read() {
    let c = cited("x (W1-W3) y (M7) z (L2 (AU6) MM1 (M12a)");
    let want: BTreeSet<String> = ["w1", "w2", "w3", "m7", "l2"].map(String::from).into();
    assert_eq!(c, want);
}

/// Every relative link of the README and the manual (docs/*.md,
/// docs/model/*.md) points at a file that exists: pages moved into the
/// manual keep their pictures and cross-references.
#[test]
fn every_link_of_the_readme_and_the_manual_resolves() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut pages = vec![root.join("README.md")];
    for dir in ["docs", "docs/model"] {
        for e in std::fs::read_dir(root.join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "md") {
                pages.push(p);
            }
        }
    }
    let mut broken = Vec::new();
    for page in &pages {
        let text = std::fs::read_to_string(page).unwrap();
        let base = page.parent().unwrap();
        for (i, _) in text.match_indices("](") {
            let rest = &text[i + 2..];
            let Some(end) = rest.find(')') else { continue };
            let target = rest[..end].split('#').next().unwrap_or("");
            if target.is_empty() || target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            if !base.join(target).exists() {
                broken.push(format!("{}: {target}", page.display()));
            }
        }
    }
    assert!(
        broken.is_empty(),
        "links to nothing:\n{}",
        broken.join("\n")
    );
}
