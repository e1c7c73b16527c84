//! Tools around the simulation: headless runs and their traces
//! ([`headless`], [`trace`]), the long soak ([`soak`]), PD gain tuning
//! with its metrics and plots ([`tune`], [`metrics`], [`plot`]), and the
//! MJCF export of the body plan ([`mjcf`]). Plots and parallel sweeps need
//! the `tools` feature.

pub mod headless;
pub mod metrics;
pub mod mjcf;
#[cfg(feature = "tools")]
pub mod plot;
pub mod soak;
pub mod trace;
#[cfg(feature = "tools")]
pub mod tune;
