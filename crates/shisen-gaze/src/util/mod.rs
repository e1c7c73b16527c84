//! The bottom layer: small numerical pieces, value checks used while files
//! are read, and RON loading with `file:line:col` errors. Nothing here knows
//! about the virtual human.

pub mod check;
pub mod delay;
pub mod load_error;
pub mod locate;
pub mod math;
pub mod ron;
pub mod schema;
