#![no_main]
//! Fuzz target `edits`: see `ksmcmc_fuzz::harness::edits`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::edits(data));
