//! `--sound FILE`: a run's soundtrack ([`shisen::sound`]) written as a WAV
//! file as the run goes, in simulation time.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use shisen::Sim;
use shisen::sim::DT;
use shisen::sound::{RATE, Soundtrack};

/// A soundtrack listening to a run and the WAV file it goes to.
pub struct SoundFile {
    track: Soundtrack,
    wav: hound::WavWriter<BufWriter<File>>,
    buf: Vec<[f32; 2]>,
    end: f64,
    path: PathBuf,
    /// Samples heard so far, and the first to write.
    heard: u64,
    from: u64,
}

impl SoundFile {
    /// Create `path` for a run with `seed` that ends at `end` s.
    pub fn create(path: &Path, seed: u64, end: f64) -> Result<Self> {
        let spec = hound::WavSpec {
            channels: 2,
            sample_rate: RATE,
            bits_per_sample: 16,
            sample_format: hound::SampleFormat::Int,
        };
        let wav = hound::WavWriter::create(path, spec)
            .with_context(|| format!("cannot create {}", path.display()))?;
        Ok(SoundFile {
            track: Soundtrack::new(seed),
            wav,
            buf: Vec::new(),
            end,
            path: path.to_path_buf(),
            heard: 0,
            from: 0,
        })
    }

    /// Write only from time `t` s on (what comes before is heard, as the
    /// crowd's mood and the voices carry over, but not written).
    pub fn starting_at(mut self, t: f64) -> Self {
        self.from = (t * f64::from(RATE)).round() as u64;
        self
    }

    /// Hear `sim`'s last tick (on the run's last, everything still held
    /// back) and write the samples.
    pub fn hear(&mut self, sim: &Sim) -> std::io::Result<()> {
        self.track.hear(sim, &mut self.buf);
        if sim.time() >= self.end - DT / 2.0 {
            self.track.finish(sim, &mut self.buf);
        }
        let skip = self
            .from
            .saturating_sub(self.heard)
            .min(self.buf.len() as u64) as usize;
        self.heard += self.buf.len() as u64;
        for s in self.buf.drain(..).skip(skip) {
            for x in s {
                self.wav
                    .write_sample((x * f32::from(i16::MAX)) as i16)
                    .map_err(std::io::Error::other)?;
            }
        }
        Ok(())
    }

    /// Complete the file's header.
    pub fn finish(self) -> Result<()> {
        let path = self.path;
        self.wav
            .finalize()
            .with_context(|| format!("cannot write {}", path.display()))
    }
}
