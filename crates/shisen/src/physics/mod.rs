//! The body and its physics: the static body plan ([`body`]), the rapier
//! world built from it ([`world`]), the opponent's driven parts
//! ([`opponent`]), the PD joint control and gains ([`control`]), the neck
//! under impact ([`neck`]), the legs, footwork and waist as planned
//! ([`lower`]), the physical pelvis and legs ([`legs`]) and the balance
//! that keeps them up ([`balance`]), and the gains' plausibility for the
//! body ([`plausible`]).

pub mod balance;
pub mod body;
pub mod control;
pub mod legs;
pub mod lower;
pub mod motor;
pub mod neck;
pub mod opponent;
pub mod plausible;
pub mod world;
