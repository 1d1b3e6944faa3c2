//! Fuzz targets for ksmcmc's readers; see `harness` and docs/fuzzing.md.
pub mod harness;
