#![no_main]
//! Fuzz target `scene_json`: see `ksmcmc_fuzz::harness::scene_json`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::scene_json(data));
