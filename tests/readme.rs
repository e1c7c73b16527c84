//! Every command the README and the manual (docs/) show runs and does
//! what they say.
//!
//! The commands are taken from the `sh` blocks of the README and the
//! manual's pages ([`PAGES`], in this order): each line that starts with
//! `cargo run --release` or `shisen` (a trailing `# comment` dropped), and
//! each `cargo run -p CRATE --example NAME` (run as the example `cargo
//! test` built). They run in that order, in one scratch folder where
//! `scenes/`, `docs/` and `crates/` are the repository's (the pages of
//! `ALONE` beside the rest, in a folder of their own), with this
//! build's binary in place of `cargo run --release --` and `shisen`; each
//! must exit 0 (or the code its comment names, `# exit N`) and print no
//! error. Commands that open the window run under a display only (ignored
//! here; CI runs them under Xvfb with `--exit-after`). Cargo, pip, pytest
//! and bench lines are the pages' own set-up and are run by CI as such.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The pages whose commands are checked, in the order they run (a page's
/// commands may read what an earlier page's wrote).
const PAGES: [&str; 11] = [
    "README.md",
    "docs/headless.md",
    "docs/scenes.md",
    "docs/window.md",
    "docs/renders.md",
    "docs/the-face.md",
    "docs/tools.md",
    "docs/fidelity.md",
    "docs/python.md",
    "docs/performance.md",
    "docs/architecture.md",
];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn page(name: &str) -> String {
    std::fs::read_to_string(root().join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A command of a page: where it is, the shell text, and the exit code it
/// must end with.
#[derive(Debug)]
struct Line {
    page: String,
    number: usize,
    shell: String,
    exit: i32,
    window: bool,
}

/// Where `cargo test` put the workspace's examples.
fn examples_dir() -> PathBuf {
    Path::new(env!("CARGO_BIN_EXE_shisen"))
        .parent()
        .expect("the binary's folder")
        .join("examples")
}

/// The commands of one page's `sh` blocks, in order.
fn commands_of(name: &str, text: &str) -> Vec<Line> {
    let bin = env!("CARGO_BIN_EXE_shisen");
    let mut out = Vec::new();
    let mut in_sh = false;
    for (k, raw) in text.lines().enumerate() {
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
        let line = |shell: String, exit: i32, window: bool| Line {
            page: name.to_string(),
            number: k + 1,
            shell,
            exit,
            window,
        };
        // `cargo run -p CRATE --example NAME [-- ARGS]`: the built example.
        if let Some(r) = cmd.strip_prefix("cargo run -p ") {
            let mut words = r.split_whitespace();
            let _crate = words.next();
            assert_eq!(words.next(), Some("--example"), "{name}:{}: {t}", k + 1);
            let example = words.next().expect("an example's name");
            let args: Vec<&str> = words.skip_while(|w| *w == "--").collect();
            let exe = examples_dir().join(example);
            out.push(line(
                format!("{} {}", exe.display(), args.join(" ")),
                0,
                false,
            ));
            continue;
        }
        let rest = if let Some(r) = cmd.strip_prefix("cargo run --release") {
            r.trim_start().strip_prefix("--").unwrap_or(r).trim_start()
        } else if let Some(r) = cmd.strip_prefix("shisen ") {
            r
        } else if cmd.starts_with("for ") && cmd.contains("shisen ") {
            // A loop over shards: `for i in 0 1; do shisen ...; done`.
            out.push(line(cmd.replace("shisen ", &format!("{bin} ")), 0, false));
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
        out.push(line(format!("{bin} {rest}"), exit, window));
    }
    out
}

/// Every page's commands, pages in [`PAGES`] order.
fn commands() -> Vec<Line> {
    PAGES
        .iter()
        .flat_map(|&name| commands_of(name, &page(name)))
        .collect()
}

/// A manual page with commands that [`PAGES`] leaves out would never be
/// checked.
#[test]
fn every_page_with_commands_is_checked() {
    for entry in std::fs::read_dir(root().join("docs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            let name = format!("docs/{}", path.file_name().unwrap().to_string_lossy());
            let text = std::fs::read_to_string(&path).unwrap();
            if !commands_of(&name, &text).is_empty() {
                assert!(
                    PAGES.contains(&name.as_str()),
                    "{name} shows commands: add it to PAGES"
                );
            }
        }
    }
}

/// A scratch folder with the repository's scenes and docs in it.
fn scratch(name: &str) -> PathBuf {
    let root = root();
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
        "{} line {}: `{}` exited {code} (want {}):\n{stderr}",
        line.page,
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
        assert!(has(w), "no command with `{w}` in the README or the manual");
    }
    assert!(c.iter().any(|l| l.window));
    assert!(c.iter().any(|l| l.shell.contains("/examples/")));
}

/// Pages whose commands read nothing another page's write, and write
/// nothing another page's read: they run in a scratch folder of their
/// own, beside the others (the fidelity battery's runs are most of this
/// test's time).
const ALONE: [&str; 1] = ["docs/fidelity.md"];

#[test]
fn every_headless_readme_command_runs_as_documented() {
    let (alone, chained): (Vec<Line>, Vec<Line>) = commands()
        .into_iter()
        .filter(|l| !l.window)
        .partition(|l| ALONE.contains(&l.page.as_str()));
    assert!(!alone.is_empty(), "no command on the pages of ALONE");
    let (dir, alone_dir) = (scratch("commands"), scratch("commands-alone"));
    std::thread::scope(|s| {
        let beside = s.spawn(|| alone.iter().for_each(|line| run(&alone_dir, line, "")));
        chained.iter().for_each(|line| run(&dir, line, ""));
        if let Err(failed) = beside.join() {
            std::panic::resume_unwind(failed);
        }
    });
    for d in [dir, alone_dir] {
        let _ = std::fs::remove_dir_all(d);
    }
}

/// The example scenes of the README and the manual (`ron` blocks that are
/// a `Scene`), each run as written from a folder beside the shipped gains:
/// every expectation holds.
#[test]
fn the_readme_example_scenes_pass_their_own_expectations() {
    let dir = scratch("examples");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::os::unix::fs::symlink(root.join("scenes/gains"), dir.join("gains")).unwrap();
    let mut n = 0;
    let mut block: Option<(usize, String)> = None;
    let texts: Vec<(&str, String)> = PAGES.iter().map(|&p| (p, page(p))).collect();
    for (name, l, k) in texts
        .iter()
        .flat_map(|(name, text)| text.lines().enumerate().map(move |(k, l)| (*name, l, k)))
    {
        match (&mut block, l.trim()) {
            (None, "```ron") => block = Some((k + 2, String::new())),
            (Some((start, text)), "```") => {
                if text.trim_start().starts_with("Scene(") {
                    let file = dir.join(format!("example{n}.ron"));
                    std::fs::write(&file, &text).unwrap();
                    let line = Line {
                        page: name.to_string(),
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
    assert!(n >= 1, "no example scene in the README or the manual");
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
