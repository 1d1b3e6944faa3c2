#![no_main]
//! Fuzz target `synth_config`: see `ksmcmc_fuzz::harness::synth_config`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::synth_config(data));
