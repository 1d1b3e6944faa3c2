#![no_main]
//! Fuzz target `world_json`: see `ksmcmc_fuzz::harness::world_json`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::world_json(data));
