#![no_main]
//! Fuzz target `ros_yaml`: see `ksmcmc_fuzz::harness::ros_yaml`.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ksmcmc_fuzz::harness::ros_yaml(data));
