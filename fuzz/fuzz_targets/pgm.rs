#![no_main]
//! Fuzz target `pgm`: see `ksmcmc_fuzz::harness::pgm`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::pgm(data));
