//! Studies: one base scene run many times with some of its fields varied
//! (personalities x opponents x seeds...), one CSV row per run.
//!
//! A study file (RON) names the base scene (relative to the study file),
//! the fields to vary, each by a list of values or an evenly spaced range,
//! and the seeds:
//!
//! ```ron
//! Study(
//!     scene: "../scenes/wave.ron",
//!     vary: [
//!         (field: "vh.personality.a_face", values: [1.0, 1.5, 2.0]),
//!         (field: "vh.behaviour.attack_rate", range: (from: 0.2, to: 1.0, steps: 5)),
//!     ],
//!     seeds: Range(from: 1, to: 10),
//! )
//! ```
//!
//! The runs are the product of every field's values and the seeds, in
//! that order (the first field varies slowest, the seed fastest); run `k`
//! is the `k`-th of them, so a [`Shard`] takes a fixed share. A field is a
//! dotted path into the scene as its file writes it (`timeline[2].at`
//! works too); each run's scene is validated like a file, so a value out
//! of range or an expectation window past a varied `duration` is an
//! error naming the run. Results go to a resumable [`ResultsFile`]: run,
//! seed, the varied values, whether every expectation held, VH resets,
//! saccades, head movements, then each expectation's measured value and
//! verdict.

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::scene::{LoadedScene, Scene};
use crate::tools::table::{ResultsFile, Shard, settings_line};
use crate::tools::{headless, parallel};
use shisen_gaze::util::ron::{LoadError, parse_ron, read_text};

/// A study file.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Study {
    /// The base scene, relative to the study file.
    pub scene: PathBuf,
    /// The fields to vary, at most 1000 (far more than a study varies:
    /// each is tried on a copy of the scene when the study loads).
    #[serde(default)]
    #[schemars(length(max = 1000))]
    pub vary: Vec<Vary>,
    /// The seeds (default: the scene's own).
    #[serde(default)]
    pub seeds: Option<Seeds>,
}

/// One varied field.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Vary {
    /// Dotted path of the field in the scene (`vh.personality.a_face`).
    pub field: String,
    /// Its values, in the field's unit: each within +-1e9 (finite and
    /// sane; each run's scene is checked against the field's own range),
    /// at most [`MAX_RUNS`] of them...
    #[serde(default)]
    #[schemars(length(max = MAX_RUNS), inner(range(min = -1e9, max = 1e9)))]
    pub values: Vec<f64>,
    /// ... or an evenly spaced range.
    #[serde(default)]
    pub range: Option<Range>,
}

/// `steps` evenly spaced values from `from` to `to` inclusive.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Range {
    /// First value, in the field's unit, within +-1e9 (each run's scene
    /// is checked against the field's own range).
    #[schemars(range(min = -1e9, max = 1e9))]
    pub from: f64,
    /// Last value, likewise within +-1e9.
    #[schemars(range(min = -1e9, max = 1e9))]
    pub to: f64,
    /// Number of values, 2 to [`MAX_RUNS`] (the values are made before
    /// the study's runs are counted).
    #[schemars(range(min = 2, max = MAX_RUNS))]
    pub steps: usize,
}

/// The seeds of a study.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum Seeds {
    /// These seeds: 1 to [`MAX_RUNS`] of them, each any 64-bit seed.
    List(
        #[schemars(length(min = 1, max = MAX_RUNS), inner(range(min = 0, max = u64::MAX)))]
        Vec<u64>,
    ),
    /// Every seed from `from` to `to` inclusive.
    Range {
        /// First seed, 0 to 1000000 (a range's seeds are listed before the
        /// study's runs are counted; name larger seeds in a `List`).
        #[schemars(range(min = 0, max = MAX_RANGE_SEED))]
        from: u64,
        /// Last seed, 0 to 1000000 (at least `from`).
        #[schemars(range(min = 0, max = MAX_RANGE_SEED))]
        to: u64,
    },
}

/// Most runs a study may expand to (a typo such as `steps: 10000` in two
/// fields should not start a hundred-million-run job), and most values a
/// varied field or a seed list may give: every run's scene is made and
/// checked before the first starts.
pub const MAX_RUNS: usize = 100_000;

/// Largest seed a [`Seeds::Range`] may name: its seeds are listed before
/// the runs are counted, so this keeps that list under 8 MB.
pub const MAX_RANGE_SEED: u64 = 1_000_000;

