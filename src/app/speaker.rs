//! The window's sound output: the soundtrack's samples played live through
//! ALSA, whose library (`libasound.so.2`, which PulseAudio and PipeWire
//! also serve) is loaded at run time, so nothing about sound is needed to
//! build. Where there is no library or no device, the window says so once
//! and runs silent.
//!
//! The window pushes samples as the simulation makes them; a thread writes
//! them to the device a period at a time, with silence when the simulation
//! falls behind (paused, a slow frame) and the oldest samples dropped when
//! it runs ahead, so the sound never lags the picture by more than
//! [`MAX_QUEUE`].

use std::collections::VecDeque;
use std::ffi::{CStr, c_char, c_int, c_long, c_uint, c_ulong, c_void};
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use shisen::sound::RATE;

/// Frames written to the device at a time: 10 ms.
const PERIOD: usize = RATE as usize / 100;
/// Most frames waiting to be played: 120 ms; older ones are dropped.
const MAX_QUEUE: usize = RATE as usize * 12 / 100;
/// The device's buffer, microseconds.
const LATENCY_US: c_uint = 60_000;

// ALSA's constants (alsa/pcm.h).
const SND_PCM_STREAM_PLAYBACK: c_int = 0;
const SND_PCM_FORMAT_S16_LE: c_int = 2;
const SND_PCM_ACCESS_RW_INTERLEAVED: c_int = 3;

type Open = unsafe extern "C" fn(*mut *mut c_void, *const c_char, c_int, c_int) -> c_int;
type SetParams =
    unsafe extern "C" fn(*mut c_void, c_int, c_int, c_uint, c_uint, c_int, c_uint) -> c_int;
type WriteI = unsafe extern "C" fn(*mut c_void, *const c_void, c_ulong) -> c_long;
type Recover = unsafe extern "C" fn(*mut c_void, c_int, c_int) -> c_int;
type Close = unsafe extern "C" fn(*mut c_void) -> c_int;
type StrError = unsafe extern "C" fn(c_int) -> *const c_char;
type ErrorHandler = unsafe extern "C" fn(*const c_char, c_int, *const c_char, c_int, *const c_char);
type SetErrorHandler = unsafe extern "C" fn(Option<ErrorHandler>) -> c_int;

/// ALSA's error handler, replaced so that its messages (a page of them
/// where there is no sound card) do not fill the terminal: opening reports
/// its own error, once. ALSA calls it as a variadic function; the fixed
/// arguments come first in the C calling convention, and the rest are
/// not read.
unsafe extern "C" fn quiet(
    _: *const c_char,
    _: c_int,
    _: *const c_char,
    _: c_int,
    _: *const c_char,
) {
}

/// ALSA's playback functions, from the library loaded at run time.
struct Alsa {
    write: WriteI,
    recover: Recover,
    close: Close,
    strerror: StrError,
    /// Kept loaded while the functions are used.
    _lib: libloading::Library,
}

/// An open playback device.
struct Pcm {
    alsa: Alsa,
    handle: *mut c_void,
}

// SAFETY: the device handle is used by one thread at a time (it moves to
// the writer thread and stays there).
unsafe impl Send for Pcm {}

impl Pcm {
    /// Open ALSA's device `name`, stereo 16 bit at [`RATE`].
    fn open(name: &CStr) -> Result<Pcm, String> {
        // SAFETY: loading the system's ALSA library runs its initialisers,
        // which have no preconditions.
        let lib = unsafe { libloading::Library::new("libasound.so.2") }
            .map_err(|e| format!("no ALSA library ({e})"))?;
        // SAFETY: the symbols' types are ALSA's documented signatures.
        let (open, set, write, recover, close, strerror, handler) = unsafe {
            let sym = |name: &[u8]| -> Result<*const (), String> {
                lib.get::<*const ()>(name)
                    .map(|s| *s)
                    .map_err(|e| format!("ALSA without {}: {e}", String::from_utf8_lossy(name)))
            };
            (
                std::mem::transmute::<*const (), Open>(sym(b"snd_pcm_open")?),
                std::mem::transmute::<*const (), SetParams>(sym(b"snd_pcm_set_params")?),
                std::mem::transmute::<*const (), WriteI>(sym(b"snd_pcm_writei")?),
                std::mem::transmute::<*const (), Recover>(sym(b"snd_pcm_recover")?),
                std::mem::transmute::<*const (), Close>(sym(b"snd_pcm_close")?),
                std::mem::transmute::<*const (), StrError>(sym(b"snd_strerror")?),
                std::mem::transmute::<*const (), SetErrorHandler>(sym(
                    b"snd_lib_error_set_handler",
                )?),
            )
        };
        // SAFETY: a function that reads nothing, valid for the process.
        unsafe { handler(Some(quiet)) };
        let alsa = Alsa {
            write,
            recover,
            close,
            strerror,
            _lib: lib,
        };
        let mut handle = std::ptr::null_mut();
        // SAFETY: a valid out-pointer and a NUL-terminated device name.
        let e = unsafe { open(&mut handle, name.as_ptr(), SND_PCM_STREAM_PLAYBACK, 0) };
        if e < 0 {
            let name = name.to_string_lossy();
            return Err(format!("no audio device `{name}` ({})", alsa.error(e)));
        }
        let pcm = Pcm { alsa, handle };
        // SAFETY: an open handle; ALSA resamples if the device needs it.
        let e = unsafe {
            set(
                pcm.handle,
                SND_PCM_FORMAT_S16_LE,
                SND_PCM_ACCESS_RW_INTERLEAVED,
                2,
                RATE,
                1,
                LATENCY_US,
            )
        };
        if e < 0 {
            return Err(format!(
                "the audio device refused 48 kHz stereo ({})",
                pcm.alsa.error(e)
            ));
        }
        Ok(pcm)
    }

