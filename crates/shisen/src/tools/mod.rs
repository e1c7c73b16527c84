//! Tools around the simulation: headless runs and their traces
//! ([`headless`], [`trace`]), many scenes at once ([`batch`]), studies
//! ([`study`]), the long soak ([`soak`]), PD gain tuning
//! with its metrics and plots ([`tune`], [`metrics`], [`plot`]), and the
//! MJCF export of the body plan ([`mjcf`]); results tables of many runs,
//! their shards and merge ([`table`]); outputs checked before a command starts
//! and written whole ([`output`]). Plots and parallel sweeps need
//! the `tools` feature.

#[cfg(feature = "tools")]
pub mod batch;
#[cfg(feature = "tools")]
pub mod fidelity;
pub mod headless;
pub mod metrics;
pub mod mjcf;
pub mod output;
#[cfg(feature = "tools")]
pub mod parallel;
#[cfg(feature = "tools")]
pub mod plot;
pub mod soak;
#[cfg(feature = "tools")]
pub mod study;
pub mod table;
pub mod trace;
#[cfg(feature = "tools")]
pub mod tune;

use std::sync::atomic::{AtomicBool, Ordering};

static STOP: AtomicBool = AtomicBool::new(false);

/// Ask every long job of this process to stop (the command line calls it
/// on Ctrl-C): loops over runs start no new run, and what they have
/// written stays whole and resumable.
pub fn request_stop() {
    STOP.store(true, Ordering::Relaxed);
}

/// Whether [`request_stop`] was called.
pub fn stop_requested() -> bool {
    STOP.load(Ordering::Relaxed)
}
