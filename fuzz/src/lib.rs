//! Fuzz targets for ksmcmc's readers; see `harness` and the FUZZING section of the README.
pub mod harness;
