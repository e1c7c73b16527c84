//! Results tables of many runs (gain sweeps, studies), and how they are
//! spread over machines: a deterministic [`Shard`] of the runs per job, a
//! resumable CSV per shard ([`ResultsFile`]), and [`merge`] to join them.
//!
//! A results file is CSV with one comment line first,
//! `# shisen <kind>: <settings>`, then the header, then one row per run
//! whose first column is the run's id. Rows are appended as runs finish
//! (so an interrupted job resumes where it stopped) and sorted by id when
//! the job completes, so the file of a whole run and the merge of its
//! shards are the same bytes.

use std::collections::BTreeMap;
use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::Mutex;

/// Errors of results files.
#[derive(Debug, thiserror::Error)]
pub enum TableError {
    /// Reading or writing failed. The OS error is part of the message,
    /// not a cause behind it (so a report of the chain says it once).
    #[error("{file}: {error}")]
    Io {
        /// The file.
        file: String,
        /// The OS error.
        error: std::io::Error,
    },
    /// The file holds another kind of results, or was made with other
    /// settings: resuming or merging would mix them.
    #[error("{file}: holds results of `{found}`, not `{wanted}`; use another output or delete it")]
    Mismatch {
        /// The file.
        file: String,
        /// Its settings line.
        found: String,
        /// The settings of this run.
        wanted: String,
    },
    /// A row or line that does not belong in a results file.
    #[error("{file}:{line}: {message}")]
    Malformed {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

/// Largest results file read, bytes.
const MAX_RESULTS_BYTES: u64 = 1 << 30;

/// A results file's text (a regular file of at most [`MAX_RESULTS_BYTES`]).
fn read(path: &Path) -> Result<String, TableError> {
    shisen_gaze::util::ron::read_text_up_to(path, MAX_RESULTS_BYTES).map_err(|e| match e {
        shisen_gaze::util::ron::LoadError::Io { reason, .. } => io(path)(reason),
        other => io(path)(std::io::Error::other(other.to_string())),
    })
}

fn io(file: &Path) -> impl FnOnce(std::io::Error) -> TableError + '_ {
    move |error| TableError::Io {
        file: file.display().to_string(),
        error,
    }
}

/// A deterministic share of a job's runs: run `k` belongs to shard
/// `k mod count`. Written `I/N` with `0 <= I < N`, so it takes a Slurm
/// array's `$SLURM_ARRAY_TASK_ID` (`--array=0-N-1`) or a Kubernetes
/// Indexed Job's `$JOB_COMPLETION_INDEX` as it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0..count`.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// The whole job in one shard.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// Whether run `k` is this shard's.
    pub fn contains(&self, k: usize) -> bool {
        k % self.count == self.index
    }
}

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || format!("expected I/N with 0 <= I < N (e.g. 0/4), got `{s}`");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// A results file being written: the rows already there (resumed), and
/// new rows appended as runs finish, from any thread.
pub struct ResultsFile {
    path: PathBuf,
    settings: String,
    header: String,
    done: BTreeMap<usize, String>,
    out: Mutex<std::io::BufWriter<std::fs::File>>,
}

impl ResultsFile {
    /// Open `path` for a job described by `settings` (`# shisen <kind>:
    /// ...` without the `# `) with the CSV `header`. An existing file is
    /// resumed if it was written with the same settings and header, and
    /// refused otherwise.
    pub fn open(path: &Path, settings: &str, header: &str) -> Result<ResultsFile, TableError> {
        let mut done = BTreeMap::new();
        let exists = path.exists();
        if exists {
            let mut text = read(path)?;
            // A row cut short with no line end (a crash mid-write) would
            // have the next row glued onto it: cut the file back to its
            // last whole line, and that run is made again.
            if !text.is_empty() && !text.ends_with('\n') {
                let keep = text.rfind('\n').map_or(0, |i| i + 1);
                std::fs::OpenOptions::new()
                    .write(true)
                    .open(path)
                    .and_then(|f| f.set_len(keep as u64))
                    .map_err(io(path))?;
                text.truncate(keep);
            }
            let (found, found_header, rows) = parse(path, &text)?;
            if found != settings || found_header != header {
                return Err(TableError::Mismatch {
                    file: path.display().to_string(),
                    found,
                    wanted: settings.to_string(),
                });
            }
            done = rows;
        }
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .map_err(io(path))?;
        let mut out = std::io::BufWriter::new(file);
        if !exists {
            writeln!(out, "# {settings}\n{header}").map_err(io(path))?;
            out.flush().map_err(io(path))?;
        }
        Ok(ResultsFile {
            path: path.to_path_buf(),
            settings: settings.to_string(),
            header: header.to_string(),
            done,
            out: Mutex::new(out),
        })
    }

