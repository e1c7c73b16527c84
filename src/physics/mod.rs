//! The body and its physics: the static body plan ([`body`]), the rapier
//! world built from it ([`world`]), and the PD joint control and gains
//! ([`control`]).

pub mod body;
pub mod control;
pub mod world;
