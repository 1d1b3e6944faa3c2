#![no_main]
//! Fuzz target `db`: see `ksmcmc_fuzz::harness::db`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::db(data));