    /// Whether run `id` is already in the file.
    pub fn has(&self, id: usize) -> bool {
        self.done.contains_key(&id)
    }

    /// The rows already in the file when it was opened, by id.
    pub fn resumed(&self) -> &BTreeMap<usize, String> {
        &self.done
    }

    /// Append the row of run `id` (`row` without the id column) and flush,
    /// so an interrupted job loses at most the runs in flight.
    pub fn push(&self, id: usize, row: &str) -> Result<(), TableError> {
        let mut out = self.out.lock().expect("results file lock");
        writeln!(out, "{id},{row}").map_err(io(&self.path))?;
        out.flush().map_err(io(&self.path))
    }

    /// Finish the job: rewrite the file with its rows sorted by id.
    pub fn finish(self) -> Result<PathBuf, TableError> {
        let ResultsFile {
            path,
            settings,
            header,
            out,
            ..
        } = self;
        drop(out.into_inner().expect("results file lock"));
        let text = read(&path)?;
        let (_, _, rows) = parse(&path, &text)?;
        write_sorted(&path, &settings, &header, &rows)?;
        Ok(path)
    }
}

/// Settings line, header and rows (by id) of a results file.
type Parsed = (String, String, BTreeMap<usize, String>);

fn parse(path: &Path, text: &str) -> Result<Parsed, TableError> {
    parse_rows(path, text, false)
}

/// [`parse`]; `strict` refuses a row cut short instead of dropping it (a
/// shard being merged must be whole: its job finished).
fn parse_rows(path: &Path, text: &str, strict: bool) -> Result<Parsed, TableError> {
    let bad = |line: usize, message: &str| TableError::Malformed {
        file: path.display().to_string(),
        line,
        message: message.to_string(),
    };
    let mut lines = text.lines();
    let settings = lines
        .next()
        .and_then(|l| l.strip_prefix("# "))
        .ok_or_else(|| bad(1, "not a shisen results file (no `# shisen ...` line)"))?;
    let header = lines.next().ok_or_else(|| bad(2, "no header"))?;
    let columns = header.split(',').count();
    let mut rows = BTreeMap::new();
    for (k, line) in lines.enumerate() {
        let n = k + 3;
        if line.is_empty() {
            continue;
        }
        // A row cut short by an interruption is dropped (its run is redone).
        if line.split(',').count() != columns {
            if strict {
                return Err(bad(
                    n,
                    &format!(
                        "a row of {} columns, not {columns}: the job that wrote this file did not finish; run it again to complete it",
                        line.split(',').count()
                    ),
                ));
            }
            continue;
        }
        let (id, _) = line.split_once(',').unwrap_or((line, ""));
        let id: usize = id
            .parse()
            .map_err(|_| bad(n, "the first column is not a run id"))?;
        if let Some(old) = rows.insert(id, line.to_string())
            && old != line
        {
            return Err(bad(
                n,
                &format!("run {id} appears twice with different values"),
            ));
        }
    }
    Ok((settings.to_string(), header.to_string(), rows))
}

fn write_sorted(
    path: &Path,
    settings: &str,
    header: &str,
    rows: &BTreeMap<usize, String>,
) -> Result<(), TableError> {
    let mut text = format!("# {settings}\n{header}\n");
    for row in rows.values() {
        text.push_str(row);
        text.push('\n');
    }
    super::output::write_whole(path, text.as_bytes()).map_err(io(path))
}