/// A study, loaded: its base scene and its runs.
pub struct LoadedStudy {
    /// The study file.
    pub file: PathBuf,
    /// The base scene.
    pub base: LoadedScene,
    /// The varied fields.
    pub fields: Vec<String>,
    /// Each run's values of the fields, and its seed.
    pub runs: Vec<(Vec<f64>, u64)>,
    /// A fingerprint of the study and scene text (a results file made from
    /// other text is not resumed).
    pub fingerprint: u64,
    /// The study file's text (errors of a run point into it).
    text: String,
}

impl LoadedStudy {
    /// Load a study file and its base scene, and expand its runs.
    pub fn load(path: &Path) -> Result<LoadedStudy, LoadError> {
        let text = read_text(path)?;
        let study: Study = parse_ron(&text, path)?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let scene_path = dir.join(&study.scene);
        let base = LoadedScene::load(&scene_path)?;
        let scene_text = read_text(&scene_path)?;
        let invalid =
            |field: String, message: String| LoadError::at_field(path, &text, field, message);
        let template = scene_value(&base.scene);
        let mut axes = Vec::new();
        for (i, v) in study.vary.iter().enumerate() {
            let values = match (&v.range, v.values.is_empty()) {
                (Some(r), true) => {
                    if r.steps < 2 {
                        return Err(invalid(
                            format!("vary[{i}].range.steps"),
                            format!("must be at least 2, got {}", r.steps),
                        ));
                    }
                    (0..r.steps)
                        .map(|k| r.from + (r.to - r.from) * k as f64 / (r.steps - 1) as f64)
                        .collect()
                }
                (None, false) => v.values.clone(),
                _ => {
                    return Err(invalid(
                        format!("vary[{i}]"),
                        "give either `values` or `range`".into(),
                    ));
                }
            };
            if let Some(bad) = values.iter().find(|x| !x.is_finite()) {
                return Err(invalid(
                    format!("vary[{i}].values"),
                    format!("must be finite, got {bad}"),
                ));
            }
            if let Some(j) = study.vary[..i].iter().position(|w| w.field == v.field) {
                return Err(invalid(
                    format!("vary[{i}].field"),
                    format!("`{}` is varied twice (vary[{j}] varies it too)", v.field),
                ));
            }
            if v.field.starts_with("vh.face") || v.field == "seed" {
                return Err(invalid(
                    format!("vary[{i}].field"),
                    format!(
                        "`{}` cannot be varied (seeds go in `seeds`; the face is shared)",
                        v.field
                    ),
                ));
            }
            let mut probe = template.clone();
            if let Err(m) = set_field(&mut probe, &v.field, values[0]) {
                return Err(invalid(format!("vary[{i}].field"), m));
            }
            axes.push(values);
        }
        let seeds = match &study.seeds {
            None => vec![base.scene.seed],
            Some(Seeds::List(s)) if !s.is_empty() => s.clone(),
            // Counted before it is listed.
            Some(Seeds::Range { from, to }) if from <= to && to - from < MAX_RUNS as u64 => {
                (*from..=*to).collect()
            }
            Some(Seeds::Range { from, to }) if from <= to => {
                return Err(invalid(
                    "seeds".into(),
                    format!(
                        "{} seeds: more than the {MAX_RUNS} runs a study may have",
                        to - from + 1
                    ),
                ));
            }
            Some(Seeds::Range { from, to }) => {
                return Err(invalid(
                    "seeds".into(),
                    format!(
                        "Range(from: {from}, to: {to}) holds no seed: `to` must be at least `from`"
                    ),
                ));
            }
            Some(Seeds::List(_)) => {
                return Err(invalid(
                    "seeds".into(),
                    "an empty list: give at least one seed".into(),
                ));
            }
        };
        let total = axes
            .iter()
            .map(Vec::len)
            .chain([seeds.len()])
            .try_fold(1usize, |n, k| n.checked_mul(k))
            .filter(|&n| n <= MAX_RUNS);
        let Some(total) = total else {
            return Err(invalid(
                "vary".into(),
                format!("expands to more than {MAX_RUNS} runs"),
            ));
        };
        let mut runs = Vec::with_capacity(total);
        for k in 0..total {
            let mut rest = k;
            let seed = seeds[rest % seeds.len()];
            rest /= seeds.len();
            let mut values = vec![0.0; axes.len()];
            for (a, axis) in axes.iter().enumerate().rev() {
                values[a] = axis[rest % axis.len()];
                rest /= axis.len();
            }
            runs.push((values, seed));
        }
        Ok(LoadedStudy {
            file: path.to_path_buf(),
            fields: study.vary.iter().map(|v| v.field.clone()).collect(),
            runs,
            fingerprint: fnv(&[text.as_bytes(), scene_text.as_bytes()]),
            base,
            text,
        })
    }

