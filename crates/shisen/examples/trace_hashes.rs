//! Run scene files headless and print one line per scene: its file, the
//! number of ticks and a 64-bit FNV-1a hash of its whole trace (every
//! column of every tick, as `shisen run --trace` writes it).
//!
//! Two builds of this example for different CPU feature levels (or one
//! run with the C library's CPU dispatch narrowed) must print the same
//! lines: tests/determinism.rs compares them.
//!
//!     cargo run --release -p shisen --features tools --example trace_hashes -- scenes/*.ron

use std::io::Write;
use std::path::PathBuf;

use shisen::scene::LoadedScene;

/// FNV-1a, 64 bits: a hash with a fixed definition (std's hasher may change
/// between Rust releases; these hashes are compared across builds).
struct Fnv(u64);

impl Write for Fnv {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        for &b in buf {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

fn main() -> anyhow::Result<()> {
    let paths: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    anyhow::ensure!(!paths.is_empty(), "usage: trace_hashes SCENE.ron...");
    for path in paths {
        let scene = LoadedScene::load(&path)?;
        let mut hash = Fnv(0xcbf2_9ce4_8422_2325);
        let report = shisen::tools::headless::run(&scene, None, Some(&mut hash), 1)?;
        println!("{} {} {:016x}", path.display(), report.ticks, hash.0);
    }
    Ok(())
}
