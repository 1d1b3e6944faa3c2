#![no_main]
//! Fuzz target `mln`: see `ksmcmc_fuzz::harness::mln`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::mln(data));