    /// The settings line of this study's results file.
    pub fn settings(&self, shard: Shard) -> String {
        let name = self
            .file
            .file_name()
            .map_or(String::new(), |n| n.to_string_lossy().into_owned());
        settings_line(
            "study",
            &[
                ("file", name),
                ("runs", self.runs.len().to_string()),
                ("text", format!("{:016x}", self.fingerprint)),
            ],
            shard,
        )
    }

    /// The CSV header of this study's results.
    pub fn header(&self) -> String {
        let mut h = String::from("run,seed");
        for f in &self.fields {
            h.push(',');
            h.push_str(&f.replace(',', ";"));
        }
        h.push_str(",passed,resets,saccades,head_moves");
        for i in 0..self.base.scene.expect.len() {
            h.push_str(&format!(",expect{i},expect{i}_pass"));
        }
        h
    }

    /// The scene of run `k`, validated like a file. An error names the
    /// study file at the varied field it comes from (or its `scene`), the
    /// run and its values, and the scene's field at fault.
    pub fn scene(&self, k: usize) -> Result<LoadedScene, LoadError> {
        let (values, seed) = &self.runs[k];
        let fields: Vec<(&str, f64)> = self
            .fields
            .iter()
            .map(String::as_str)
            .zip(values.iter().copied())
            .collect();
        let label = format!("{} run {k}", self.file.display());
        edit_scene(&self.base, &fields, Some(*seed), &label).map_err(|e| {
            let (field, message) = match e {
                LoadError::Invalid { field, message, .. } => (field, message),
                LoadError::Io { reason, .. } => ("-".into(), reason.to_string()),
            };
            // The varied field the error is in, else the base scene.
            let at = self
                .fields
                .iter()
                .position(|f| field.starts_with(f.as_str()) || f.starts_with(field.as_str()))
                .map_or("scene".to_string(), |i| format!("vary[{i}]"));
            let values: Vec<String> = fields.iter().map(|(f, x)| format!("{f} = {x}")).collect();
            LoadError::at_field(
                &self.file,
                &self.text,
                at,
                format!(
                    "run {k} ({}, seed {seed}): {field}: {message}",
                    values.join(", ")
                ),
            )
        })
    }

    /// Check the scenes of runs `runs` (the first bad one's error): a
    /// study is refused whole before anything is written.
    pub fn check(&self, runs: &[usize]) -> Result<(), LoadError> {
        for &k in runs {
            self.scene(k)?;
        }
        Ok(())
    }

    /// The runs of `shard`.
    pub fn runs_of(&self, shard: Shard) -> Vec<usize> {
        (0..self.runs.len())
            .filter(|&k| shard.contains(k))
            .collect()
    }

    /// Run this `shard` of the study on `jobs` threads into `results`
    /// (runs already there are skipped), with a progress bar. Returns the
    /// number of runs made now.
    pub fn run(&self, shard: Shard, jobs: usize, results: &ResultsFile) -> anyhow::Result<usize> {
        let todo: Vec<usize> = (0..self.runs.len())
            .filter(|&k| shard.contains(k) && !results.has(k))
            .collect();
        // Every run's scene is checked before any simulation starts (and
        // made again when its run starts: a study's scenes are not all
        // held at once).
        self.check(&todo)?;
        let bar = parallel::bar(todo.len() as u64, "runs");
        let made = std::sync::atomic::AtomicUsize::new(0);
        parallel::pool(jobs).install(|| {
            todo.par_iter().try_for_each(|&k| {
                // Ctrl-C: no new run starts; one cut short is not written.
                if super::stop_requested() {
                    return Ok(());
                }
                let r = headless::run(&self.scene(k)?, None, None, 1)?;
                if r.interrupted {
                    return Ok(());
                }
                let (values, seed) = &self.runs[k];
                let mut row = seed.to_string();
                for x in values {
                    row.push_str(&format!(",{x}"));
                }
                row.push_str(&format!(
                    ",{},{},{},{}",
                    u8::from(r.passed()),
                    r.resets,
                    r.saccades,
                    r.head_moves
                ));
                for v in &r.verdicts {
                    row.push_str(&format!(",{},{}", v.value, u8::from(v.pass)));
                }
                results.push(k, &row)?;
                made.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                bar.inc(1);
                anyhow::Ok(())
            })
        })?;
        bar.finish_and_clear();
        Ok(made.into_inner())
    }
}