/// Join the results files of a job's shards into `out`: they must share
/// settings (apart from the shard) and header, and the result is the file
/// the whole job would have written, rows sorted by id. The set must be
/// complete: every shard `0/N .. N-1/N` once (N from the settings line),
/// each whole (no row cut short, every run of the shard present when the
/// settings give the job's run count). Returns the number of rows. `out`
/// must not exist yet.
pub fn merge(inputs: &[PathBuf], out: &Path) -> Result<usize, TableError> {
    let refuse = |file: &Path, message: String| TableError::Malformed {
        file: file.display().to_string(),
        line: 0,
        message,
    };
    if out.exists() {
        return Err(TableError::Io {
            file: out.display().to_string(),
            error: std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                "exists already; merge writes a new file",
            ),
        });
    }
    let mut first: Option<(String, String, usize)> = None;
    // Which input holds each shard.
    let mut shard_of: BTreeMap<usize, &Path> = BTreeMap::new();
    let mut all = BTreeMap::new();
    for p in inputs {
        let text = read(p)?;
        let (full, header, rows) = parse_rows(p, &text, true)?;
        let shard = shard_in(&full)
            .ok_or_else(|| refuse(p, format!("its settings line names no shard: `{full}`")))?;
        let settings = without_shard(&full);
        match &first {
            None => first = Some((settings, header, shard.count)),
            Some((s, h, n)) if *s != settings || *h != header || *n != shard.count => {
                return Err(TableError::Mismatch {
                    file: p.display().to_string(),
                    found: full,
                    wanted: format!("{s} (in {} shards)", n),
                });
            }
            Some(_) => {}
        }
        if let Some(other) = shard_of.insert(shard.index, p) {
            return Err(refuse(
                p,
                format!(
                    "shard {shard} again (also {}); each shard is merged once",
                    other.display()
                ),
            ));
        }
        for (id, row) in rows {
            if !shard.contains(id) {
                return Err(refuse(
                    p,
                    format!("run {id} is not shard {shard}'s (run k is shard k mod N's)"),
                ));
            }
            all.insert(id, row);
        }
    }
    let (settings, header, count) = first.ok_or_else(|| refuse(out, "nothing to merge".into()))?;
    // Counted, and the first few named (the counts come from the files'
    // text, and may be huge).
    let missing = count - shard_of.len();
    if missing > 0 {
        let first: Vec<String> = (0..count)
            .filter(|i| !shard_of.contains_key(i))
            .take(5)
            .map(|i| format!("{i}/{count}"))
            .collect();
        return Err(refuse(
            out,
            format!(
                "the job has {count} shards; {missing} missing ({}{}): merge every shard's output",
                first.join(", "),
                if missing > first.len() { ", ..." } else { "" }
            ),
        ));
    }
    if let Some(runs) = pair(&settings, "runs").and_then(|r| r.parse::<usize>().ok()) {
        let absent = runs - all.range(..runs).count();
        if let Some(k) = (0..runs)
            .find(|k| !all.contains_key(k))
            .filter(|_| absent > 0)
        {
            return Err(refuse(
                shard_of[&(k % count)],
                format!(
                    "{absent} of the job's {runs} runs are missing (first: run {k}, shard {}/{count}): finish that shard's job (it resumes) and merge again",
                    k % count
                ),
            ));
        }
        if let Some((&k, _)) = all.range(runs..).next() {
            return Err(refuse(
                shard_of[&(k % count)],
                format!("run {k} is beyond the job's {runs} runs"),
            ));
        }
    }
    write_sorted(out, &settings, &header, &all)?;
    Ok(all.len())
}

/// The value of `key=` in a settings line.
fn pair<'a>(settings: &'a str, key: &str) -> Option<&'a str> {
    settings
        .split(' ')
        .find_map(|w| w.strip_prefix(key)?.strip_prefix('='))
}

/// The shard a settings line names.
fn shard_in(settings: &str) -> Option<Shard> {
    pair(settings, "shard")?.parse().ok()
}

