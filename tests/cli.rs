//! The command line: exit codes and error messages for good and bad input.

use std::path::Path;
use std::process::Command;

fn shisen(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_shisen"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn write_scene(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("shisen-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

#[test]
fn a_passing_scene_exits_zero_and_prints_one_line_per_expectation() {
    let p = write_scene(
        "ok.ron",
        "Scene(duration: 0.3, expect: [Finite, AngleBelow(joint: NeckYaw, max_deg: 70.0)])",
    );
    let (code, out, err) = shisen(&["run", &p, "--headless"]);
    assert_eq!(code, 0, "{out}{err}");
    assert_eq!(
        out.lines().filter(|l| l.starts_with("PASS")).count(),
        2,
        "{out}"
    );
}

#[test]
fn a_failing_expectation_exits_one() {
    let p = write_scene(
        "fail.ron",
        "Scene(duration: 0.3, expect: [GazeShare(target: \"left_glove\", from: 0.0, to: 0.3, at_least: 0.9)])",
    );
    let (code, out, _) = shisen(&["run", &p, "--headless"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("FAIL"), "{out}");
}

/// Each bad file exits 2 with `file:line:col: field: message` and runs nothing.
#[test]
fn broken_scenes_name_file_line_and_field() {
    let cases = [
        (
            "syntax.ron",
            "Scene(\n  duration: 1.0,\n  timeline: [ (at: 1.0 ]\n)",
            ":3:",
            "-",
        ),
        (
            "unknown.ron",
            "Scene(\n  duration: 1.0,\n  sed: 4,\n)",
            ":3:",
            "sed",
        ),
        (
            "nan.ron",
            "Scene(\n  duration: 1.0,\n  timeline: [\n    (at: 0.2, do: Punch(hand: Left, target: Head, speed: NaN)),\n  ],\n)",
            ":4:",
            "timeline[0].do.Punch.speed",
        ),
        (
            "gain.ron",
            "Scene(\n  duration: 1.0,\n  gains: Gains(\n    eye: (kp: 0.03, kd: 0.0002),\n    neck: (kp: -150.0, kd: 8.0),\n    shoulder: (kp: 300.0, kd: 20.0),\n    elbow: (kp: 60.0, kd: 3.5),\n  ),\n)",
            ":5:",
            "gains.neck.kp",
        ),
        (
            "range.ron",
            "Scene(\n  duration: 1.0,\n  expect: [\n    GazeShare(target: \"head\", from: 0.0, to: 1.0, at_least: 1.5),\n  ],\n)",
            ":4:",
            "at_least",
        ),
        (
            "vacuous.ron",
            "Scene(\n  duration: 1.0,\n  expect: [\n    Finite,\n    Blows(kind: Hit, by: Vh, from: 0.0, to: 1.0),\n  ],\n)",
            ":5:",
            "expect[1].at_least",
        ),
        (
            "inverted.ron",
            "Scene(\n  duration: 1.0,\n  expect: [\n    Blows(kind: Block, by: Opponent, from: 0.0, to: 1.0,\n      at_least: 2, at_most: 1),\n  ],\n)",
            ":5:",
            "expect[0].at_most",
        ),
    ];
    for (name, text, line, field) in cases {
        let p = write_scene(name, text);
        let (code, out, err) = shisen(&["run", &p, "--headless"]);
        assert_eq!(code, 2, "{name}: {out}{err}");
        assert!(
            err.contains(&format!("{p}{line}")),
            "{name}: no file:line in {err}"
        );
        assert!(
            err.contains(field),
            "{name}: field `{field}` not named in {err}"
        );
        assert!(
            !out.contains("PASS") && !out.contains("simulated"),
            "{name} ran: {out}"
        );
    }
}

#[test]
fn a_missing_file_is_reported() {
    let (code, _, err) = shisen(&["run", "/nonexistent/scene.ron", "--headless"]);
    assert_eq!(code, 2);
    assert!(err.contains("/nonexistent/scene.ron"), "{err}");
}

#[test]
fn trace_has_the_documented_header() {
    let dir = std::env::temp_dir().join(format!("shisen-trace-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let trace = dir.join("t.csv");
    let p = write_scene("t.ron", "Scene(duration: 0.05)");
    let (code, _, err) = shisen(&[
        "run",
        &p,
        "--headless",
        "--trace",
        trace.to_str().unwrap(),
        "--trace-every",
        "10",
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&trace).unwrap();
    let header = text.lines().next().unwrap();
    assert_eq!(header, shisen::tools::trace::header());
    assert_eq!(text.lines().count(), 1 + 5, "50 ticks, every 10th");
    // every column is documented in the manual's trace table
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/headless.md"))
            .unwrap();
    for col in shisen::tools::trace::column_names() {
        assert!(
            readme.contains(&format!("`{col}`")),
            "docs/headless.md does not document column `{col}`"
        );
    }
}

#[test]
fn face_export_and_calibrate_write_their_files() {
    let dir = std::env::temp_dir().join(format!("shisen-face-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let glb = dir.join("head.glb");
    let (code, out, err) = shisen(&[
        "face",
        "export",
        "--out",
        glb.to_str().unwrap(),
        "--rows",
        "32",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let bytes = std::fs::read(&glb).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    let csv = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/face/thesis_appendix_a.csv");
    let ron = dir.join("db.ron");
    let (code, out, err) = shisen(&[
        "face",
        "calibrate",
        csv.to_str().unwrap(),
        "--out",
        ron.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    // the written database loads as a scene's face database
    let scene = write_scene(
        "db_scene.ron",
        &format!(
            "Scene(duration: 0.05, vh: (face: (database: \"{}\")))",
            ron.display()
        ),
    );
    let (code, out, err) = shisen(&["run", &scene, "--headless"]);
    assert_eq!(code, 0, "{out}{err}");
}

#[test]
fn overrides_and_arguments_are_checked_before_anything_runs() {
    let p = write_scene(
        "windows.ron",
        "Scene(duration: 2.0, expect: [GazeShare(target: \"head\", from: 0.5, to: 2.0, at_least: 0.1)])",
    );
    let (code, _, err) = shisen(&["run", &p, "--duration", "1"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--duration 1") && err.contains("expect[0]"),
        "{err}"
    );
    let (code, _, err) = shisen(&["run", &p, "--duration", "0.0001"]);
    assert_eq!(code, 2, "{err}");
    let (code, _, err) = shisen(&["run", &p, "--plot", "y.csv"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains(".png"), "{err}");
    let (code, _, err) = shisen(&["render", "default", "--at", "1e12", "--out", "x.png"]);
    assert_eq!(code, 2, "{err}");
    // Past the scene's end (the default scene lasts 10 s): refused, not
    // rendered at the end.
    let (code, _, err) = shisen(&["render", "default", "--at", "100", "--out", "x.png"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--at 100") && err.contains("end (10 s)"),
        "{err}"
    );
    // The option at fault is the one named.
    let (code, _, err) = shisen(&[
        "render", "default", "--at", "1", "--until", "2", "--fps", "100000", "--out", "x.png",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--fps 100000") && !err.contains("--slow"),
        "{err}"
    );
    // A trace stride with no trace is a mistake, not ignored.
    let (code, _, err) = shisen(&["run", &p, "--trace-every", "10"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--trace"), "{err}");
    let (code, _, err) = shisen(&["soak", "--minutes", "1e5"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--force"), "{err}");
    let (code, _, err) = shisen(&["tune", "--from-guess"]);
    assert_eq!(code, 2, "{err}");
    // Writing gains nothing tuned would copy them unchanged.
    let (code, _, err) = shisen(&["tune", "--write-gains", "g.ron"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--auto"), "{err}");
    assert!(!Path::new("g.ron").exists());
    let (code, _, err) = shisen(&["--orbit", "run", &p]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--orbit"), "{err}");
    // The window refuses a bad scene before it opens, with the run's code.
    let bad = write_scene("bad_window.ron", "Scene(duration: -1.0)");
    let (code, _, err) = shisen(&["--scene", &bad]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("bad_window.ron:1:"), "{err}");
}

#[test]
fn a_plot_writes_no_file_it_was_not_asked_for_and_dash_is_stdout() {
    let p = write_scene("plot.ron", "Scene(duration: 0.2, expect: [Finite])");
    let dir = Path::new(&p).parent().unwrap().join("plots");
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("x.png");
    let csv = dir.join("x.csv");
    std::fs::write(&csv, "mine").unwrap();
    let (code, out, err) = shisen(&["run", &p, "--plot", png.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(png.exists());
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), "mine");
    let (code, out, err) = shisen(&["run", &p, "--trace", "-"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("t,action,"), "{out}");
    assert!(err.contains("PASS"), "{err}");
    assert!(!Path::new("-").exists());
}

/// Start `shisen args`, press Ctrl-C (SIGINT) after `after`, and return
/// its exit code, how long it took to stop, and its standard error.
fn interrupt(args: &[&str], after: std::time::Duration) -> (i32, std::time::Duration, String) {
    use std::io::Read;
    let mut child = Command::new(env!("CARGO_BIN_EXE_shisen"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("binary runs");
    std::thread::sleep(after);
    let sent = std::time::Instant::now();
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(kill.success());
    let status = child.wait().unwrap();
    let took = sent.elapsed();
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    (status.code().unwrap_or(-1), took, err)
}

#[test]
fn ctrl_c_stops_long_commands_within_a_second_with_130() {
    let second = std::time::Duration::from_millis(1000);
    let (code, took, err) = interrupt(&["soak", "--minutes", "500"], second);
    assert_eq!(code, 130, "soak: {err}");
    assert!(took < 2 * second, "soak took {took:?} to stop");
    assert!(err.contains("interrupted"), "{err}");
    // A study keeps every finished run whole, and resumes.
    let dir = std::env::temp_dir().join(format!("shisen-cli-int-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("s.csv");
    let study = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/studies/attention_vs_attack.ron"
    );
    let args = [
        "study",
        study,
        "--out",
        csv.to_str().unwrap(),
        "--jobs",
        "1",
    ];
    let (code, took, err) = interrupt(&args, 3 * second);
    assert_eq!(code, 130, "study: {err}");
    assert!(took < 2 * second, "study took {took:?} to stop");
    let text = std::fs::read_to_string(&csv).unwrap();
    let columns = text.lines().nth(1).unwrap().split(',').count();
    assert!(
        text.lines()
            .skip(2)
            .all(|l| l.split(',').count() == columns),
        "a row cut short:\n{text}"
    );
    // Resuming accepts the file (and is interrupted again).
    let (code, _, err) = interrupt(&args, second);
    assert_eq!(code, 130, "resumed study: {err}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn outputs_never_overwrite_inputs_or_each_other() {
    let p = write_scene("overwrite_me.ron", "Scene(duration: 0.1)");
    let before = std::fs::read_to_string(&p).unwrap();
    let (code, _, err) = shisen(&["run", &p, "--trace", &p]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--trace") && err.contains("reads"), "{err}");
    assert_eq!(std::fs::read_to_string(&p).unwrap(), before);
    // Two scenes of one name in two folders would write one trace.
    let a = write_scene("twin.ron", "Scene(duration: 0.1)");
    let dir = Path::new(&a).parent().unwrap().join("other");
    std::fs::create_dir_all(&dir).unwrap();
    let b = dir.join("twin.ron");
    std::fs::write(&b, "Scene(duration: 0.1)").unwrap();
    let out = dir.join("runs");
    let (code, _, err) = shisen(&[
        "test",
        &a,
        b.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("twin.csv"), "{err}");
    // A missing folder is refused before the run.
    let (code, _, err) = shisen(&["run", &a, "--trace", "/nonexistent/x/t.csv"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("does not exist"), "{err}");
}

/// `run --sound`: a 20 s scene's soundtrack as a WAV (stereo, 48 kHz, 16
/// bit, the run's length), each blow of the trace heard as the sound
/// rises where its glove struck (30 ms before the row that reports it);
/// an output that is not a WAV is refused before anything runs.
#[test]
fn the_soundtrack_is_written_with_each_blow_at_its_tick() {
    let dir = std::env::temp_dir().join(format!("shisen-sound-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (wav, csv) = (dir.join("s.wav"), dir.join("s.csv"));
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/sound.ron");
    let (w, c) = (wav.to_str().unwrap(), csv.to_str().unwrap());
    let (code, out, err) = shisen(&["run", scene.to_str().unwrap(), "--sound", w, "--trace", c]);
    assert_eq!(code, 0, "{out}{err}");
    let mut r = hound::WavReader::open(&wav).unwrap();
    let spec = r.spec();
    assert_eq!(
        (spec.channels, spec.sample_rate, spec.bits_per_sample),
        (2, 48_000, 16)
    );
    let x: Vec<f32> = r
        .samples::<i16>()
        .map(|s| f32::from(s.unwrap()) / 32768.0)
        .collect();
    assert_eq!(x.len(), 2 * 20 * 48_000);
    // Level over 2 ms frames, both ears.
    let f: Vec<f32> = x
        .chunks(192)
        .map(|c| (c.iter().map(|v| v * v).sum::<f32>() / 96.0).sqrt())
        .collect();
    let trace = std::fs::read_to_string(&csv).unwrap();
    let mut lines = trace.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| head.iter().position(|h| *h == n).unwrap();
    let (tc, bc) = (col("t"), col("blows"));
    let mut blows = Vec::new();
    for l in lines {
        let v: Vec<&str> = l.split(',').collect();
        if !v[bc].is_empty() {
            blows.push(v[tc].parse::<f64>().unwrap() - 0.03);
        }
    }
    assert!(blows.len() >= 4, "{blows:?}");
    let mut last = f64::NEG_INFINITY;
    for t in blows {
        // A glove on the guard and then the head in one punch is one sound.
        if t - last < 0.045 {
            continue;
        }
        last = t;
        let k = (t / 0.002).round() as usize;
        let before = f[k - 20..k - 3].iter().copied().fold(0.0, f32::max);
        let after = f[k - 1..k + 6].iter().copied().fold(0.0, f32::max);
        assert!(
            after > 1.5 * before,
            "a blow at {t:.3} s: {after} after, {before} before"
        );
    }
    let (code, _, err) = shisen(&["run", scene.to_str().unwrap(), "--sound", "x.png"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--sound"), "{err}");
}