    /// Write interleaved frames, recovering from an underrun; an error
    /// that does not recover ends the playback.
    fn write(&mut self, frames: &[i16]) -> Result<(), String> {
        let n = (frames.len() / 2) as c_ulong;
        // SAFETY: `frames` holds `n` interleaved stereo frames.
        let w = unsafe { (self.alsa.write)(self.handle, frames.as_ptr().cast(), n) };
        if w < 0 {
            // SAFETY: an open handle.
            let e = unsafe { (self.alsa.recover)(self.handle, w as c_int, 1) };
            if e < 0 {
                return Err(self.alsa.error(e));
            }
        }
        Ok(())
    }
}

impl Alsa {
    fn error(&self, e: c_int) -> String {
        // SAFETY: snd_strerror returns a static NUL-terminated string.
        unsafe { CStr::from_ptr((self.strerror)(e)) }
            .to_string_lossy()
            .into_owned()
    }
}

impl Drop for Pcm {
    fn drop(&mut self) {
        // SAFETY: the handle is open and not used after this.
        unsafe { (self.alsa.close)(self.handle) };
    }
}

/// What the window and the writer thread share.
struct Shared {
    queue: Mutex<VecDeque<[f32; 2]>>,
    /// Volume 0-1 as f32 bits (0 when muted).
    volume: AtomicU32,
    stop: AtomicBool,
}

/// Live playback of the soundtrack.
pub struct Speaker {
    shared: Arc<Shared>,
    thread: Option<JoinHandle<()>>,
}

impl Speaker {
    /// Open the audio device (ALSA's `default`, or the one named by the
    /// environment variable `SHISEN_AUDIO_DEVICE`, e.g. `hw:1,0`), or say
    /// why there is none.
    pub fn open() -> Result<Speaker, String> {
        let name = std::env::var("SHISEN_AUDIO_DEVICE").unwrap_or_else(|_| "default".into());
        let name = std::ffi::CString::new(name)
            .map_err(|_| "SHISEN_AUDIO_DEVICE holds a NUL byte".to_string())?;
        Self::open_on(&name)
    }

    /// Open ALSA's device `name`.
    fn open_on(name: &CStr) -> Result<Speaker, String> {
        let mut pcm = Pcm::open(name)?;
        let shared = Arc::new(Shared {
            queue: Mutex::new(VecDeque::with_capacity(MAX_QUEUE)),
            volume: AtomicU32::new(1.0f32.to_bits()),
            stop: AtomicBool::new(false),
        });
        let s = shared.clone();
        let thread = std::thread::Builder::new()
            .name("sound".into())
            .spawn(move || {
                let mut frames = vec![0i16; PERIOD * 2];
                // Each write blocks until the device has room: the device
                // paces the loop.
                while !s.stop.load(Ordering::Relaxed) {
                    let v = f32::from_bits(s.volume.load(Ordering::Relaxed));
                    {
                        let mut q = s.queue.lock().unwrap_or_else(|e| e.into_inner());
                        for f in frames.chunks_mut(2) {
                            let x = q.pop_front().unwrap_or([0.0; 2]);
                            f[0] = (x[0] * v * f32::from(i16::MAX)) as i16;
                            f[1] = (x[1] * v * f32::from(i16::MAX)) as i16;
                        }
                    }
                    if let Err(e) = pcm.write(&frames) {
                        tracing::warn!("the sound stopped: {e}");
                        break;
                    }
                }
            })
            .map_err(|e| format!("cannot start the sound thread ({e})"))?;
        Ok(Speaker {
            shared,
            thread: Some(thread),
        })
    }

    /// Queue samples to play (the oldest dropped past [`MAX_QUEUE`]).
    pub fn play(&self, samples: &[[f32; 2]]) {
        let mut q = self.shared.queue.lock().unwrap_or_else(|e| e.into_inner());
        q.extend(samples);
        let over = q.len().saturating_sub(MAX_QUEUE);
        q.drain(..over);
    }

    /// Set the volume, 0-1 (0: muted).
    pub fn set_volume(&self, v: f32) {
        self.shared
            .volume
            .store(v.clamp(0.0, 1.0).to_bits(), Ordering::Relaxed);
    }
}

impl Drop for Speaker {
    fn drop(&mut self) {
        self.shared.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A device that is not there is a reason in words, not a crash.
    #[test]
    fn no_device_is_a_reason_not_a_crash() {
        let why = Speaker::open_on(c"shisen-no-such-device")
            .err()
            .expect("no such device");
        assert!(
            why.contains("no audio device") || why.contains("ALSA"),
            "{why}"
        );
    }

    /// On ALSA's null device (there wherever the library is), what is
    /// queued is played out, and the player stops when dropped.
    #[test]
    fn queued_sound_is_played_and_the_player_stops() {
        let s = Speaker::open_on(c"null")
            .unwrap_or_else(|why| panic!("{why} (the test needs libasound2 installed)"));
        s.play(&[[0.5; 2]; PERIOD * 4]);
        let left = || s.shared.queue.lock().unwrap().len();
        let t = std::time::Instant::now();
        while left() > 0 && t.elapsed().as_secs() < 5 {
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        assert_eq!(left(), 0, "played");
        // More than the queue holds: the oldest go.
        s.set_volume(0.0);
        s.play(&vec![[0.1; 2]; MAX_QUEUE * 2]);
        assert!(left() <= MAX_QUEUE);
        drop(s);
    }
}
