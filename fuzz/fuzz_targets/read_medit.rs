//! Fuzz target: the .mesh reader, then the map builder, must never panic.
#![no_main]

#[path = "common.rs"]
mod common;

libfuzzer_sys::fuzz_target!(|data: &[u8]| common::read_and_build("mesh", data));
