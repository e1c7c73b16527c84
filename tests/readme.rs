//! Every command the README shows runs and does what the README says.
//!
//! The commands are taken from the README's `sh` blocks: each line that
//! starts with `cargo run --release` or `shisen` (a trailing `# comment`
//! dropped). They run in README order, in one scratch folder where
//! `scenes/` and `docs/` are the repository's, with this build's binary
//! in place of `cargo run --release --` and `shisen`; each must exit 0
//! (or the code its comment names, `# exit N`) and print no error.
//! Commands that open the window run under a display only (ignored here;
//! CI runs them under Xvfb with `--exit-after`). Cargo, pip, pytest and
//! bench lines are the README's own set-up and are run by CI as such.

use std::path::{Path, PathBuf};
use std::process::Command;

const README: &str = include_str!("../README.md");

/// A README command: its line, the shell text, and the exit code it must
/// end with.
#[derive(Debug)]
struct Line {
    number: usize,
    shell: String,
    exit: i32,
    window: bool,
}

/// The shisen commands of the README's `sh` blocks, in order.
fn commands() -> Vec<Line> {
    let bin = env!("CARGO_BIN_EXE_shisen");
    let mut out = Vec::new();
    let mut in_sh = false;
    for (k, raw) in README.lines().enumerate() {
        let t = raw.trim();
        if t.starts_with("```") {
            in_sh = t == "```sh";
            continue;
        }
        if !in_sh {
            continue;
        }
        let (cmd, comment) = match t.find(" #") {
            Some(i) => (t[..i].trim(), t[i + 2..].trim()),
            None => (t, ""),
        };
        let rest = if let Some(r) = cmd.strip_prefix("cargo run --release") {
            r.trim_start().strip_prefix("--").unwrap_or(r).trim_start()
        } else if let Some(r) = cmd.strip_prefix("shisen ") {
            r
        } else if cmd.starts_with("for ") && cmd.contains("shisen ") {
            // A loop over shards: `for i in 0 1; do shisen ...; done`.
            out.push(Line {
                number: k + 1,
                shell: cmd.replace("shisen ", &format!("{bin} ")),
                exit: 0,
                window: false,
            });
            continue;
        } else {
            continue;
        };
        let exit = comment
            .split_once("exit ")
            .and_then(|(_, n)| {
                let digits: String = n.chars().take_while(char::is_ascii_digit).collect();
                digits.parse().ok()
            })
            .unwrap_or(0);
        // The window: no subcommand (nothing, or options first).
        let window =
            rest.is_empty() || (rest.starts_with("--") && !rest.starts_with("--print-bindings"));
        out.push(Line {
            number: k + 1,
            shell: format!("{bin} {rest}"),
            exit,
            window,
        });
    }
    out
}

/// A scratch folder with the repository's scenes and docs in it.
fn scratch(name: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::env::temp_dir().join(format!("shisen-readme-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for d in ["scenes", "docs", "crates"] {
        std::os::unix::fs::symlink(root.join(d), dir.join(d)).unwrap();
    }
    dir
}

fn run(dir: &Path, line: &Line, extra: &str) {
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("{}{extra}", line.shell))
        .current_dir(dir)
        // Mesa's device-select layer prints "error: XDG_RUNTIME_DIR ..."
        // under a bare X server; it is not the command's error.
        .env("NODEVICE_SELECT", "1")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let code = out.status.code().unwrap_or(-1);
    assert!(
        code == line.exit && !stderr.contains("error:") && !stderr.contains("panicked"),
        "README line {}: `{}` exited {code} (want {}):\n{stderr}",
        line.number,
        line.shell,
        line.exit
    );
}

#[test]
fn the_readme_shows_commands_of_every_kind() {
    let c = commands();
    let has = |w: &str| c.iter().any(|l| l.shell.contains(w));
    for w in [
        " run ",
        " test",
        " study ",
        " merge ",
        " render ",
        " fidelity",
        " tune",
        " soak",
        " face ",
        " schema",
    ] {
        assert!(has(w), "no README command with `{w}`");
    }
    assert!(c.iter().any(|l| l.window));
}

#[test]
fn every_headless_readme_command_runs_as_documented() {
    let dir = scratch("commands");
    for line in commands().iter().filter(|l| !l.window) {
        run(&dir, line, "");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The README's example scenes (`ron` blocks that are a `Scene`), each
/// run as written from a folder beside the shipped gains: every
/// expectation holds.
#[test]
fn the_readme_example_scenes_pass_their_own_expectations() {
    let dir = scratch("examples");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::os::unix::fs::symlink(root.join("scenes/gains"), dir.join("gains")).unwrap();
    let mut n = 0;
    let mut block: Option<(usize, String)> = None;
    for (k, l) in README.lines().enumerate() {
        match (&mut block, l.trim()) {
            (None, "```ron") => block = Some((k + 2, String::new())),
            (Some((start, text)), "```") => {
                if text.trim_start().starts_with("Scene(") {
                    let file = dir.join(format!("example{n}.ron"));
                    std::fs::write(&file, &text).unwrap();
                    let line = Line {
                        number: *start,
                        shell: format!("{} run {}", env!("CARGO_BIN_EXE_shisen"), file.display()),
                        exit: 0,
                        window: false,
                    };
                    run(&dir, &line, "");
                    n += 1;
                }
                block = None;
            }
            (Some((_, text)), _) => {
                text.push_str(l);
                text.push('\n');
            }
            (None, _) => {}
        }
    }
    assert!(n >= 1, "no example scene in the README");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
#[ignore = "opens the window: needs a display (CI runs it under Xvfb)"]
fn every_window_readme_command_opens_and_closes() {
    let dir = scratch("window");
    // Files the window commands read are made by the commands before them.
    for line in commands() {
        if line.window {
            run(&dir, &line, " --exit-after 2");
        } else if line.shell.contains("--print-bindings") {
            run(&dir, &line, "");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
