#![no_main]
//! Fuzz target `png`: see `ksmcmc_fuzz::harness::png`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::png(data));