/// `base` with the numbers at dotted field paths (`vh.personality.a_face`,
/// `timeline[2].do.speed`) set, and its seed if given, validated like a
/// file (`label` names it in errors). Gains go inline, so they can be
/// varied too (`gains.neck.kp`).
pub fn edit_scene(
    base: &LoadedScene,
    fields: &[(&str, f64)],
    seed: Option<u64>,
    label: &str,
) -> Result<LoadedScene, LoadError> {
    let invalid =
        |field: &str, message: String| LoadError::invalid(Path::new(label), (1, 1), field, message);
    let mut scene = base.scene.clone();
    scene.gains = Some(base.gains.clone());
    scene.gains_file = None;
    let mut v = scene_value(&scene);
    for (f, x) in fields {
        set_field(&mut v, f, *x).map_err(|e| invalid(f, e))?;
    }
    let mut scene: Scene = serde_json::from_value(v).map_err(|e| invalid("-", e.to_string()))?;
    if let Some(seed) = seed {
        scene.seed = seed;
    }
    let scene = Scene::parse(&scene.to_ron(), Path::new(label))?;
    Ok(LoadedScene {
        gains: scene.gains.clone().unwrap_or_else(|| base.gains.clone()),
        scene,
        face: base.face.clone(),
        source: label.to_string(),
    })
}

/// The scene as a JSON value (the field paths of its file).
fn scene_value(scene: &Scene) -> Value {
    serde_json::to_value(scene).expect("scenes serialise")
}

/// Set the number at dotted `path` (`a.b[2].c`) of `v`, keeping integers
/// integral. The field must exist and hold a number.
fn set_field(v: &mut Value, path: &str, x: f64) -> Result<(), String> {
    let mut cur = v;
    for part in path.split('.') {
        let (key, idx) = match part.split_once('[') {
            Some((k, rest)) => {
                let i: usize = rest
                    .strip_suffix(']')
                    .and_then(|s| s.parse().ok())
                    .ok_or_else(|| format!("`{path}`: bad index in `{part}`"))?;
                (k, Some(i))
            }
            None => (part, None),
        };
        if !key.is_empty() {
            cur = descend(cur, key).ok_or_else(|| no_field(path, key))?;
        }
        if let Some(i) = idx {
            cur = cur
                .get_mut(i)
                .ok_or_else(|| format!("`{path}`: no element {i} in `{key}`"))?;
        }
    }
    let n = match cur {
        Value::Number(n) if n.is_f64() => serde_json::Number::from_f64(x),
        Value::Number(_) if x.fract() == 0.0 && x >= 0.0 => Some((x as u64).into()),
        Value::Number(_) => return Err(format!("`{path}` takes whole numbers, got {x}")),
        other => return Err(format!("`{path}` is not a number (it is {other})")),
    };
    *cur = Value::Number(n.ok_or_else(|| format!("`{path}`: {x} is not a number"))?);
    Ok(())
}

/// The member `key` of an object, or of the single variant an enum value
/// is (`{"Punch": {"speed": ..}}` reached as `do.Punch.speed` or `do.speed`).
fn descend<'a>(v: &'a mut Value, key: &str) -> Option<&'a mut Value> {
    let obj = v.as_object_mut()?;
    if obj.contains_key(key) {
        return obj.get_mut(key);
    }
    if obj.len() == 1 {
        return obj.values_mut().next()?.as_object_mut()?.get_mut(key);
    }
    None
}

fn no_field(path: &str, key: &str) -> String {
    format!("`{path}`: the scene has no field `{key}` there")
}

/// FNV-1a over some byte strings.
fn fnv(parts: &[&[u8]]) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for p in parts {
        for &b in *p {
            h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
        h = (h ^ 0xff).wrapping_mul(0x0100_0000_01b3);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_are_set_by_path_and_checked() {
        let scene = LoadedScene::default_scene().scene;
        let mut v = scene_value(&scene);
        set_field(&mut v, "vh.personality.a_face", 2.5).unwrap();
        set_field(&mut v, "timeline[0].at", 0.25).unwrap();
        let back: Scene = serde_json::from_value(v.clone()).unwrap();
        assert_eq!(back.vh.personality.a_face, 2.5);
        assert_eq!(back.timeline[0].at, 0.25);
        assert!(
            set_field(&mut v, "vh.personality.a_fcae", 1.0)
                .unwrap_err()
                .contains("a_fcae")
        );
        assert!(set_field(&mut v, "timeline[99].at", 1.0).is_err());
        assert!(
            set_field(&mut v, "name", 1.0)
                .unwrap_err()
                .contains("not a number")
        );
    }
}
