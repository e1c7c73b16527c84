//! Many scenes at once (`shisen test`): every scene of some files and
//! folders run headless in parallel, judged, and reported one line per
//! scene, as a summary and as JUnit XML for CI servers.
//!
//! The report follows the JUnit schema that Maven Surefire and Jenkins
//! read (`junit-10.xsd`): one `<testsuite>` per scene, one `<testcase>`
//! per expectation, a `<failure>` with the measured value when it does
//! not hold, an `<error>` when the scene cannot be loaded.

use std::fmt::Write as _;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rayon::prelude::*;

use crate::scene::LoadedScene;
use crate::tools::headless::{self, Report};
use crate::tools::parallel;
use crate::tools::table::Shard;

/// The scene files named by `paths`: files as given, folders by the
/// `.ron` files directly in them (not their subfolders, which hold gains
/// and face data), sorted. A path that does not exist is an error.
pub fn scene_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            let entries = std::fs::read_dir(p).map_err(|e| format!("{}: {e}", p.display()))?;
            let mut found: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.is_file() && f.extension().is_some_and(|x| x == "ron"))
                .collect();
            found.sort();
            out.extend(found);
        } else if p.is_file() {
            out.push(p.clone());
        } else {
            return Err(format!("{}: no such file or folder", p.display()));
        }
    }
    Ok(out)
}

/// One scene's run.
#[derive(Debug)]
pub struct SceneRun {
    /// The scene file.
    pub path: PathBuf,
    /// The scene's name (its file stem if it could not be loaded).
    pub name: String,
    /// The report, or why the scene could not be loaded or run.
    pub outcome: Result<Report, String>,
    /// Wall time of the run, s (reporting only).
    pub wall: f64,
}

impl SceneRun {
    /// True if the scene loaded and every expectation holds.
    pub fn passed(&self) -> bool {
        self.outcome.as_ref().is_ok_and(Report::passed)
    }

    /// One line for a terminal: PASS / FAIL / ERROR, the scene, what failed.
    pub fn line(&self) -> String {
        match &self.outcome {
            Err(e) => format!("ERROR {}: {e}", self.path.display()),
            Ok(r) => {
                let failed: Vec<String> = r
                    .verdicts
                    .iter()
                    .filter(|v| !v.pass)
                    .map(|v| format!("{} (measured {})", v.what, v.measured))
                    .collect();
                let n = r.verdicts.len();
                if failed.is_empty() {
                    format!("PASS  {} ({n}/{n}, {:.1} s)", self.name, self.wall)
                } else {
                    format!(
                        "FAIL  {} ({}/{n}): {}",
                        self.name,
                        n - failed.len(),
                        failed.join("; ")
                    )
                }
            }
        }
    }
}

/// Run `files` (this `shard` of them) on `jobs` threads with a progress
/// bar. With `out`, each scene's trace (`NAME.csv`) and plot (`NAME.png`)
/// are kept there. Results come back in file order.
pub fn run_scenes(
    files: &[PathBuf],
    jobs: usize,
    shard: Shard,
    out: Option<&Path>,
) -> Vec<SceneRun> {
    let mine: Vec<&PathBuf> = files
        .iter()
        .enumerate()
        .filter(|(k, _)| shard.contains(*k))
        .map(|(_, f)| f)
        .collect();
    let bar = parallel::bar(mine.len() as u64, "scenes");
    let runs = parallel::pool(jobs).install(|| {
        mine.par_iter()
            .map(|f| {
                if super::stop_requested() {
                    return SceneRun {
                        path: f.to_path_buf(),
                        name: stem_of(f),
                        outcome: Err(INTERRUPTED.into()),
                        wall: 0.0,
                    };
                }
                let r = run_one(f, out);
                bar.inc(1);
                bar.set_message(r.name.clone());
                r
            })
            .collect()
    });
    bar.finish_and_clear();
    runs
}

/// The outcome of a scene a stop request (Ctrl-C) cut short or kept from
/// starting.
pub const INTERRUPTED: &str = "interrupted (Ctrl-C)";

/// A scene file's name without its folder and extension: its output's
/// name under `test --out`.
pub fn stem_of(path: &Path) -> String {
    path.file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned())
}

/// Scene files whose outputs (`NAME.csv`, `NAME.png`) would be one file
/// in an output folder: the first such pair.
pub fn colliding_outputs(files: &[PathBuf]) -> Option<(&PathBuf, &PathBuf)> {
    let mut seen: std::collections::HashMap<String, &PathBuf> = Default::default();
    for f in files {
        if let Some(first) = seen.insert(stem_of(f).to_lowercase(), f) {
            return Some((first, f));
        }
    }
    None
}

