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
    /// Reading or writing failed.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The OS error.
        source: std::io::Error,
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

fn io(file: &Path) -> impl FnOnce(std::io::Error) -> TableError + '_ {
    move |source| TableError::Io {
        file: file.display().to_string(),
        source,
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
            let text = std::fs::read_to_string(path).map_err(io(path))?;
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
        let text = std::fs::read_to_string(&path).map_err(io(&path))?;
        let (_, _, rows) = parse(&path, &text)?;
        write_sorted(&path, &settings, &header, &rows)?;
        Ok(path)
    }
}

/// Settings line, header and rows (by id) of a results file.
type Parsed = (String, String, BTreeMap<usize, String>);

fn parse(path: &Path, text: &str) -> Result<Parsed, TableError> {
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
    // Written beside and renamed over: the old file stays whole until the
    // new one is.
    let tmp = path.with_extension("csv.tmp");
    let mut text = format!("# {settings}\n{header}\n");
    for row in rows.values() {
        text.push_str(row);
        text.push('\n');
    }
    std::fs::write(&tmp, text).map_err(io(&tmp))?;
    std::fs::rename(&tmp, path).map_err(io(path))
}

/// Join the results files of a job's shards into `out`: they must share
/// settings (apart from the shard) and header, and the result is the file
/// the whole job would have written; rows are taken once each
/// (a run found in two files must have the same values) and sorted by id.
/// Returns the number of rows. `out` must not exist yet.
pub fn merge(inputs: &[PathBuf], out: &Path) -> Result<usize, TableError> {
    if out.exists() {
        return Err(TableError::Io {
            file: out.display().to_string(),
            source: std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                "exists already; merge writes a new file",
            ),
        });
    }
    let mut first: Option<(String, String)> = None;
    let mut all = BTreeMap::new();
    for p in inputs {
        let text = std::fs::read_to_string(p).map_err(io(p))?;
        let (settings, header, rows) = parse(p, &text)?;
        let settings = without_shard(&settings);
        match &first {
            None => first = Some((settings, header)),
            Some((s, h)) if *s != settings || *h != header => {
                return Err(TableError::Mismatch {
                    file: p.display().to_string(),
                    found: settings,
                    wanted: s.clone(),
                });
            }
            Some(_) => {}
        }
        for (id, row) in rows {
            if let Some(old) = all.insert(id, row.clone())
                && old != row
            {
                return Err(TableError::Malformed {
                    file: p.display().to_string(),
                    line: 0,
                    message: format!("run {id} differs from another input's"),
                });
            }
        }
    }
    let (settings, header) = first.ok_or_else(|| TableError::Malformed {
        file: out.display().to_string(),
        line: 0,
        message: "nothing to merge".into(),
    })?;
    write_sorted(out, &settings, &header, &all)?;
    Ok(all.len())
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
}
