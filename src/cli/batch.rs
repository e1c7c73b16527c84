//! `shisen test`, `shisen study`, `shisen merge`: many runs, in parallel
//! and in shards.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, Result, bail};

use shisen::tools::batch;
use shisen::tools::output::{Outputs, write_whole};
use shisen::tools::study::LoadedStudy;
use shisen::tools::table::{self, ResultsFile, Shard};

use crate::run::Interrupted;

/// Threads for `--jobs` (the option is 1-256; default: every core).
pub fn jobs(jobs: Option<usize>) -> usize {
    jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// Run every scene of `paths`; exit 0 if all hold, 1 if an expectation
/// fails, 2 if a scene cannot be loaded (the others still run).
pub fn test_cmd(
    paths: &[PathBuf],
    jobs: usize,
    shard: Shard,
    junit: Option<&Path>,
    out: Option<&Path>,
) -> Result<ExitCode> {
    let files = batch::scene_files(paths).map_err(anyhow::Error::msg)?;
    if files.is_empty() {
        bail!("no scene files (.ron) in {}", show(paths));
    }
    let mut plan = Outputs::new();
    for f in &files {
        plan = plan.input(f);
    }
    if let Some(p) = junit {
        plan = plan.file_as("--junit", p, "a JUnit report (XML)", &["xml"]);
    }
    if let Some(dir) = out {
        if let Some((a, b)) = batch::colliding_outputs(&files) {
            bail!(
                "--out {}: {} and {} would write the same {}.csv; give scene files distinct names",
                dir.display(),
                a.display(),
                b.display(),
                batch::stem_of(b)
            );
        }
        plan = plan.folder("--out", dir);
    }
    plan.check()?;
    let wall = Instant::now(); // reporting only
    let runs = batch::run_scenes(&files, jobs, shard, out);
    for r in &runs {
        println!("{}", r.line());
    }
    let errors = runs.iter().filter(|r| r.outcome.is_err()).count();
    let failed = runs
        .iter()
        .filter(|r| r.outcome.is_ok() && !r.passed())
        .count();
    println!(
        "{} scenes{}: {} passed, {failed} failed, {errors} could not be loaded ({:.1} s wall, {jobs} jobs)",
        runs.len(),
        if shard == Shard::ALL {
            String::new()
        } else {
            format!(" (shard {shard})")
        },
        runs.len() - failed - errors,
        wall.elapsed().as_secs_f64()
    );
    if let Some(p) = junit {
        write_whole(p, batch::junit(&runs, files.len(), shard).as_bytes())
            .with_context(|| format!("cannot write {}", p.display()))?;
        println!("JUnit report: {}", p.display());
    }
    if shisen::tools::stop_requested() {
        return Err(
            Interrupted("before every scene ran: the report lists them as errors".into()).into(),
        );
    }
    Ok(if errors > 0 {
        ExitCode::from(2)
    } else if failed > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// Run a study (or this shard of it) into `out`, resuming what is there.
pub fn study_cmd(study: &Path, out: &Path, jobs: usize, shard: Shard) -> Result<()> {
    let s = LoadedStudy::load(study)?;
    let mut plan = Outputs::new()
        .input(study)
        .input(Path::new(&s.base.source))
        .file_as("--out", out, "CSV", &["csv"]);
    for f in s.base.files() {
        plan = plan.input(&f);
    }
    plan.check()?;
    // A run the study cannot make refuses it before its results file is
    // made (a header-only file would block the corrected re-run).
    s.check(&s.runs_of(shard))?;
    let results = ResultsFile::open(out, &s.settings(shard), &s.header())?;
    let resumed = (0..s.runs.len())
        .filter(|&k| shard.contains(k) && results.has(k))
        .count();
    let made = s.run(shard, jobs, &results)?;
    if shisen::tools::stop_requested() {
        return Err(Interrupted(format!(
            "after {made} runs: {} holds every finished run; run the same command again to resume",
            out.display()
        ))
        .into());
    }
    let path = results.finish()?;
    println!(
        "study {}: {} runs in all; this job{}: {made} run now, {resumed} resumed; results in {}",
        study.display(),
        s.runs.len(),
        if shard == Shard::ALL {
            String::new()
        } else {
            format!(" (shard {shard})")
        },
        path.display()
    );
    Ok(())
}

/// Join shard outputs: results CSVs of `study`/`sweep`, or JUnit reports
/// of `test` (`.xml`).
pub fn merge_cmd(inputs: &[PathBuf], out: &Path) -> Result<()> {
    if inputs.is_empty() {
        bail!("nothing to merge");
    }
    let mut plan = Outputs::new().file_as("--out", out, "CSV or a JUnit report", &["csv", "xml"]);
    for p in inputs {
        plan = plan.input(p);
    }
    plan.check()?;
    if out.extension().is_some_and(|e| e == "xml") {
        if out.exists() {
            bail!("{}: exists already; merge writes a new file", out.display());
        }
        let texts = inputs
            .iter()
            .map(|p| Ok(shisen::util::ron::read_text(p)?))
            .collect::<Result<Vec<_>>>()?;
        let merged = batch::merge_junit(&texts).map_err(anyhow::Error::msg)?;
        write_whole(out, merged.as_bytes())
            .with_context(|| format!("cannot write {}", out.display()))?;
        println!("{} reports merged into {}", inputs.len(), out.display());
    } else {
        let n = table::merge(inputs, out)?;
        println!(
            "{n} rows from {} files merged into {}",
            inputs.len(),
            out.display()
        );
    }
    Ok(())
}

fn show(paths: &[PathBuf]) -> String {
    paths
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}