fn run_one(path: &Path, out: Option<&Path>) -> SceneRun {
    let wall = Instant::now();
    let stem = stem_of(path);
    let loaded = match LoadedScene::load(path) {
        Ok(l) => l,
        Err(e) => {
            return SceneRun {
                path: path.to_path_buf(),
                name: stem,
                outcome: Err(e.to_string()),
                wall: wall.elapsed().as_secs_f64(),
            };
        }
    };
    let outcome = match out {
        None => headless::run(&loaded, None, None, 1).map_err(|e| e.to_string()),
        Some(dir) => run_kept(&loaded, &dir.join(format!("{stem}.csv"))),
    }
    .and_then(|r| {
        if r.interrupted {
            Err(INTERRUPTED.into())
        } else {
            Ok(r)
        }
    });
    SceneRun {
        path: path.to_path_buf(),
        name: loaded.scene.name.clone(),
        outcome,
        wall: wall.elapsed().as_secs_f64(),
    }
}

/// A run whose trace is kept at `csv`, with its plot beside it.
fn run_kept(loaded: &LoadedScene, csv: &Path) -> Result<Report, String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", csv.display());
    // Written beside and renamed into place when whole.
    let dir = csv.parent().unwrap_or(Path::new("."));
    let tmp = tempfile::Builder::new()
        .prefix(".shisen-")
        .suffix(".tmp")
        .tempfile_in(dir)
        .map_err(|e| err(&e))?;
    let mut w = BufWriter::new(tmp);
    let report = headless::run(loaded, None, Some(&mut w), 1).map_err(|e| err(&e))?;
    let tmp = w.into_inner().map_err(|e| err(&e.into_error()))?;
    // A run cut short keeps the last whole trace (and its plot) in place.
    if report.interrupted {
        return Ok(report);
    }
    tmp.persist(csv).map_err(|e| err(&e.error))?;
    crate::tools::plot::plot_trace(csv, &csv.with_extension("png"), (1400, 900))
        .map_err(|e| err(&e))?;
    Ok(report)
}

/// The JUnit XML report of `runs` (see the module docs for the schema).
///
/// A comment before the root names the job, `<!-- shisen test: scenes=S
/// shard=I/N -->` (S scene files in the whole job), for [`merge_junit`].
pub fn junit(runs: &[SceneRun], scenes: usize, shard: Shard) -> String {
    let mut suites = String::new();
    let (mut tests, mut failures, mut errors, mut time) = (0, 0, 0, 0.0);
    for r in runs {
        suites.push_str(&junit_suite(r));
        time += r.wall;
        match &r.outcome {
            Ok(rep) => {
                tests += rep.verdicts.len();
                failures += rep.verdicts.iter().filter(|v| !v.pass).count();
            }
            Err(_) => {
                tests += 1;
                errors += 1;
            }
        }
    }
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!-- shisen test: scenes={scenes} shard={shard} -->\n<testsuites name=\"shisen\" tests=\"{tests}\" failures=\"{failures}\" errors=\"{errors}\" time=\"{time:.3}\">\n{suites}</testsuites>\n"
    )
}

/// One scene as a `<testsuite>` element.
fn junit_suite(r: &SceneRun) -> String {
    let name = xml(&r.name);
    let file = xml(&r.path.display().to_string());
    let mut s = String::new();
    match &r.outcome {
        Err(e) => {
            let _ = write!(
                s,
                "  <testsuite name=\"{name}\" file=\"{file}\" tests=\"1\" failures=\"0\" errors=\"1\" time=\"{:.3}\">\n    <testcase name=\"load\" classname=\"{name}\">\n      <error type=\"load\" message=\"{}\"/>\n    </testcase>\n  </testsuite>\n",
                r.wall,
                xml(e)
            );
        }
        Ok(rep) => {
            let failures = rep.verdicts.iter().filter(|v| !v.pass).count();
            let _ = writeln!(
                s,
                "  <testsuite name=\"{name}\" file=\"{file}\" tests=\"{}\" failures=\"{failures}\" errors=\"0\" time=\"{:.3}\">",
                rep.verdicts.len(),
                r.wall
            );
            for v in &rep.verdicts {
                let case = format!(
                    "    <testcase name=\"{}\" classname=\"{name}\"",
                    xml(&v.what)
                );
                if v.pass {
                    let _ = writeln!(s, "{case}/>");
                } else {
                    let _ = writeln!(
                        s,
                        "{case}>\n      <failure type=\"expectation\" message=\"measured {}\"/>\n    </testcase>",
                        xml(&v.measured)
                    );
                }
            }
            s.push_str("  </testsuite>\n");
        }
    }
    s
}

