#![no_main]
//! Fuzz target `world_arbitrary`: see `ksmcmc_fuzz::harness::world_arbitrary`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::world_arbitrary(data));
