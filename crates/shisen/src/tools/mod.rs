//! Tools around the simulation: headless runs and their traces
//! ([`headless`], [`trace`]), many scenes at once ([`batch`]), studies
//! ([`study`]), the long soak ([`soak`]), PD gain tuning
//! with its metrics and plots ([`tune`], [`metrics`], [`plot`]), and the
//! MJCF export of the body plan ([`mjcf`]); results tables of many runs,
//! their shards and merge ([`table`]). Plots and parallel sweeps need
//! the `tools` feature.

#[cfg(feature = "tools")]
pub mod batch;
#[cfg(feature = "tools")]
pub mod fidelity;
pub mod headless;
pub mod metrics;
pub mod mjcf;
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