/// Join the JUnit reports of a test run's shards into one.
pub fn merge_junit(reports: &[String]) -> Result<String, String> {
    let (mut tests, mut failures, mut errors, mut time) = (0u64, 0u64, 0u64, 0.0f64);
    let mut suites = String::new();
    // The job (scene count and shard count) and which input has each shard.
    let mut job: Option<(usize, usize)> = None;
    let mut seen: Vec<Option<usize>> = Vec::new();
    for (k, text) in reports.iter().enumerate() {
        let (scenes, shard) = junit_job(text)
            .ok_or_else(|| format!("input {}: no `<!-- shisen test: scenes=S shard=I/N -->` line (not a shisen report, or an old one)", k + 1))?;
        if shard.count > scenes.max(1) {
            return Err(format!(
                "input {}: {} shards of a job of {scenes} scenes",
                k + 1,
                shard.count
            ));
        }
        match job {
            None => {
                job = Some((scenes, shard.count));
                seen = vec![None; shard.count];
            }
            Some(j) if j != (scenes, shard.count) => {
                return Err(format!(
                    "input {}: a job of {scenes} scenes in {} shards, not {} in {}",
                    k + 1,
                    shard.count,
                    j.0,
                    j.1
                ));
            }
            Some(_) => {}
        }
        if let Some(other) = seen[shard.index].replace(k) {
            return Err(format!(
                "inputs {} and {} are both shard {shard}; each shard is merged once",
                other + 1,
                k + 1
            ));
        }
        let open = text
            .find("<testsuites ")
            .ok_or_else(|| format!("input {}: not a shisen JUnit report", k + 1))?;
        let head_end = open + text[open..].find('>').ok_or("unterminated <testsuites>")?;
        let head = &text[open..head_end];
        let attr = |a: &str| -> Result<String, String> {
            let key = format!(" {a}=\"");
            let i = head.find(&key).ok_or(format!("no {a} attribute"))? + key.len();
            Ok(head[i..i + head[i..].find('"').ok_or("bad attribute")?].to_string())
        };
        let num =
            |a: &str| -> Result<u64, String> { attr(a)?.parse().map_err(|_| format!("bad {a}")) };
        tests += num("tests")?;
        failures += num("failures")?;
        errors += num("errors")?;
        time += attr("time")?.parse::<f64>().map_err(|_| "bad time")?;
        let body = &text[head_end + 1..];
        let close = body
            .rfind("</testsuites>")
            .ok_or("unterminated <testsuites>")?;
        suites.push_str(body[..close].trim_start_matches('\n'));
    }
    let (scenes, count) = job.ok_or("nothing to merge")?;
    let missing: Vec<String> = (0..count)
        .filter(|&i| seen[i].is_none())
        .map(|i| format!("{i}/{count}"))
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "the job has {count} shards; missing {}: merge every shard's report",
            missing.join(", ")
        ));
    }
    Ok(format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!-- shisen test: scenes={scenes} shard=0/1 -->\n<testsuites name=\"shisen\" tests=\"{tests}\" failures=\"{failures}\" errors=\"{errors}\" time=\"{time:.3}\">\n{suites}</testsuites>\n"
    ))
}

/// The job a report's first comment names: scene count and shard.
fn junit_job(text: &str) -> Option<(usize, Shard)> {
    let line = text.lines().find(|l| l.starts_with("<!-- shisen test:"))?;
    let word = |key: &str| {
        line.split(' ')
            .find_map(|w| w.strip_prefix(key)?.strip_prefix('='))
    };
    Some((word("scenes")?.parse().ok()?, word("shard")?.parse().ok()?))
}

/// Text escaped for an XML attribute.
fn xml(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\n' => o.push_str("&#10;"),
            c if (c as u32) < 0x20 && c != '\t' => {}
            c => o.push(c),
        }
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::expect::Verdict;

    fn run(name: &str, pass: &[bool]) -> SceneRun {
        SceneRun {
            path: PathBuf::from(format!("scenes/{name}.ron")),
            name: name.into(),
            outcome: Ok(Report {
                verdicts: pass
                    .iter()
                    .map(|&p| Verdict {
                        what: "gaze on \"head\" > 50%".into(),
                        measured: "12.5% <".into(),
                        value: 0.125,
                        pass: p,
                    })
                    .collect(),
                ticks: 10,
                sim_time: 0.01,
                resets: 0,
                saccades: 0,
                head_moves: 0,
                interrupted: false,
            }),
            wall: 0.5,
        }
    }

    #[test]
    fn junit_counts_escapes_and_merges() {
        let bad = SceneRun {
            path: "x.ron".into(),
            name: "x".into(),
            outcome: Err("x.ron:1:1: - : oops".into()),
            wall: 0.0,
        };
        let a = junit(&[run("a", &[true, false])], 3, "0/2".parse().unwrap());
        let b = junit(&[run("b", &[true]), bad], 3, "1/2".parse().unwrap());
        assert!(
            merge_junit(std::slice::from_ref(&a))
                .unwrap_err()
                .contains("missing 1/2")
        );
        assert!(
            merge_junit(&[a.clone(), a.clone()])
                .unwrap_err()
                .contains("both shard 0/2")
        );
        assert!(a.contains("tests=\"2\" failures=\"1\" errors=\"0\""), "{a}");
        assert!(
            a.contains("&quot;head&quot;") && a.contains("12.5% &lt;"),
            "{a}"
        );
        let m = merge_junit(&[a, b]).unwrap();
        assert!(
            m.contains("<testsuites name=\"shisen\" tests=\"4\" failures=\"1\" errors=\"1\""),
            "{m}"
        );
        assert_eq!(m.matches("<testsuite ").count(), 3);
        assert_eq!(m.matches("</testsuites>").count(), 1);
    }
}