/// The settings line with its shard set to the whole job (`shard=0/1`),
/// as a merge of every shard is.
fn without_shard(settings: &str) -> String {
    settings
        .split(' ')
        .map(|w| {
            if w.starts_with("shard=") {
                "shard=0/1"
            } else {
                w
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The settings line of a job: its kind and `key=value` pairs, with the
/// shard last (merge ignores it).
pub fn settings_line(kind: &str, pairs: &[(&str, String)], shard: Shard) -> String {
    let mut s = format!("shisen {kind}:");
    for (k, v) in pairs {
        s.push_str(&format!(" {k}={v}"));
    }
    s.push_str(&format!(" shard={shard}"));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_runs() {
        let shards: Vec<Shard> = (0..4).map(|i| format!("{i}/4").parse().unwrap()).collect();
        for k in 0..100 {
            assert_eq!(shards.iter().filter(|s| s.contains(k)).count(), 1);
        }
        assert!("4/4".parse::<Shard>().is_err());
        assert!("1/0".parse::<Shard>().is_err());
        assert!("x".parse::<Shard>().is_err());
    }

    #[test]
    fn resume_refuses_other_settings_and_keeps_rows() {
        let dir = std::env::temp_dir().join(format!("shisen-table-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("r.csv");
        let _ = std::fs::remove_file(&p);
        let f = ResultsFile::open(&p, "shisen t: a=1 shard=0/1", "id,x").unwrap();
        f.push(2, "20").unwrap();
        f.push(0, "0").unwrap();
        drop(f);
        // A row cut short, with no line end, is dropped and redone.
        let mut text = std::fs::read_to_string(&p).unwrap();
        text.push_str("1,1");
        std::fs::write(&p, text).unwrap();
        let f = ResultsFile::open(&p, "shisen t: a=1 shard=0/1", "id,x").unwrap();
        assert!(f.has(0) && f.has(2) && !f.has(1));
        f.push(1, "10").unwrap();
        f.finish().unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        assert_eq!(text, "# shisen t: a=1 shard=0/1\nid,x\n0,0\n1,10\n2,20\n");
        assert!(matches!(
            ResultsFile::open(&p, "shisen t: a=2 shard=0/1", "id,x"),
            Err(TableError::Mismatch { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    fn shard_file(dir: &Path, i: usize, n: usize, runs: usize, skip: Option<usize>) -> PathBuf {
        let p = dir.join(format!("s{i}.csv"));
        let mut text = format!("# shisen t: runs={runs} shard={i}/{n}\nid,x\n");
        for k in (0..runs).filter(|k| k % n == i && Some(*k) != skip) {
            text.push_str(&format!("{k},{}\n", k * 10));
        }
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn merge_takes_only_whole_sets_of_shards() {
        let dir = std::env::temp_dir().join(format!("shisen-merge-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("all.csv");
        let s: Vec<PathBuf> = (0..3).map(|i| shard_file(&dir, i, 3, 8, None)).collect();
        let err = |inputs: &[PathBuf]| {
            let _ = std::fs::remove_file(&out);
            merge(inputs, &out).unwrap_err().to_string()
        };
        assert!(err(&s[..2]).contains("1 missing (2/3)"), "{}", err(&s[..2]));
        assert!(err(&[s[0].clone(), s[0].clone(), s[1].clone()]).contains("shard 0/3 again"));
        let gap = shard_file(&dir, 1, 3, 8, Some(4));
        assert!(err(&[s[0].clone(), gap, s[2].clone()]).contains("run 4"));
        std::fs::write(&s[1], "# shisen t: runs=8 shard=1/3\nid,x\n1,10\n4\n7,70\n").unwrap();
        assert!(err(&s).contains("did not finish"));
        let s1 = shard_file(&dir, 1, 3, 8, None);
        let _ = std::fs::remove_file(&out);
        assert_eq!(merge(&[s[2].clone(), s1, s[0].clone()], &out).unwrap(), 8);
        let text = std::fs::read_to_string(&out).unwrap();
        assert!(text.starts_with("# shisen t: runs=8 shard=0/1\nid,x\n0,0\n1,10\n"));
        // The temporary file is gone, and no other file was made.
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 4);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
