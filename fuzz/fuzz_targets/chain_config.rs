#![no_main]
//! Fuzz target `chain_config`: see `ksmcmc_fuzz::harness::chain_config`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::chain_config(data));
